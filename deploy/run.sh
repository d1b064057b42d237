#!/usr/bin/env bash
# Install what is missing, build, and run the default scenario as processes: swa_sim, one swa_agent per UAV and
# swa_monitor over Fast DDS (8 UAVs, GNSS lost by all at 10 s, 120 s simulated, lockstep), then the standalone
# baseline on the same seed; prints where the report is. Exit status: the monitor's verdict on the SWA run
# (0 PASS, 1 FAIL, 3 INCOMPLETE). Extra arguments go to swa_launch, e.g. --set seed=3 --out DIR.
#   bash deploy/run.sh [--set key=value]... [--out DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

# Only the programs of a launch (the bridge for --vehicle px4): the tests and benchmarks build with the test command.
bash "$root/deploy/build.sh" swa_launch swa_sim swa_agent swa_monitor swa_px4_bridge
"$build/bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_8.yaml" --compare standalone \
  --out "$root/out/run" "$@"
