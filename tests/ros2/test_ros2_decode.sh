#!/usr/bin/env bash
# The ROS 2 profile's payloads decoded by an independent ROS 2 CDR implementation (issue #13, no ROS installation):
#   test_ros2_decode.sh TEST_ROS2_PROFILE_BINARY WORK_DIR
# 1. installs Node.js and npm from Debian if missing, and the decoder's npm packages (package-lock.json) into WORK_DIR;
# 2. runs test_ros2_profile, which launches a 4-UAV run in the ros2 naming, checks every endpoint's names and writes
#    every captured payload with its Fast DDS decoding to WORK_DIR/capture.json;
# 3. decodes each payload again with @foxglove/rosmsg2-serialization against idl/swa_msgs/msg and compares field by
#    field (decoder/decode_check.mjs).
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
profile_test=$1
work=$2

rm -rf "$work"
install_npm_folder "$here/decoder" "$work/decoder"

SWA_ROS2_CAPTURE="$work/capture.json" "$profile_test"
node "$work/decoder/decode_check.mjs" "$work/capture.json" "$root/idl/swa_msgs/msg"
