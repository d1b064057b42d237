#!/usr/bin/env bash
# ctest (label security): deploy/security/make-credentials.sh from the outside, without DDS. What a participant
# will check is checked here with openssl (chains, S/MIME signatures, subject names in RFC 2253 order), plus
# the permissions each role gets, private key modes, argument errors, and the overwrite rules (refuse, --reuse-ca,
# --force, a failed run leaves the directory as it was). Each case works in its own temporary directory.
set -euo pipefail

readonly PROG=${0##*/}

usage() {
  cat <<EOF
$PROG: tests deploy/security/make-credentials.sh (no DDS involved).

Usage: $PROG SCRIPT     SCRIPT = path of make-credentials.sh

Prints one line per failed check and a summary; exit 0 when every check passed, 1 otherwise, 2 bad arguments.
EOF
}

FAILURES=0 CHECKS=0 SCRIPT='' WORK=''

fail() {
  echo "FAIL: $*" >&2
  FAILURES=$((FAILURES + 1))
}

# check DESCRIPTION COMMAND...: the command must succeed (its output is shown only if it does not).
check() {
  local what=$1
  shift
  CHECKS=$((CHECKS + 1))
  if ! "$@" >"$WORK/check.out" 2>&1; then
    fail "$what"
    sed 's/^/    /' "$WORK/check.out" >&2
  fi
}

# expect_status STATUS DESCRIPTION COMMAND...: the command must exit with STATUS (its output goes to $WORK/out).
expect_status() {
  local want=$1 what=$2 got=0
  shift 2
  CHECKS=$((CHECKS + 1))
  "$@" >"$WORK/out" 2>&1 || got=$?
  if ((got != want)); then
    fail "$what: exit $got, expected $want; output:"
    sed 's/^/    /' "$WORK/out" >&2
  fi
}

output_has() { grep -qF -- "$1" "$WORK/out"; }

mode_of() { stat -c %a "$1"; }

# Checksums of every file under $1 (names relative to it), to compare a directory before and after.
tree_sum() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum); }

rfc2253_subject() {
  local s
  s=$(openssl x509 -in "$1" -noout -subject -nameopt RFC2253)
  echo "${s#subject=}"
}

# The <topic> entries of one action (publish / subscribe) of a permissions XML, sorted, space separated.
granted() {
  local xml=$1 action=$2
  sed -n "/<$action>/,/<\/$action>/p" "$xml" | sed -n 's:.*<topic>\(.*\)</topic>.*:\1:p' | sort | tr '\n' ' '
}

sorted() { printf '%s\n' "$@" | sort | tr '\n' ' '; }

test_arguments() {
  expect_status 0 "--help" bash "$SCRIPT" --help
  check "--help describes the layout" output_has "ca/key.pem"
  expect_status 2 "no arguments" bash "$SCRIPT"
  expect_status 2 "N = 0" bash "$SCRIPT" "$WORK/a" 0
  expect_status 2 "N not a number" bash "$SCRIPT" "$WORK/a" four
  expect_status 2 "domain beyond 232" bash "$SCRIPT" --domains 5-300 "$WORK/a" 2
  expect_status 2 "reversed domain range" bash "$SCRIPT" --domains 9-3 "$WORK/a" 2
  expect_status 2 "unknown option" bash "$SCRIPT" --bogus "$WORK/a" 2
  check "the option is named" output_has "--bogus"
  expect_status 2 "--org with a comma" bash "$SCRIPT" --org "A,B" "$WORK/a" 2
  expect_status 2 "--force with --reuse-ca" bash "$SCRIPT" --force --reuse-ca "$WORK/a" 2
  check "bad arguments create nothing" test ! -e "$WORK/a"
}

test_layout_and_documents() {
  local d=$WORK/creds name cert
  expect_status 0 "create 3 UAVs" bash "$SCRIPT" "$d" 3
  for name in swa_sim swa_monitor swa_agent_0 swa_agent_1 swa_agent_2; do
    for f in cert.pem key.pem permissions.p7s permissions.xml; do
      check "$name/$f exists" test -s "$d/$name/$f"
    done
    check "$name/key.pem is 0600" test "$(mode_of "$d/$name/key.pem")" = 600
    cert=$d/$name/cert.pem
    check "$name: certificate issued by ca.pem (strict)" \
      openssl verify -x509_strict -CAfile "$d/ca.pem" "$cert"
    check "$name: EC prime256v1 key" bash -c "openssl x509 -in '$cert' -noout -text | grep -q prime256v1"
    check "$name: CN is the participant name" test "$(rfc2253_subject "$cert")" = "CN=$name,O=SWA"
    check "$name: permissions signed by ca.pem" \
      openssl smime -verify -text -in "$d/$name/permissions.p7s" -CAfile "$d/ca.pem" -out /dev/null
    check "$name: <subject_name> is the RFC 2253 subject" \
      grep -qF "<subject_name>$(rfc2253_subject "$cert")</subject_name>" "$d/$name/permissions.xml"
    # S/MIME text is signed in canonical form (CRLF line ends).
    check "$name: signed text is the XML" \
      bash -c "openssl smime -verify -text -in '$d/$name/permissions.p7s' -CAfile '$d/ca.pem' 2>/dev/null |
               tr -d '\r' | diff - '$d/$name/permissions.xml'"
    check "$name: default DENY" grep -q "<default>DENY</default>" "$d/$name/permissions.xml"
  done
  check "swa_agent_3 not created" test ! -e "$d/swa_agent_3"
  check "ca/key.pem is 0600" test "$(mode_of "$d/ca/key.pem")" = 600
  check "no staging left" bash -c "! ls -A '$d' | grep -q staging"
  check "governance signed by ca.pem" \
    openssl smime -verify -text -in "$d/governance.p7s" -CAfile "$d/ca.pem" -out /dev/null
  local g=$d/governance.xml
  check "authenticated join" grep -q "<allow_unauthenticated_participants>false<" "$g"
  check "join access control" grep -q "<enable_join_access_control>true<" "$g"
  check "data encrypted" grep -q "<data_protection_kind>ENCRYPT<" "$g"
  check "metadata encrypted" grep -q "<metadata_protection_kind>ENCRYPT<" "$g"
  check "read access control" grep -q "<enable_read_access_control>true<" "$g"
  check "write access control" grep -q "<enable_write_access_control>true<" "$g"
  check "domains 0..232" bash -c "grep -q '<min>0</min>' '$g' && grep -q '<max>232</max>' '$g'"

  check "agent 1 publishes only its cmd_vel and state" test "$(granted "$d/swa_agent_1/permissions.xml" publish)" = \
    "$(sorted swa/uav1/cmd_vel swa/uav1/state)"
  check "agent 1 subscribes only its sensors, the clock and the ground's mission" \
    test "$(granted "$d/swa_agent_1/permissions.xml" subscribe)" = \
    "$(sorted swa/uav1/imu swa/uav1/detections swa/uav1/gnss swa/uav1/sensors swa/clock swa/swarm/mission \
      rt/uav1/detections rt/uav1/uvdar/measuredPoses)"
  check "the ground publishes only the mission" test "$(granted "$d/swa_ground/permissions.xml" publish)" = \
    "$(sorted swa/swarm/mission)"
  check "the ground subscribes nothing" test -z "$(granted "$d/swa_ground/permissions.xml" subscribe)"
  check "sim publishes sensors, truth, events, clock, and the outputs of every UAV's PX4 and ArduPilot" \
    test "$(granted "$d/swa_sim/permissions.xml" publish)" = \
    "$(sorted 'swa/uav*/imu' 'swa/uav*/detections' 'swa/uav*/gnss' 'swa/uav*/sensors' swa/truth swa/events swa/clock \
      'rt/uav*/detections' 'rt/uav*/uvdar/measuredPoses' 'rt/px4_*/fmu/out/vehicle_attitude' \
      'rt/px4_*/fmu/out/sensor_combined' 'rt/px4_*/fmu/out/vehicle_status' 'rt/px4_*/fmu/out/vehicle_status_v1' \
      'rt/px4_*/fmu/out/vehicle_command_ack' 'rt/px4_*/fmu/out/vehicle_gps_position' \
      'rt/px4_*/fmu/out/vehicle_local_position' 'rt/px4_*/fmu/out/vehicle_local_position_v1' \
      'rt/ap/v*/imu/experimental/data' 'rt/ap/v*/status' 'rt/ap/v*/navsat' 'rr/ap/v*/arm_motorsReply' \
      'rr/ap/v*/mode_switchReply')"
  check "sim subscribes commands and the inputs of PX4 and ArduPilot only" \
    test "$(granted "$d/swa_sim/permissions.xml" subscribe)" = \
    "$(sorted 'swa/uav*/cmd_vel' 'rt/px4_*/fmu/in/trajectory_setpoint' 'rt/px4_*/fmu/in/offboard_control_mode' \
      'rt/px4_*/fmu/in/vehicle_command' 'rt/px4_*/fmu/in/vehicle_visual_odometry' 'rt/ap/v*/cmd_vel' 'rt/ap/v*/tf' \
      'rq/ap/v*/arm_motorsRequest' 'rq/ap/v*/mode_switchRequest')"
  check "monitor publishes nothing" test -z "$(granted "$d/swa_monitor/permissions.xml" publish)"
  check "monitor subscribes every topic (to record it)" \
    test "$(granted "$d/swa_monitor/permissions.xml" subscribe)" = "$(sorted swa/truth swa/events swa/clock \
    'swa/uav*/state' 'swa/uav*/imu' 'swa/uav*/detections' 'swa/uav*/gnss' 'swa/uav*/sensors' 'swa/uav*/cmd_vel' \
    'swa/uav*/bridge_state' swa/swarm/mission)"
}

test_overwrite_rules() {
  local d=$WORK/rot before
  bash "$SCRIPT" "$d" 3 >/dev/null
  before=$(tree_sum "$d")
  expect_status 1 "second run without a flag refuses" bash "$SCRIPT" "$d" 3
  check "refusal names the way out" output_has "--reuse-ca"
  check "refusal changed nothing" test "$(tree_sum "$d")" = "$before"

  local ca_before cert_before
  ca_before=$(sha256sum <"$d/ca.pem") cert_before=$(sha256sum <"$d/swa_agent_0/cert.pem")
  expect_status 0 "--reuse-ca with fewer UAVs" bash "$SCRIPT" --reuse-ca "$d" 2
  check "--reuse-ca keeps the CA" test "$(sha256sum <"$d/ca.pem")" = "$ca_before"
  check "--reuse-ca issues new identities" test "$(sha256sum <"$d/swa_agent_0/cert.pem")" != "$cert_before"
  check "--reuse-ca: identities verify against the kept CA" \
    openssl verify -x509_strict -CAfile "$d/ca.pem" "$d/swa_agent_1/cert.pem"
  check "--reuse-ca removes agents beyond N" test ! -e "$d/swa_agent_2"

  echo keep >"$d/notes.txt"
  expect_status 0 "--force" bash "$SCRIPT" --force "$d" 2
  check "--force makes a new CA" test "$(sha256sum <"$d/ca.pem")" != "$ca_before"
  check "--force leaves other files alone" test "$(cat "$d/notes.txt")" = keep

  # A failure half-way (openssl refusing to sign) must leave the directory exactly as it was.
  local fake=$WORK/fakebin real
  real=$(command -v openssl)
  mkdir -p "$fake"
  # shellcheck disable=SC2016  # $1, $2, $@ belong to the fake openssl
  printf '#!/bin/sh\n[ "$1" = smime ] && [ "$2" = -sign ] && exit 1\nexec %s "$@"\n' "$real" >"$fake/openssl"
  chmod +x "$fake/openssl"
  before=$(tree_sum "$d")
  expect_status 1 "--force with a failing openssl" env PATH="$fake:$PATH" bash "$SCRIPT" --force "$d" 2
  check "a failed run changes nothing" test "$(tree_sum "$d")" = "$before"
  check "a failed run leaves no staging" bash -c "! ls -A '$d' | grep -q staging"
  expect_status 1 "a failed run into a new directory" env PATH="$fake:$PATH" bash "$SCRIPT" "$WORK/new" 2
  check "... leaves no directory behind" test ! -e "$WORK/new"

  mkdir -p "$WORK/foreign" && echo x >"$WORK/foreign/file"
  expect_status 1 "a non-empty directory without credentials" bash "$SCRIPT" "$WORK/foreign" 2
  check "... is left alone" test "$(ls -A "$WORK/foreign")" = file
}

test_bridges_and_naming() {
  local d=$WORK/bridges
  expect_status 0 "--bridges --px4-prefix drone_" bash "$SCRIPT" --bridges --px4-prefix drone_ "$d" 2
  check "bridge 1 publishes UAV 1's sensors, its diagnostics and its own vehicle's inputs, odometry included" \
    test "$(granted "$d/swa_bridge_1/permissions.xml" publish)" = \
    "$(sorted swa/uav1/imu swa/uav1/detections swa/uav1/gnss swa/uav1/bridge_state \
      rt/drone_1/fmu/in/trajectory_setpoint rt/drone_1/fmu/in/offboard_control_mode rt/drone_1/fmu/in/vehicle_command \
      rt/drone_1/fmu/in/vehicle_visual_odometry rt/ap/v2/cmd_vel rt/ap/v2/tf rq/ap/v2/arm_motorsRequest \
      rq/ap/v2/mode_switchRequest)"
  check "bridge 1 subscribes UAV 1's commands, its agent's state and its own vehicle's outputs (PX4, ArduPilot ap/v2)" \
    test "$(granted "$d/swa_bridge_1/permissions.xml" subscribe)" = \
    "$(sorted swa/uav1/cmd_vel swa/uav1/state rt/drone_1/fmu/out/vehicle_attitude rt/drone_1/fmu/out/sensor_combined \
      rt/drone_1/fmu/out/vehicle_status \
      rt/drone_1/fmu/out/vehicle_status_v1 rt/drone_1/fmu/out/vehicle_command_ack \
      rt/drone_1/fmu/out/vehicle_gps_position rt/drone_1/fmu/out/vehicle_local_position \
      rt/drone_1/fmu/out/vehicle_local_position_v1 rt/ap/v2/imu/experimental/data rt/ap/v2/status \
      rt/ap/v2/navsat rr/ap/v2/arm_motorsReply rr/ap/v2/mode_switchReply)"
  check "the simulator plays every drone_<I>" grep -q "<topic>rt/drone_\*/fmu/out/vehicle_attitude</topic>" \
    "$d/swa_sim/permissions.xml"

  d=$WORK/ros2
  expect_status 0 "--naming ros2 --ros-namespace /lab/a" bash "$SCRIPT" --naming ros2 --ros-namespace /lab/a "$d" 1
  check "agent 0 publishes under the ROS mapping, cmd_vel_stamped too" \
    test "$(granted "$d/swa_agent_0/permissions.xml" publish)" = \
    "$(sorted rt/lab/a/swa/uav0/cmd_vel rt/lab/a/swa/uav0/state rt/lab/a/swa/uav0/cmd_vel_stamped)"
  check "monitor subscribes under the ROS mapping" test "$(granted "$d/swa_monitor/permissions.xml" subscribe)" = \
    "$(sorted rt/lab/a/swa/truth rt/lab/a/swa/events rt/lab/a/swa/clock 'rt/lab/a/swa/uav*/state' \
    'rt/lab/a/swa/uav*/imu' 'rt/lab/a/swa/uav*/detections' 'rt/lab/a/swa/uav*/gnss' 'rt/lab/a/swa/uav*/sensors' \
    'rt/lab/a/swa/uav*/cmd_vel' 'rt/lab/a/swa/uav*/bridge_state' rt/lab/a/swa/swarm/mission)"
  expect_status 2 "--ros-namespace without --naming ros2" bash "$SCRIPT" --ros-namespace a "$WORK/b" 1
  expect_status 2 "--naming other" bash "$SCRIPT" --naming ros "$WORK/b" 1
  expect_status 2 "--ros-namespace with a '-'" bash "$SCRIPT" --naming ros2 --ros-namespace team-a "$WORK/b" 1
  expect_status 2 "--px4-prefix with a '/'" bash "$SCRIPT" --px4-prefix a/b "$WORK/b" 1
  check "refused options create nothing" test ! -e "$WORK/b"
}

test_options() {
  local d=$WORK/opts
  expect_status 0 "--domains 7 --days 2 --org Test" bash "$SCRIPT" --domains 7 --days 2 --org "Test Lab" "$d" 1
  check "one domain" bash -c "grep -q '<min>7</min>' '$d/governance.xml' && grep -q '<max>7</max>' '$d/governance.xml'"
  check "permissions cover the same domains" grep -q '<max>7</max>' "$d/swa_agent_0/permissions.xml"
  check "organisation in the subject" test "$(rfc2253_subject "$d/swa_agent_0/cert.pem")" = "CN=swa_agent_0,O=Test Lab"
  check "certificate valid for 2 days, not 3" bash -c \
    "openssl x509 -in '$d/swa_agent_0/cert.pem' -noout -checkend $((2 * 86400 - 600)) >/dev/null &&
     ! openssl x509 -in '$d/swa_agent_0/cert.pem' -noout -checkend $((2 * 86400 + 600)) >/dev/null"
}

main() {
  if [[ ${1:-} == -h || ${1:-} == --help ]]; then
    usage
    exit 0
  fi
  (($# == 1)) || {
    usage >&2
    exit 2
  }
  SCRIPT=$1
  [[ -r $SCRIPT ]] || {
    echo "$PROG: cannot read $SCRIPT" >&2
    exit 2
  }
  WORK=$(mktemp -d "${TMPDIR:-/tmp}/swa_test_make_credentials.XXXXXX")
  trap 'rm -rf -- "$WORK"' EXIT

  test_arguments
  test_layout_and_documents
  test_overwrite_rules
  test_bridges_and_naming
  test_options

  echo "$PROG: $((CHECKS - FAILURES)) of $CHECKS checks passed"
  ((FAILURES == 0))
}

main "$@"
