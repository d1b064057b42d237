#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test.
#   bash deploy/test.sh [ctest args...]      e.g. bash deploy/test.sh -L unit
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

bash "$root/deploy/build.sh"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
