#!/usr/bin/env bash
# ctest top_level_folders_keep_their_floors: of the arrows between the top-level folders (folder_arrows.py), at most
# two run back up: agent/ and sim/ reach the runtime and the wire in idl/, which reaches their cores (ARCHITECTURE.md,
# "Layers": the top level is by role, the layers cut across it). And the check can fail: a copy of the tree where the
# wire includes a program of deploy/ is refused.
#   test_folder_arrows.sh SOURCE_DIR
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
src=$1
python3 "$here/folder_arrows.py" "$src" --at-most 2

work=$(mktemp -d /tmp/swa_folder_arrows.XXXXXX)
trap 'rm -rf "$work"' EXIT
for top in agent sim monitor idl deploy; do cp -r "$src/$top" "$work/"; done
printf '#include "../../deploy/programs/launch/launch.h"\n' >> "$work/idl/wire/world.cpp"
out=$(python3 "$here/folder_arrows.py" "$work" --at-most 2) &&
  { echo "test_folder_arrows: the wire including a program was accepted: $out" >&2; exit 1; }
grep -q 'idl -> deploy' <<<"$out" || { echo "test_folder_arrows: the new arrow not named: $out" >&2; exit 1; }
echo "test_folder_arrows: at most two arrows run back up; a third is refused"
