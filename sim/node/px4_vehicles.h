#pragma once
// swa_sim's UAVs as PX4 autopilots (vehicle.interface = px4) of one release (vehicle.px4_release): for each UAV, under
// PX4's topics of the namespace px4_<i>, the simulator publishes vehicle_attitude (its IMU sample as PX4's quaternion,
// stamped on the vehicle's clock = simulation time) and vehicle_status (the release's layout and topic name), reads
// trajectory_setpoint, offboard_control_mode and vehicle_command with PX4's QoS, and lets a stand-in
// (swa/sim/px4_standin.h) decide what the vehicle flies. The agents are reached through one swa_px4_bridge each;
// detections go to the agents on their own topics, GNSS too unless vehicle.gnss_source = autopilot (then
// vehicle_gps_position and vehicle_local_position, forwarded by the bridges). The first trajectory_setpoint stamped
// with a recent attitude sample's timestamp is that sample's answer: it goes to the drivers' lockstep / realtime rules
// like an agent's cmd_vel (answer.h). The bridge's own setpoints (zero velocity for a stale agent, stamped like the
// last answer), heartbeats and commands go to the stand-in at once. vehicle_local_position carries its global reference
// as PX4's does (xy_global, ref_timestamp, ref_lat, ref_lon): a fixed airfield at the world's origin, set with the
// first report; vehicle.px4_origin_shift_at_s moves it once, mid- flight, and re-bases x, y on it as EKF2 does when its
// global origin is re-set (issue #46).

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <swa/px4/OffboardControlMode_v1_15.h>
#include <swa/px4/SensorCombined_v1_15.h>
#include <swa/px4/SensorGps_v1_15.h>
#include <swa/px4/SensorGps_v1_17.h>
#include <swa/px4/TrajectorySetpoint_v1_15.h>
#include <swa/px4/VehicleAttitude_v1_15.h>
#include <swa/px4/VehicleCommandAck_v1_15.h>
#include <swa/px4/VehicleCommand_v1_15.h>
#include <swa/px4/VehicleLocalPosition_v1_15.h>
#include <swa/px4/VehicleLocalPosition_v1_16.h>
#include <swa/px4/VehicleOdometry_v1_15.h>
#include <swa/px4/VehicleStatus_v1_15.h>
#include <swa/px4/VehicleStatus_v1_16.h>

#include "answer.h"
#include "autopilot_vehicles.h"
#include "swa/dds/participant.h"
#include "swa/dds/sample_queue.h"
#include "swa/px4/map_projection.h"
#include "swa/sim/px4_standin.h"
#include "swa/sim/world.h"
#include "swa/wire/px4.h"

namespace swa::sim_node {

class Px4Vehicles : public AutopilotVehicles {
 public:
  // Creates every UAV's PX4 endpoints on `participant` (which must outlive this). Throws swa::dds::DdsError.
  // `source`: what the agents fuse, which decides the attitude vehicle_attitude reports (AttitudeStream).
  Px4Vehicles(dds::Participant& participant, int uav_count, const sim::VehicleSetup& setup, agent::ImuSource source);

  // UAV `uav`'s PX4 endpoints the bridge has not matched yet, appended to `missing`.
  void unmatched(int uav, std::vector<std::string>& missing) const override;

  // UAV `uav`'s IMU sample as PX4's sensor_combined (its accelerometer) and vehicle_attitude. False if the middleware
  // refused either.
  bool publishAttitude(int uav, const agent::ImuSample& s, std::uint32_t seq) override;
  // UAV `uav`'s GNSS sample as its PX4 reports it (vehicle.gnss_source = autopilot): vehicle_gps_position and
  // vehicle_local_position. False if the middleware refused either (or the source is not the autopilot).
  bool publishGnss(int uav, const agent::GnssSample& g) override;
  // The newest vehicle_attitude of `uav` once more. PX4 streams its attitude whatever happens; in lockstep the
  // simulated time stands still while the simulator waits for an answer, so the stand-in repeats the sample: a
  // best-effort sample lost on the way (or sent before the bridge's reader matched) would otherwise stall the run.
  void repeatAttitude(int uav) override;

  // Waits up to `wait` for what the bridges sent, at simulation time `now`: answers are appended to `answers`; the
  // rest goes to the stand-ins (the bridges' own setpoints only if `admit`).
  void drain(std::vector<Answer>& answers, Clock::duration wait, agent::StampNs now, const AdmitFn& admit) override;
  // An answer the driver applies: the vehicle's newest setpoint.
  void apply(const Answer& a) override;
  // Before the world steps from `now`: each vehicle's decision commanded to the world, vehicle_status when it changed
  // (and at 5 Hz), the stand-ins' events.
  void step(sim::World& world, const EventFn& event) override;

  std::string commandTopic(int uav) const override;

 private:
  using Input = std::variant<px4_msgs::msg::TrajectorySetpoint, px4_msgs::msg::OffboardControlMode,
                             px4_msgs::msg::VehicleCommand, px4_msgs::msg::VehicleOdometry>;
  struct Arrival {
    int uav = 0;
    Input message;
    Clock::time_point received;
    dds::WriterGuid writer{};
  };
  struct Vehicle {
    Vehicle(double com_of_loss_t_s, const std::optional<sim::Px4EstimatorParams>& ekf)
        : standin(com_of_loss_t_s, ekf) {}
    sim::Px4Standin standin;
    AttitudeStream<px4_msgs::msg::VehicleAttitude> attitude;
    dds::Writer<px4_msgs::msg::SensorCombined> accelerometer;           // sensor_combined
    dds::Writer<px4_msgs::msg::VehicleStatus> status;                   // v1.15
    dds::Writer<px4_v1_16::px4_msgs::msg::VehicleStatus> status_v1_16;  // v1.16 and later
    // vehicle.gnss_source = autopilot only, in the release's layouts.
    dds::Writer<px4_msgs::msg::SensorGps> gps;                                   // v1.15, v1.16
    dds::Writer<px4_v1_17::px4_msgs::msg::SensorGps> gps_v1_17;                  // v1.17
    dds::Writer<px4_msgs::msg::VehicleLocalPosition> position;                   // v1.15
    dds::Writer<px4_v1_16::px4_msgs::msg::VehicleLocalPosition> position_v1_16;  // v1.16, v1.17
    dds::Writer<px4_msgs::msg::VehicleCommandAck> ack;
    dds::Reader<px4_msgs::msg::TrajectorySetpoint> setpoint;
    dds::Reader<px4_msgs::msg::OffboardControlMode> mode;
    dds::Reader<px4_msgs::msg::VehicleCommand> command;
    dds::Reader<px4_msgs::msg::VehicleOdometry> odometry;  // vehicle_visual_odometry: the bridge's external vision
    std::string ns;
    double yaw_rate_radps = 0.0;  // of the newest setpoint given to the stand-in (which knows only the velocity)
    std::uint8_t status_sent_nav = 255, status_sent_arming = 255;
    agent::StampNs status_sent_at = 0;
    // vehicle_local_position's global reference, from the first report on; the projection around it once moved.
    std::optional<wire::LocalReference> reference;
    std::optional<px4::MapProjection> moved;
  };
  // vehicle.px4_origin_shift_*: when (nullopt: never) and where to [m], in the old origin's NED frame.
  struct OriginShift {
    std::optional<agent::StampNs> at;
    px4::NedPoint by;
  };

  void publishStatus(int uav, Vehicle& v, agent::StampNs now);
  // The reference of vehicle `uav`'s report at `now` (`timestamp_us` on its clock): set by the first, moved once.
  const wire::LocalReference& referenceAt(int uav, Vehicle& v, agent::StampNs now, std::uint64_t timestamp_us);
  // `g` (the world's east, north) in the vehicle's local frame around its reference.
  agent::GnssSample inLocalFrame(const Vehicle& v, agent::GnssSample g) const;

  dds::SampleQueue<Arrival> queue_;  // declared before the vehicles' readers are made, outlives their listeners' use
  std::vector<Vehicle> vehicles_;
  std::vector<Arrival> arrived_;
  std::uint64_t acks_ = 0;
  OriginShift shift_;
};

}  // namespace swa::sim_node
