#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test, then the sanitizer stage (the labels
# unit, closedloop and fuzz again, built with ASan + UBSan: deploy/test-sanitize.sh). Ends with what each stage took.
#   bash deploy/test.sh                      everything (what CI runs)
#   bash deploy/test.sh [ctest args...]      the Release build and those ctest arguments only, e.g. -L unit
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

stages=()
timed() {  # timed NAME COMMAND...: runs it, notes its wall time
  local name=$1 start=$SECONDS
  shift
  "$@"
  local s=$((SECONDS - start))
  stages+=("$name $((s / 60)) min $((s % 60)) s")
}
timed build bash "$root/deploy/build.sh"
timed "Release tests" ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
if [ $# -eq 0 ]; then
  timed "sanitizer stage" bash "$root/deploy/test-sanitize.sh"
fi
echo "test.sh: $(IFS=';'; echo "${stages[*]}" | sed 's/;/, /g'); $((SECONDS / 60)) min $((SECONDS % 60)) s in all"
