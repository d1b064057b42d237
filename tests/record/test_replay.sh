#!/usr/bin/env bash
# A recorded run replayed (issue #14):
#   test_replay.sh BIN_DIR WORK_DIR
# 1. records a 4-UAV lockstep run (swa_launch --record);
# 2. swa_replay --check re-runs every agent's core on the recording: every command bit-identical (exit 0); with
#    another formation radius the commands differ (exit 1);
# 3. replays it over DDS (--lockstep) into four fresh swa_agent processes and a fresh swa_monitor: every agent's
#    answer equals its recorded command byte for byte, and the monitor's verdict and scores equal the recorded run's.
# Processes run in their own swarm partition (SWA_SWARM) on a random domain; every one is stopped on exit.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=$1
work=$2
scenario=$root/deploy/scenarios/dropout_4.yaml
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
}
trap cleanup EXIT

rm -rf "$work"
mkdir -p "$work"
reserve_test_domain $((120 + RANDOM % 100))
export SWA_DOMAIN=$TEST_DOMAIN

# 1.
"$bin/swa_launch" --scenario "$scenario" --set duration_s=20 --out "$work/run" --record --timeout-s 240 \
  || fail "the recorded run did not PASS"
recording=$work/run/run.mcap

# 2.
"$bin/swa_replay" "$recording" --check | tee "$work/check.txt" || fail "--check with the recorded parameters: exit $?"
[ "$(grep -c ' 0 differ' "$work/check.txt")" -eq 4 ] || fail "--check: not every UAV identical"
grep -q "^IDENTICAL" "$work/check.txt" || fail "--check: no IDENTICAL verdict"
set +e
"$bin/swa_replay" "$recording" --check --uav 2 --set agent.formation.radius_m=12 >"$work/check_r12.txt"
status=$?
set -e
cat "$work/check_r12.txt"
[ "$status" -eq 1 ] || fail "--check with another radius exited $status, expected 1 (DIFFERENT)"
grep -q "^uav 2: .* [1-9][0-9]* differ" "$work/check_r12.txt" || fail "--check with another radius: nothing differs"

# 3. Fresh processes on the recorded data, in a partition of their own.
export SWA_SWARM=replay$$
for i in 0 1 2 3; do
  "$bin/swa_agent" --id "$i" --config "$work/run/agent.yaml" >"$work/agent_$i.log" 2>&1 &
  pids+=($!)
done
"$bin/swa_monitor" --scenario "$work/run/scenario.yaml" --out "$work/replayed" --quiet --timeout-s 120 \
  >"$work/monitor.log" 2>&1 &
monitor=$!
pids+=("$monitor")
timeout 180 "$bin/swa_replay" "$recording" --lockstep --speed 0 --wait-s 60 | tee "$work/replay.txt" \
  || fail "the lockstep replay into fresh agents: exit $? (see $work/replay.txt)"
[ "$(grep -c ' 0 differ, 0 not recorded, 0 not answered' "$work/replay.txt")" -eq 4 ] \
  || fail "a fresh agent's answers differ from the recorded commands"
set +e
wait "$monitor"
monitor_status=$?
set -e
[ "$monitor_status" -eq 0 ] || fail "the monitor of the replay exited $monitor_status (see $work/monitor.log)"
python3 - "$work/run/summary.json" "$work/replayed/summary.json" <<'PY'
import json, sys
recorded, replayed = (json.load(open(p)) for p in sys.argv[1:])
problems = []
# Truth is replayed as recorded and the agents answer bit for bit: the scores are the recorded run's, exactly.
# (Not the count of states received: an agent also states itself once per wall second when its inputs pause, and
# the wall clock of a replay is not the run's.)
for key in ("verdict", "steps", "mean_neighbor_distance_m", "min_separation_m", "anees_position", "anees_velocity",
            "nees_samples", "collisions"):
    if recorded[key] != replayed[key]:
        problems.append(f"{key}: recorded run {recorded[key]}, replay {replayed[key]}")
for p in problems:
    print("test_replay: FAIL:", p, file=sys.stderr)
print(f"test_replay: replayed run: verdict {replayed['verdict']}, d_NB {replayed['mean_neighbor_distance_m']}, "
      f"ANEES {replayed['anees_position']}")
sys.exit(1 if problems else 0)
PY
echo "test_replay: PASS"
