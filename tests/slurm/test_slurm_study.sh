#!/usr/bin/env bash
# A study on a real Slurm cluster (issue #15): test_slurm_study.sh BIN_DIR WORK_DIR
# Brings up a single-node cluster (slurmctld + slurmd + munged from Debian's packages, on free ports, everything
# under WORK_DIR: local_cluster.sh), submits tests/slurm/study_2x3.yaml (2 x 3 grid points x 4 seeds) with
# deploy/slurm/submit-study.sh as 4 array tasks and a dependent merge job, and checks that OUT/study/ is byte for byte
# what swa_batch writes for the same study run here in one process; the same for the shipped example study
# (deploy/scenarios/study_drift_vs_n.yaml), whose drift must fall with N. Then a study whose third shard fails: the
# merge job must never run. Tears the cluster down on every exit.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin_dir=$(cd "$1" && pwd)
work=$2
# shellcheck source=local_cluster.sh
source "$here/local_cluster.sh"

rm -rf "$work"
mkdir -p "$work"
submit=$root/deploy/slurm/submit-study.sh

# Mistakes are refused before anything reaches Slurm (no cluster needed yet).
refused() {  # refused WHY ARGS...: submit-study must exit 2 saying WHY, and create no study directory
  local why=$1
  shift
  # --bin-dir first: after a `--` in ARGS it would be one of swa_batch's arguments
  if "$submit" --bin-dir "$bin_dir" "$@" > "$work/refused.log" 2>&1; then fail "submitted although $why"; fi
  grep -q "$why" "$work/refused.log" || fail "refused without saying '$why': $(cat "$work/refused.log")"
  [ ! -e "$work/never" ] || fail "a refused submission created its --out"
}
refused "is this script's to set" --scenario "$here/study_2x3.yaml" --out "$work/never" -- --jobs 4
refused "shards must be a whole number" --scenario "$here/study_2x3.yaml" --out "$work/never" --shards 0
refused "not a readable file" --scenario "$work/none.yaml" --out "$work/never"
refused "nothing submitted" --scenario "$here/study_2x3.yaml" --out "$work/never" -- --sweep uav_count=4,0
refused "would make every shard run nothing" --scenario "$here/study_2x3.yaml" --out "$work/never" -- --dry-run
echo "test_slurm_study: submit-study refuses bad arguments and a study with a bad grid point before submitting"

cluster=$work/cluster
trap 'slurm_cluster_down "$cluster"' EXIT
slurm_cluster_install || fail "slurm-wlm and munge could not be installed"
slurm_cluster_up "$cluster" || fail "the single-node cluster did not come up"
sinfo --noheader --format='%P %a %D %t' | sed 's/^/test_slurm_study: sinfo: /'

scenario=$here/study_2x3.yaml
cd "$work"  # the jobs run here too (sbatch --chdir); the scenario's path is given the same way to both

"$bin_dir/swa_batch" --scenario "$scenario" --out "$work/local" > "$work/local.log"

"$submit" --scenario "$scenario" --out "$work/slurm" --shards 4 --cpus-per-task 1 \
  --bin-dir "$bin_dir" --time 00:10:00 | tee "$work/submit.log"
array_id=$(cat "$work/slurm/array.jobid")
merge_id=$(cat "$work/slurm/merge.jobid")
slurm_wait_jobs "$array_id" "$merge_id" || {
  tail -n 20 "$work"/slurm/logs/*.out >&2 || true
  fail "the study's jobs did not all complete"
}

diff -r "$work/local" "$work/slurm/study" || fail "the Slurm study differs from the same study run locally"
rows=$(($(wc -l < "$work/local/runs.csv") - 1))
[ "$rows" -eq 24 ] || fail "runs.csv has $rows rows, expected 2 x 3 x 4 = 24"
[ "$(ls "$work/local/points" | wc -l)" -eq 6 ] || fail "not 6 grid points"
# Each shard was its own array task, and merged only after all four ended.
for i in 1 2 3 4; do
  grep -q "\"shard\": \"$i/4\"" "$work/slurm/shards/$i/study.json" || fail "shards/$i/study.json is not shard $i/4"
  grep -q "study-shard: shard $i/4 on" "$work/slurm/logs/shard_$i.out" || fail "array task $i did not run shard $i/4"
done
echo "test_slurm_study: 4 array tasks + merge == local run: runs.csv ($rows rows), 6 points, study.json, study.html"

# The shipped example study (deploy/scenarios/study_drift_vs_n.yaml: 8 grid points of 120 s runs), locally and on the
# cluster, with 5 of its 20 seeds (40 runs): what the cluster must get right is the same with fewer seeds, and the
# drift's fall with N shows on 5 as well (the 20 are the study itself: bash tests/bench/bench_study.sh).
example=$root/deploy/scenarios/study_drift_vs_n.yaml
"$bin_dir/swa_batch" --scenario "$example" --seeds 5 --out "$work/example_local" > "$work/example_local.log"
"$submit" --scenario "$example" --out "$work/example_slurm" --shards 4 --bin-dir "$bin_dir" --time 00:20:00 \
  -- --seeds 5 > "$work/submit-example.log"
SLURM_WAIT_TIMEOUT=480 slurm_wait_jobs "$(cat "$work/example_slurm/array.jobid")" \
  "$(cat "$work/example_slurm/merge.jobid")" || fail "the example study's jobs did not all complete"
diff -r "$work/example_local" "$work/example_slurm/study" || fail "the example study differs on Slurm"
# Its figure: for both neighbourhood rules the mean drift falls from N = 4 to N = 32 and no run collides.
python3 - "$work/example_local/runs.csv" << 'PY' || fail "the example study does not show drift falling with N"
import csv, statistics, sys
cells = {}
for row in csv.DictReader(open(sys.argv[1])):
    cells.setdefault((row["agent.formation.neighbourhood"], int(row["uav_count"])), []).append(row)
ok = True
for rule in ("gabriel", "k_nearest"):
    drift = [statistics.mean(float(r["drift_velocity_mps"]) for r in cells[(rule, n)]) for n in (4, 8, 16, 32)]
    collisions = sum(float(r["collisions"]) for n in (4, 8, 16, 32) for r in cells[(rule, n)])
    print(f"test_slurm_study: {rule}: mean drift at N = 4, 8, 16, 32: " + ", ".join(f"{d:.4f}" for d in drift) +
          f" m/s; collisions {collisions:.0f}")
    ok &= drift[3] < 0.5 * drift[0] and collisions == 0
sys.exit(0 if ok else 1)
PY
echo "test_slurm_study: the example study (40 runs) on 4 array tasks + merge == local run"

# A shard that fails: swa_batch exits 1 for shard 3/4 only. The merge must never run, and no study is written.
mkdir -p "$work/failing"
cat > "$work/failing/swa_batch" << WRAPPER
#!/bin/bash
case " \$* " in *" --shard 3/4 "*) echo "planted failure of shard 3/4" >&2; exit 1 ;; esac
exec "$bin_dir/swa_batch" "\$@"
WRAPPER
chmod +x "$work/failing/swa_batch"
"$submit" --scenario "$scenario" --out "$work/broken" --shards 4 \
  --bin-dir "$work/failing" --time 00:10:00 > "$work/submit-broken.log"
broken_array=$(cat "$work/broken/array.jobid")
broken_merge=$(cat "$work/broken/merge.jobid")
if slurm_wait_jobs "$broken_array" "$broken_merge" > "$work/wait-broken.log" 2>&1; then
  fail "every job of the study with a failing shard completed"
fi
# (no `| head`: under pipefail a reader that stops early can fail the pipeline)
job_info=$(scontrol show job "$broken_merge")
state=$(grep -o -m 1 'JobState=[A-Z_]*' <<< "$job_info")
# Cancelled by Slurm without ever starting: a merge that ran and failed (no dependency, or afterany) would leave a
# log, and would end FAILED.
[ "$state" = "JobState=CANCELLED" ] || fail "the merge job is $state, not CANCELLED, although shard 3 failed"
grep -q "Reason=DependencyNeverSatisfied" <<< "$job_info" || fail "the merge job was not cancelled for its dependency"
[ ! -e "$work/broken/logs/merge.out" ] || fail "the merge job started although shard 3 failed"
[ ! -e "$work/broken/study" ] || fail "a study was written although shard 3 failed"
grep -q "planted failure" "$work/broken/logs/shard_3.out" || fail "shard 3's log does not show its failure"
echo "test_slurm_study: a failed shard: merge job $broken_merge never ran ($state), no study written"
echo "test_slurm_study: PASS"
