#pragma once
// swa_sim's UAVs as ArduPilot Copters (vehicle.interface = ardupilot, autopilot_vehicles.h): for each UAV, under
// AP_DDS's topics of the namespace ap/v<i+1>, the simulator publishes imu/experimental/data (its IMU sample's
// attitude as ArduPilot's quaternion, stamped on the vehicle's clock = simulation time) and status (on every change,
// TRANSIENT_LOCAL as ArduPilot sends it), reads cmd_vel, answers the arm_motors and mode_switch services, and lets a
// stand-in (swa/sim/ardupilot_standin.h) decide what the vehicle flies. GNSS goes to the agents on their own topics,
// or with vehicle.gnss_source = autopilot as each vehicle's navsat, forwarded by the bridges.

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <swa/ros/ArdupilotServices.h>
#include <swa/ros/ArdupilotStatus.h>
#include <swa/ros/Imu.h>
#include <swa/ros/NavSatFix.h>
#include <swa/ros/TFMessage.h>
#include <swa/ros/TwistStamped.h>

#include "autopilot_vehicles.h"
#include "swa/dds/participant.h"
#include "swa/dds/sample_queue.h"
#include "swa/sim/ardupilot_standin.h"
#include "swa/sim/scenario.h"

namespace swa::sim_node {

class ArdupilotVehicles : public AutopilotVehicles {
 public:
  // Creates every UAV's ArduPilot endpoints on `participant` (which must outlive this). Throws swa::dds::DdsError.
  ArdupilotVehicles(dds::Participant& participant, int uav_count, const sim::VehicleSetup& setup,
                    agent::ImuSource source);

  void unmatched(int uav, std::vector<std::string>& missing) const override;
  bool publishAttitude(int uav, const agent::ImuSample& s, std::uint32_t seq) override;
  // vehicle.gnss_source = autopilot: a valid sample as ArduPilot's navsat (latitude and longitude around a fixed home);
  // nothing while the scenario's GNSS is lost, as ArduPilot sends nothing while its GPS is unhealthy.
  bool publishGnss(int uav, const agent::GnssSample& g) override;
  void repeatAttitude(int uav) override;
  void drain(std::vector<Answer>& answers, Clock::duration wait, agent::StampNs now, const AdmitFn& admit) override;
  void apply(const Answer& a) override;
  void step(sim::World& world, const EventFn& event) override;
  std::string commandTopic(int uav) const override;

 private:
  struct ArmRequest {
    ardupilot_msgs::srv::ArmMotors_Request request;
    dds::SampleId id;
  };
  struct ModeRequest {
    ardupilot_msgs::srv::ModeSwitch_Request request;
    dds::SampleId id;
  };
  using Input = std::variant<geometry_msgs::msg::TwistStamped, ArmRequest, ModeRequest, tf2_msgs::msg::TFMessage>;
  struct Arrival {
    int uav = 0;
    Input message;
    Clock::time_point received;
    dds::WriterGuid writer{};
  };
  struct Vehicle {
    Vehicle(double guid_timeout_s, const std::optional<sim::ArdupilotEstimatorParams>& ekf)
        : standin(guid_timeout_s, ekf) {}
    sim::ArdupilotStandin standin;
    std::string ns;
    AttitudeStream<sensor_msgs::msg::Imu> imu;  // imu/experimental/data
    dds::Writer<ardupilot_msgs::msg::Status> status;
    dds::Writer<sensor_msgs::msg::NavSatFix> navsat;  // vehicle.gnss_source = autopilot only
    dds::Writer<ardupilot_msgs::srv::ArmMotors_Response> arm_reply;
    dds::Writer<ardupilot_msgs::srv::ModeSwitch_Response> mode_reply;
    dds::Reader<geometry_msgs::msg::TwistStamped> cmd_vel;
    dds::Reader<tf2_msgs::msg::TFMessage> tf;  // ap/tf: the bridge's external odometry
    dds::Reader<ardupilot_msgs::srv::ArmMotors_Request> arm_request;
    dds::Reader<ardupilot_msgs::srv::ModeSwitch_Request> mode_request;
    double yaw_rate_radps = 0.0;  // of the newest cmd_vel given to the stand-in
    bool status_sent = false, status_armed = false, status_ekf_failsafe = false;
    std::uint8_t status_mode = 0;
  };

  void publishStatus(Vehicle& v, agent::StampNs now);

  dds::SampleQueue<Arrival> queue_;  // declared before the vehicles' readers are made, outlives their listeners' use
  std::vector<Vehicle> vehicles_;
  std::vector<Arrival> arrived_;
};

}  // namespace swa::sim_node
