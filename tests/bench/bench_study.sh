#!/usr/bin/env bash
# What a study costs (issue #15; not a ctest; results in BENCHMARKS.md):
#
#   bench_study.sh [BIN_DIR] [ROUNDS] [SHARDS]     (defaults: build/bin, 3, 1000)
#
# 1. Throughput: a fixed sweep (uav_count 8, 16 x both neighbourhood rules x 6 seeds of 120 s = 24 runs) with
#    --jobs 1 and --jobs 2, alternating, ROUNDS times: wall time per configuration, medians and their ratio.
# 2. The shipped example study (deploy/scenarios/study_drift_vs_n.yaml, 160 runs of 120 s) once, on every core: its
#    wall time, and the mean drift and d_NB per swarm size and rule from its runs.csv (the drift-vs-N trend).
# 3. Merge: a study of 2 * SHARDS short runs cut into SHARDS shards (each shard a swa_batch process), then
#    `swa_batch merge` of all of them, ROUNDS times: its wall time (median), and the merged files equal to the
#    whole study's.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=${1:-$root/build/bin}
rounds=${2:-3}
shard_count=${3:-1000}
batch=$bin/swa_batch
[ -x "$batch" ] || { echo "bench_study: no $batch (bash deploy/build.sh swa_batch)" >&2; exit 2; }
work=$(mktemp -d /tmp/swa_bench_study.XXXXXX)
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# seconds of wall time of a command (its output to a log)
wall() {
  local t0 t1
  t0=$(date +%s.%N)
  "$@" > "$work/last.log" 2>&1 || { cat "$work/last.log" >&2; exit 1; }
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}'
}

echo "## machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u +%F)"
echo
echo "### 1. Sweep throughput: --jobs 1 against --jobs 2 ($rounds rounds, alternating)"
sweep=(--scenario "$root/deploy/scenarios/dropout_8.yaml" --set duration_s=120 --sweep uav_count=8,16
  --sweep agent.formation.neighbourhood=gabriel,k_nearest --seeds 6)
: > "$work/j1"
: > "$work/j2"
echo "| round | --jobs 1 wall [s] | --jobs 2 wall [s] |"
echo "|---|---|---|"
for ((r = 1; r <= rounds; ++r)); do
  rm -rf "$work/sweep_j1" "$work/sweep_j2"  # a study's --out must not hold an older study
  a=$(wall "$batch" "${sweep[@]}" --jobs 1 --out "$work/sweep_j1")
  b=$(wall "$batch" "${sweep[@]}" --jobs 2 --out "$work/sweep_j2")
  echo "$a" >> "$work/j1"
  echo "$b" >> "$work/j2"
  printf '| %d | %.2f | %.2f |\n' "$r" "$a" "$b"
done
m1=$(median < "$work/j1")
m2=$(median < "$work/j2")
cmp -s "$work/sweep_j1/runs.csv" "$work/sweep_j2/runs.csv" || { echo "bench_study: --jobs 1 and 2 differ" >&2; exit 1; }
printf '| median | %.2f | %.2f |\n\nthroughput --jobs 2 / --jobs 1 = %.2fx (same runs.csv)\n' "$m1" "$m2" \
  "$(awk -v a="$m1" -v b="$m2" 'BEGIN {print a / b}')"

echo
echo "### 2. The example study (deploy/scenarios/study_drift_vs_n.yaml, every core)"
t=$(wall "$batch" --scenario "$root/deploy/scenarios/study_drift_vs_n.yaml" --out "$work/example")
printf 'wall time %.1f s for %d runs\n\n' "$t" "$(($(wc -l < "$work/example/runs.csv") - 1))"
python3 - "$work/example/runs.csv" << 'PY'
import csv, statistics, sys
from collections import defaultdict
cells = defaultdict(list)
for row in csv.DictReader(open(sys.argv[1])):
    cells[(int(row["uav_count"]), row["agent.formation.neighbourhood"])].append(row)
print("| N | rule | drift [m/s] mean ± std | d_NB [m] | collisions | runs |")
print("|---|---|---|---|---|---|")
for (n, rule), rows in sorted(cells.items()):
    drift = [float(r["drift_velocity_mps"]) for r in rows]
    dnb = [float(r["mean_neighbor_distance_m"]) for r in rows]
    print(f"| {n} | {rule} | {statistics.mean(drift):.4f} ± {statistics.stdev(drift):.4f} | "
          f"{statistics.mean(dnb):.2f} | {sum(float(r['collisions']) for r in rows):.0f} | {len(rows)} |")
PY

echo
echo "### 3. Merge of $shard_count shards ($((2 * shard_count)) runs of 2 s, 4 UAVs)"
small=(--scenario "$root/deploy/scenarios/dropout_4.yaml" --set duration_s=2 --sweep imu.bias_std=0.05,0.1
  --seeds "$shard_count")
"$batch" "${small[@]}" --out "$work/small_whole" > /dev/null
shards=()
for ((i = 1; i <= shard_count; ++i)); do
  "$batch" "${small[@]}" --shard "$i/$shard_count" --jobs 1 --out "$work/shards/$i" > /dev/null
  shards+=("$work/shards/$i")
done
: > "$work/merge"
for ((r = 1; r <= rounds; ++r)); do
  rm -rf "$work/merged"
  wall "$batch" merge "${shards[@]}" --out "$work/merged" >> "$work/merge"
done
diff -r "$work/small_whole" "$work/merged" > /dev/null || { echo "bench_study: merged != whole" >&2; exit 1; }
printf 'merge wall time: %s s (rounds: %s); merged files == the whole study'"'"'s\n' \
  "$(median < "$work/merge" | xargs printf '%.3f')" "$(xargs printf '%.3f ' < "$work/merge")"
