#!/usr/bin/env bash
# A study whole and in shards (issue #15): test_study_shards.sh SWA_BATCH WORK_DIR
# 2 swarm sizes x 3 neighbourhood settings x 4 seeds (20 s each) run once whole and once as 4 shards merged (given in
# another order): runs.csv, every points/<k>/summary.json and study.json are byte-identical; the merge refuses a
# missing shard, a shard given twice, a shard of another study or another cut, and an --out holding a study; studies
# whose grid points repeat a scenario or move the seed are refused before they run. No DDS: swa_batch runs in-process.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
batch=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
study=(--scenario "$root/deploy/scenarios/dropout_4.yaml" --set duration_s=20 --sweep uav_count=4,6
  --sweep agent.formation.neighbourhood=gabriel,k_nearest --sweep imu.bias_std=0.05,0.1 --seeds 4)
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
"$batch" "${study[@]}" --shard 1/2 --jobs 1 --out "$work/half" >/dev/null
refused "merge the shards of one cut" "$work/half" "$work/shard2" "$work/shard3" "$work/shard4"
if "$batch" merge "$work/shard1" "$work/shard2" "$work/shard3" "$work/shard4" --out "$work/whole" 2>"$work/refused.log"
then fail "merged into a directory holding a study"; fi
grep -q "already holds a study" "$work/refused.log" || fail "merge over a study refused without saying why"

# Studies refused before they run: a value in two spellings, an alias of a swept key, an old study in --out.
refused_study() {  # refused_study WHY ARGS...: swa_batch must exit 2 saying WHY
  local why=$1
  shift
  if "$batch" "$@" > "$work/refused.log" 2>&1; then fail "ran a study although $why"; fi
  grep -q "$why" "$work/refused.log" || fail "refused without saying '$why': $(cat "$work/refused.log")"
}
base=(--scenario "$root/deploy/scenarios/dropout_4.yaml" --set duration_s=2)
refused_study "are the same scenario" "${base[@]}" --sweep imu.bias_std=0.1,0.10 --out "$work/r1"
refused_study "given twice" "${base[@]}" --sweep agent.formation.k=1,5 --sweep agent.k=2 --out "$work/r2"
# k changes nothing at the gabriel points: their runs would be labelled with values that were never applied
refused_study "agent.formation.k applies to the k_nearest rule only" "${base[@]}" \
  --sweep agent.formation.neighbourhood=gabriel,k_nearest --sweep agent.formation.k=2,3 --out "$work/r4"
refused_study "agent.formation.k applies to the k_nearest rule only" "${base[@]}" \
  --sweep agent.formation.k=2,3 --sweep agent.formation.neighbourhood=gabriel,k_nearest --out "$work/r5"
refused_study "seeds are a study's repetitions" "${base[@]}" --sweep "seed =5,9" --out "$work/r3"
refused_study "already holds a study" "${study[@]}" --out "$work/whole"
echo "test_study_shards: PASS"
