#!/usr/bin/env bash
# Install what is missing (Debian packages only), configure a Release build with warnings as errors, and build.
#   bash deploy/build.sh               everything: programs, tests, benchmarks (the test command's build)
#   bash deploy/build.sh TARGET...     only these targets and what they need, e.g. swa_launch swa_sim
#   SWA_BUILD_DIR   build directory (default: <repo>/build)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

bash "$root/deploy/install-deps.sh"
# Ninja for a new build directory (it starts compiling at once and keeps both cores busy; an existing directory keeps
# the generator it was made with). ccache and mold are picked up by CMakeLists.txt.
generator=()
if [ ! -f "$build/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSWA_WERROR=ON
if [ $# -gt 0 ]; then
  cmake --build "$build" -j "$(nproc)" --target "$@"
else
  cmake --build "$build" -j "$(nproc)"
fi
