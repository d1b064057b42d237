#!/usr/bin/env bash
# ctest qos_profile_names_have_one_home: every profile of idl/runtime/dds/profiles.xml is named once in
# swa/dds/qos_profiles.h and nowhere else in C++ (check_qos_names.py); and the check can fail: a stray literal and a
# profile without its constant are both refused.
#   test_qos_names.sh SOURCE_DIR
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
src=$1
python3 "$here/check_qos_names.py" "$src"

work=$(mktemp -d /tmp/swa_qos_names.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/idl/runtime/dds/include/swa/dds" "$work/agent/node"
printf '<profiles><data_writer profile_name="a_writer"/><data_reader profile_name="a_reader"/></profiles>\n' \
  > "$work/idl/runtime/dds/profiles.xml"
printf 'inline constexpr const char* kAWriter = "a_writer";\ninline constexpr const char* kAReader = "a_reader";\n' \
  > "$work/idl/runtime/dds/include/swa/dds/qos_profiles.h"
python3 "$here/check_qos_names.py" "$work" > /dev/null || { echo "test_qos_names: a clean tree was refused" >&2; exit 1; }
printf 'auto w = p.writer<T>(topic, "a_writer");\n' > "$work/agent/node/stray.cpp"
out=$(python3 "$here/check_qos_names.py" "$work") && { echo "test_qos_names: a stray literal was accepted" >&2; exit 1; }
grep -q 'agent/node/stray.cpp:1: the profile name "a_writer" written out' <<<"$out" ||
  { echo "test_qos_names: the stray literal not named: $out" >&2; exit 1; }
rm "$work/agent/node/stray.cpp"
sed -i 's|</profiles>|<data_reader profile_name="b_reader"/></profiles>|' "$work/idl/runtime/dds/profiles.xml"
out=$(python3 "$here/check_qos_names.py" "$work") && { echo "test_qos_names: a profile without constant accepted" >&2; exit 1; }
grep -q 'profile b_reader has no constant' <<<"$out" || { echo "test_qos_names: not named: $out" >&2; exit 1; }
echo "test_qos_names: every profile has one constant and no literal elsewhere; a stray literal and a missing constant are refused"
