#!/usr/bin/env bash
# Install what is missing, build, and run the paper's experiment in-process: 8 UAVs, GNSS lost by all at 10 s,
# 120 s, 10 seeds, with the standalone baseline on the same seeds. Extra arguments go to swa_batch.
#   bash deploy/batch.sh [--set key=value]... [--seeds N] [--out DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

bash "$root/deploy/build.sh" swa_batch
"$build/bin/swa_batch" --scenario "$root/deploy/scenarios/dropout_8.yaml" --seeds 10 --jobs "$(nproc)" \
  --compare standalone --out "$root/out/batch" "$@"
