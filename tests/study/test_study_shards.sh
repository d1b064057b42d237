#!/usr/bin/env bash
# A study whole and in shards (issue #15): test_study_shards.sh SWA_BATCH WORK_DIR
# 2 swarm sizes x 3 neighbourhood settings x 4 seeds (20 s each) run once whole and once as 4 shards merged (given in
# another order): runs.csv, every points/<k>/summary.json and study.json are byte-identical; the merge refuses a
# missing shard, a shard given twice and a shard of another study. No DDS: swa_batch runs in-process.
set -euo pipefail
batch=$1
work=$2
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
fail() {
  echo "test_study_shards: FAIL: $*" >&2
  exit 1
}
rm -rf "$work"
mkdir -p "$work"
study=(--scenario "$root/deploy/scenarios/dropout_4.yaml" --set duration_s=20 --sweep uav_count=4,6
  --sweep agent.formation.neighbourhood=gabriel,k_nearest --sweep agent.formation.k=2,3 --seeds 4)
# (k only matters for k_nearest; the grid is still 2 x 2 x 2 points.)
"$batch" "${study[@]}" --out "$work/whole" >"$work/whole.log"
for i in 1 2 3 4; do
  "$batch" "${study[@]}" --shard "$i/4" --jobs 1 --out "$work/shard$i" >"$work/shard$i.log"
done
"$batch" merge "$work/shard3" "$work/shard1" "$work/shard4" "$work/shard2" --out "$work/merged" >"$work/merge.log"
diff -r "$work/whole" "$work/merged" || fail "the merged shards differ from the whole study"
rows=$(($(wc -l <"$work/whole/runs.csv") - 1))
[ "$rows" -eq 32 ] || fail "runs.csv has $rows rows, expected 2 x 2 x 2 x 4 = 32"
[ "$(ls "$work/whole/points" | wc -l)" -eq 8 ] || fail "not 8 grid points"
echo "test_study_shards: whole == 4 shards merged: runs.csv ($rows rows), 8 points, study.json"

refused() {  # refused WHY ARGS...: the merge must fail, saying WHY
  local why=$1
  shift
  if "$batch" merge "$@" --out "$work/refused" 2>"$work/refused.log"; then fail "merged although $why"; fi
  grep -q "$why" "$work/refused.log" || fail "refused without saying '$why': $(cat "$work/refused.log")"
}
refused "not given" "$work/shard1" "$work/shard2" "$work/shard3"
refused "repeats run" "$work/shard1" "$work/shard2" "$work/shard3" "$work/shard4" "$work/shard2"
"$batch" "${study[@]}" --set imu.bias_std=0.2 --shard 4/4 --jobs 1 --out "$work/other" >/dev/null
refused "is of study" "$work/shard1" "$work/shard2" "$work/shard3" "$work/other"
echo "test_study_shards: PASS"
