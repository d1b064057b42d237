#!/usr/bin/env bash
# The other systems' messages SWA speaks (vision_msgs, UVDAR's mrs_msgs, PX4's per release, ArduPilot's), checked both
# ways with an independent ROS 2 CDR implementation against the upstream definitions in tests/upstream (issues #27 and
# #42, no ROS installation):
#   test_foreign_decode.sh FOREIGN_PAYLOADS_BINARY WORK_DIR
# 1. installs Node.js and npm from Debian if missing, and the decoder's npm packages (package-lock.json) into WORK_DIR;
# 2. foreign_payloads write: SWA's payloads of every type, with the values set;
# 3. decoder/foreign_check.mjs decodes them field for field and serialises the same values itself;
# 4. foreign_payloads check: SWA reads those as the agent does.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
payloads=$1
work=$2

rm -rf "$work"
install_npm_folder "$here/decoder" "$work/decoder"

"$payloads" write "$work/capture.json"
node "$work/decoder/foreign_check.mjs" "$work/capture.json" "$root/tests/upstream" "$work/independent.json"
"$payloads" check "$work/independent.json"
rm -rf "$work"
