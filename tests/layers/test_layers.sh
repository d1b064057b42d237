#!/usr/bin/env bash
# ctest includes_follow_the_layers: the source tree's includes follow the layer order of check_layers.py (ARCHITECTURE.md,
# "Layers"); and the check can fail: a small tree with an include against the order, and one with a file in no
# layer, are both refused.
#   test_layers.sh SOURCE_DIR
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
src=$1
python3 "$here/check_layers.py" "$src"

work=$(mktemp -d /tmp/swa_layers.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/agent/src" "$work/agent/node" "$work/idl/runtime/dds/include/swa/dds"
echo '#pragma once' > "$work/idl/runtime/dds/include/swa/dds/participant.h"
printf '#include "swa/dds/participant.h"\n' > "$work/agent/src/upward.cpp"
printf '#include "swa/dds/participant.h"\n' > "$work/agent/node/downward.cpp"
out=$(python3 "$here/check_layers.py" "$work") && { echo "test_layers: an upward include was accepted" >&2; exit 1; }
grep -q 'agent/src/upward.cpp:1: includes swa/dds/participant.h' <<<"$out" ||
  { echo "test_layers: the upward include not named: $out" >&2; exit 1; }
grep -q 'downward.cpp' <<<"$out" && { echo "test_layers: a process including the runtime refused: $out" >&2; exit 1; }
rm "$work/agent/src/upward.cpp"
mkdir -p "$work/agent/nowhere"
printf 'int x;\n' > "$work/agent/nowhere/new.cpp"
out=$(python3 "$here/check_layers.py" "$work") && { echo "test_layers: a file in no layer was accepted" >&2; exit 1; }
grep -q 'agent/nowhere/new.cpp: in no layer' <<<"$out" || { echo "test_layers: not named: $out" >&2; exit 1; }
echo "test_layers: the tree follows the layers; an upward include and a file in no layer are refused"
