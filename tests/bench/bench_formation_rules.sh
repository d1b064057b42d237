#!/usr/bin/env bash
# Issue #10's formation statistics with their bars (not a ctest since issue #25; results in BENCHMARKS.md): every
# swarm size from 3 to 16 over 10 seeds of 600 s (d_NB within 3 % of r at 120 s and at the end, one group, no
# collision, nobody closer than 7 m), the drift of 8 UAVs, IMU-bias removal with a poor IMU, the old k-nearest rules
# as contrasts and a 240 deg field of view. Each bar is a GoogleTest assertion of
# tests/closedloop/formation_statistics.cpp; the test suite keeps one seed of each case as a guard
# (tests/closedloop/test_formation_guard.cpp).
#
#   bench_formation_rules.sh [BIN_DIR] [gtest args...]     (default build/bin; e.g. --gtest_filter='EverySwarmSize*')
#
# About 3 min on 2 cores (Release). Exit status non-zero if a bar is missed.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=${1:-$root/build/bin}
[ $# -gt 0 ] && shift
if [ ! -x "$bin/formation_statistics" ]; then
  echo "bench_formation_rules: no $bin/formation_statistics (bash deploy/build.sh)" >&2
  exit 2
fi
exec "$bin/formation_statistics" "$@"
