#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test, then the sanitizer stage (the labels
# unit, closedloop and fuzz again, built with ASan + UBSan: deploy/test-sanitize.sh).
#   bash deploy/test.sh                      everything (what CI runs)
#   bash deploy/test.sh [ctest args...]      the Release build and those ctest arguments only, e.g. -L unit
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

bash "$root/deploy/build.sh"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
if [ $# -eq 0 ]; then
  bash "$root/deploy/test-sanitize.sh"
fi
