# Sourced by make-credentials.sh (its DOMAIN_MIN/MAX, naming and topic globals): the XML documents it signs, the
# governance of the domains and each participant's permissions, with the topics of its role.
domains_xml() {
  local indent=$1
  printf '%s<domains>\n%s  <id_range>\n%s    <min>%d</min>\n%s    <max>%d</max>\n%s  </id_range>\n%s</domains>\n' \
    "$indent" "$indent" "$indent" "$DOMAIN_MIN" "$indent" "$DOMAIN_MAX" "$indent" "$indent"
}

# Element order matters: Fast DDS's parser expects the schema's sequence exactly.
governance_xml() {
  cat <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<!-- SWA domain governance, made by deploy/security/make-credentials.sh. Signed copy: governance.p7s. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
$(domains_xml '      ')
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <!-- NONE: every topic's payload and submessages are already encrypted below, discovery and liveliness
           above; protecting whole RTPS messages too would encrypt every control-loop message twice. -->
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF
}

topics_xml() {
  local kind=$1 t
  shift
  (($#)) || return 0
  echo "        <$kind>"
  echo "          <topics>"
  for t in "$@"; do echo "            <topic>$t</topic>"; done
  echo "          </topics>"
  echo "        </$kind>"
}

# The topics of each role, from idl/runtime/dds/include/swa/dds/topics.h and the nodes (sim/node, agent/node,
# agent/bridge_node, monitor/node). fnmatch patterns: uav* stands for every UAV index, $PX4_PREFIX* for every vehicle.
px4_out() {
  echo "rt/$1/fmu/out/vehicle_attitude rt/$1/fmu/out/sensor_combined rt/$1/fmu/out/vehicle_status" \
       "rt/$1/fmu/out/vehicle_status_v1" \
       "rt/$1/fmu/out/vehicle_command_ack rt/$1/fmu/out/vehicle_gps_position rt/$1/fmu/out/vehicle_local_position" \
       "rt/$1/fmu/out/vehicle_local_position_v1"
}
px4_in() {
  echo "rt/$1/fmu/in/trajectory_setpoint rt/$1/fmu/in/offboard_control_mode rt/$1/fmu/in/vehicle_command" \
       "rt/$1/fmu/in/vehicle_visual_odometry"
}
# ArduPilot (AP_DDS): UAV I's vehicle is ap/v<I+1> (DDS_USE_NS 1, MAV_SYSID I+1); its services' requests and replies
# are topics of their own (rq/, rr/).
ap_out() {
  echo "rt/$1/imu/experimental/data rt/$1/status rt/$1/navsat rr/$1/arm_motorsReply rr/$1/mode_switchReply"
}
ap_in() { echo "rt/$1/cmd_vel rt/$1/tf rq/$1/arm_motorsRequest rq/$1/mode_switchRequest"; }
# Detections as real detectors publish them (agent sensor.input vision_msgs / uvdar), ROS names already.
detector_topics() { echo "rt/uav$1/detections rt/uav$1/uvdar/measuredPoses"; }

publishes() {
  local r=$SWA_ROOT
  case $1 in
    swa_sim)
      echo "${r}uav*/imu ${r}uav*/detections ${r}uav*/gnss ${r}uav*/sensors ${r}truth ${r}events ${r}clock" \
        "$(px4_out "$PX4_PREFIX*")" \
        "$(detector_topics '*') $(ap_out 'ap/v*')"
      ;;
    swa_monitor) echo '' ;;
    # The ground station (swa_mission): the swarm's mission, and nothing else.
    swa_ground) echo "${r}swarm/mission" ;;
    swa_agent_*)
      local i=${1#swa_agent_}
      echo "${r}uav$i/cmd_vel ${r}uav$i/state$([[ $NAMING == ros2 ]] && echo " ${r}uav$i/cmd_vel_stamped")"
      ;;
    swa_bridge_*)
      local i=${1#swa_bridge_}
      echo "${r}uav$i/imu ${r}uav$i/detections ${r}uav$i/gnss ${r}uav$i/bridge_state $(px4_in "$PX4_PREFIX$i")" \
        "$(ap_in "ap/v$((i + 1))")"
      ;;
  esac
}

subscribes() {
  local r=$SWA_ROOT
  case $1 in
    swa_sim) echo "${r}uav*/cmd_vel $(px4_in "$PX4_PREFIX*") $(ap_in 'ap/v*')" ;;
    # The monitor reads every topic of the run: the UAVs' inputs and commands only to record them (--record).
    swa_monitor)
      echo "${r}truth ${r}events ${r}clock ${r}uav*/state ${r}uav*/imu ${r}uav*/detections ${r}uav*/gnss" \
        "${r}uav*/sensors ${r}uav*/cmd_vel ${r}uav*/bridge_state ${r}swarm/mission"
      ;;
    swa_agent_*)
      local i=${1#swa_agent_}
      # and the ground's mission (issue #45), which no agent may write
      echo "${r}uav$i/imu ${r}uav$i/detections ${r}uav$i/gnss ${r}uav$i/sensors ${r}clock ${r}swarm/mission" \
        "$(detector_topics "$i")"
      ;;
    swa_bridge_*)
      local i=${1#swa_bridge_}
      # its own agent's state: the estimate it feeds its autopilot as external odometry (issue #43)
      echo "${r}uav$i/cmd_vel ${r}uav$i/state $(px4_out "$PX4_PREFIX$i") $(ap_out "ap/v$((i + 1))")"
      ;;
  esac
}

permissions_xml() {
  local name=$1 subject=$2 not_before=$3 not_after=$4
  local -a pub sub
  read -r -a pub <<<"$(publishes "$name")"
  read -r -a sub <<<"$(subscribes "$name")"
  cat <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<!-- Permissions of $name, made by deploy/security/make-credentials.sh. Signed copy: permissions.p7s. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$name">
      <subject_name>$subject</subject_name>
      <validity>
        <not_before>$not_before</not_before>
        <not_after>$not_after</not_after>
      </validity>
      <allow_rule>
$(domains_xml '        ')
$(topics_xml publish "${pub[@]+"${pub[@]}"}"; topics_xml subscribe "${sub[@]+"${sub[@]}"}")
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
EOF
}
