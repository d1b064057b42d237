#!/usr/bin/env bash
# Install what is missing (Debian packages only), configure a Release build and build everything.
#   SWA_BUILD_DIR   build directory (default: <repo>/build)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

bash "$root/deploy/install-deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSWA_WERROR=ON
cmake --build "$build" -j "$(nproc)"
