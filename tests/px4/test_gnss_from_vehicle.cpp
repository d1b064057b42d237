// GNSS loss signalled by the vehicle, end to end without DDS timing: the simulator's GNSS samples as each release's
// PX4 stand-in reports them (vehicle_gps_position, vehicle_local_position), serialised and read back in the release's
// layout, through the bridge's GnssForward into an anchored agent. The agent must stop using GNSS at the first report
// after the scenario drops it, and use it again at the first report after the regain: its GNSS state is the
// vehicle's at every report, so the switch happens in the IMU period the report arrives in.
// ArduPilot signals no loss (issue #42: the owner accepted "within --gnss-silence-s"): its stand-in sends no
// NavSatFix while GNSS is lost, and the agent must switch within --gnss-silence-s of the last fix on the IMU's clock.

#include <gtest/gtest.h>

#include <optional>

#include <swa/px4/SensorGps_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_17PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_16PubSubTypes.h>

#include "swa/agent/agent.h"
#include "swa/autopilot/navsat.h"
#include "swa/px4/gnss.h"
#include "swa/px4/map_projection.h"
#include "swa/px4/release.h"
#include "swa/sim/scenario_io.h"
#include "swa/sim/timing.h"
#include "swa/sim/world.h"
#include "swa/wire/ardupilot.h"
#include "swa/wire/px4.h"

namespace swa::px4::gnss_vehicle_test {
namespace {

// A message through the wire and back: what the bridge reads is what the stand-in wrote, in the release's bytes.
template <class PubSubType>
typename PubSubType::type roundTrip(typename PubSubType::type m) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  EXPECT_TRUE(type.serialize(&m, &p));
  typename PubSubType::type back;
  EXPECT_TRUE(type.deserialize(&p, &back));
  return back;
}

// The stand-in's two reports of `g` in release `r`, read by the bridge.
std::optional<agent::GnssSample> throughVehicle(Release r, const agent::GnssSample& g, GnssForward& forward) {
  const std::uint64_t t = *timestampUsOf(g.stamp_ns);
  if (hasV117SensorGps(r)) {
    forward.onGps(wire::gpsReportOf(roundTrip<px4_v1_17::px4_msgs::msg::SensorGpsPubSubType>(
        wire::sensorGps<px4_v1_17::px4_msgs::msg::SensorGps>(t, g))));
  } else {
    forward.onGps(wire::gpsReportOf(
        roundTrip<px4_msgs::msg::SensorGpsPubSubType>(wire::sensorGps<px4_msgs::msg::SensorGps>(t, g))));
  }
  if (hasV116VehicleLocalPosition(r)) {
    return forward.onLocalPosition(
        wire::localPositionOf(roundTrip<px4_v1_16::px4_msgs::msg::VehicleLocalPositionPubSubType>(
            wire::vehicleLocalPosition<px4_v1_16::px4_msgs::msg::VehicleLocalPosition>(t, g))));
  }
  return forward.onLocalPosition(wire::localPositionOf(roundTrip<px4_msgs::msg::VehicleLocalPositionPubSubType>(
      wire::vehicleLocalPosition<px4_msgs::msg::VehicleLocalPosition>(t, g))));
}

// vehicle_local_position's reference in the release's layout, written by the stand-in and read by the bridge.
LocalPositionReport referenceThroughWire(Release r, const std::optional<wire::LocalReference>& reference) {
  agent::GnssSample g;
  g.valid = true;
  g.position_m = agent::Vec2(-500.25, 12.5);
  g.std_m = 0.5;
  if (hasV116VehicleLocalPosition(r)) {
    return wire::localPositionOf(roundTrip<px4_v1_16::px4_msgs::msg::VehicleLocalPositionPubSubType>(
        wire::vehicleLocalPosition<px4_v1_16::px4_msgs::msg::VehicleLocalPosition>(7, g, true, false, reference)));
  }
  return wire::localPositionOf(roundTrip<px4_msgs::msg::VehicleLocalPositionPubSubType>(
      wire::vehicleLocalPosition<px4_msgs::msg::VehicleLocalPosition>(7, g, true, false, reference)));
}

TEST(GnssFromVehicle, TheLocalOriginsReferenceCrossesTheWireInEveryRelease) {
  for (const Release r : kReleases) {
    SCOPED_TRACE(releaseName(r));
    // GIVEN a local position relative to an origin PX4 set at 12.5 s
    const wire::LocalReference reference{12'500'000, GeoPoint{47.397742123456789, 8.545594987654321}};
    // WHEN it goes through the wire in the release's layout
    const LocalPositionReport p = referenceThroughWire(r, reference);
    // THEN the bridge reads the reference bit for bit (float64 on the wire), beside x, y
    EXPECT_TRUE(p.xy_global);
    EXPECT_EQ(p.ref_timestamp_us, 12'500'000u);
    EXPECT_EQ(p.ref_lat_deg, reference.point.lat_deg);
    EXPECT_EQ(p.ref_lon_deg, reference.point.lon_deg);
    EXPECT_EQ(p.x_m, 12.5);
    EXPECT_EQ(p.y_m, -500.25);
    // AND without one it says so
    EXPECT_FALSE(referenceThroughWire(r, std::nullopt).xy_global);
  }
}

TEST(GnssFromVehicle, AnAnchoredAgentFollowsTheVehiclesGnssStateAtEveryReportInEveryRelease) {
  for (const Release r : kReleases) {
    SCOPED_TRACE(releaseName(r));
    // GIVEN 4 UAVs that lose GNSS at 3 s and regain it at 6 s, GNSS at 10 Hz, hovering, one anchored agent on UAV 1
    const sim::Scenario s =
        sim::loadScenario(std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml",
                          {"duration_s=9", "gnss.dropout_start_s=3", "gnss.dropout_end_s=6", "agent.mode=anchored"});
    sim::World world(s);
    agent::Agent agent(s.agent);
    GnssForward forward;
    int reports = 0, lost_reports = 0, mismatches = 0;
    std::optional<double> switched_off_s, switched_on_s;
    while (!world.finished()) {
      const sim::UavSensors& in = world.sensors()[1];
      if (in.imu) agent.onImu(*in.imu);
      if (in.gnss) {
        // WHEN the stand-in reports the sample and the bridge forwards what it makes of it
        const bool was = agent.diagnostics().gnss_valid;
        if (const std::optional<agent::GnssSample> g = throughVehicle(r, *in.gnss, forward)) agent.onGnss(*g);
        ++reports;
        lost_reports += in.gnss->valid ? 0 : 1;
        // THEN at once the agent's GNSS state is the vehicle's
        if (agent.diagnostics().gnss_valid != in.gnss->valid) ++mismatches;
        const double t = sim::stampSeconds(in.gnss->stamp_ns);
        if (was && !in.gnss->valid && !switched_off_s) switched_off_s = t;
        if (!was && in.gnss->valid && switched_off_s && !switched_on_s) switched_on_s = t;
      }
      world.step();
    }
    EXPECT_EQ(mismatches, 0) << "of " << reports << " reports";
    EXPECT_EQ(lost_reports, 30);  // 3 s at 10 Hz
    ASSERT_TRUE(switched_off_s && switched_on_s);
    EXPECT_NEAR(*switched_off_s, 3.0, 1e-9);  // the first report at the loss, not a rate-limited later one
    EXPECT_NEAR(*switched_on_s, 6.0, 1e-9);
    EXPECT_EQ(forward.counters().forwarded + forward.counters().invalid_forwarded, static_cast<std::uint64_t>(reports));
  }
}

TEST(GnssFromVehicle, AnAnchoredAgentOnArdupilotSwitchesWithinTheSilenceOfTheLastFixAndBackAtTheFirstFix) {
  for (const double silence_s : {0.5, 0.25, 1.2}) {
    SCOPED_TRACE(silence_s);
    // GIVEN 4 UAVs that lose GNSS at 3 s and regain it at 6 s, GNSS at 10 Hz, IMU at 100 Hz, an anchored agent on
    // UAV 1 and the bridge's NavSatForward with --gnss-silence-s = silence_s
    const sim::Scenario s =
        sim::loadScenario(std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml",
                          {"duration_s=9", "gnss.dropout_start_s=3", "gnss.dropout_end_s=6", "agent.mode=anchored"});
    sim::World world(s);
    agent::Agent agent(s.agent);
    ardupilot::NavSatForward navsat(ardupilot::NavSatForwardConfig{silence_s, 2.5});
    const ardupilot::LocalTangent home{47.397742, 8.545594};
    std::optional<double> last_fix_s, switched_off_s, switched_on_s;
    while (!world.finished()) {
      const sim::UavSensors& in = world.sensors()[1];
      const bool was = agent.diagnostics().gnss_valid;
      // WHEN the IMU sample arrives, the bridge reads the vehicle's time off it (loss by silence), and a NavSatFix
      // arrives only while the stand-in has a fix, through the wire as ArduPilot's message
      if (in.imu) {
        agent.onImu(*in.imu);
        if (const auto g = navsat.onVehicleTime(*timestampUsOf(in.imu->stamp_ns))) agent.onGnss(*g);
      }
      if (in.gnss && in.gnss->valid) {
        double lat = 0.0, lon = 0.0;
        home.latLonOf(in.gnss->position_m, lat, lon);
        const sensor_msgs::msg::NavSatFix m =
            wire::navSatFix(*timestampUsOf(in.gnss->stamp_ns), lat, lon, in.gnss->std_m);
        if (const auto g = navsat.onNavSat(wire::navSatReportOf(m))) agent.onGnss(*g);
        if (!switched_off_s) last_fix_s = sim::stampSeconds(in.gnss->stamp_ns);
      }
      if (in.imu) {  // every step (100 Hz): the instant of this step's samples
        const double t = sim::stampSeconds(in.imu->stamp_ns);
        if (was && !agent.diagnostics().gnss_valid && !switched_off_s) switched_off_s = t;
        if (!was && agent.diagnostics().gnss_valid && switched_off_s && !switched_on_s) switched_on_s = t;
      }
      world.step();
    }
    // THEN the agent stopped using GNSS silence_s after the last fix (2.9 s) on the IMU's clock, not later
    ASSERT_TRUE(last_fix_s && switched_off_s && switched_on_s);
    EXPECT_NEAR(*last_fix_s, 2.9, 1e-9);
    EXPECT_GT(*switched_off_s, *last_fix_s);
    EXPECT_LE(*switched_off_s - *last_fix_s, silence_s + 1e-9);
    // AND used it again at the first fix after the regain
    EXPECT_NEAR(*switched_on_s, 6.0, 1e-9);
  }
}

}  // namespace
}  // namespace swa::px4::gnss_vehicle_test
