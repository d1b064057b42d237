#!/usr/bin/env bash
# A monitor-only recording (issue #24, swa_launch --record=monitor):
#   test_record_monitor_set.sh BIN_DIR WORK_DIR
# 1. records a 4-UAV lockstep run of 5 s with --record=monitor;
# 2. the reference MCAP reader (@mcap/core, mcap_reader/) confirms the file's channels and counts are what the monitor
#    says it wrote (recording.json), and that set is exactly truth, events, each UAV's state and the metrics: no
#    sensor, command, bridge state or clock channel; the counts equal what the monitor scored (summary.json);
# 3. swa_replay, which needs the sensors, refuses the file with exit 2 and says it is a monitor-only recording,
#    both with --check and when asked to replay over DDS.
# The launcher gives the run a swarm partition of its own on a random domain; node and npm come from Debian/npm as in
# test_mcap_record.sh.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=$1
work=$2
rm -rf "$work"
install_npm_folder "$here/mcap_reader" "$work/reader" mcap_check.mjs

reserve_test_domain $((120 + RANDOM % 100))

# 1.
"$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_4.yaml" --set duration_s=5 \
  --domain "$TEST_DOMAIN" --out "$work/run" --record=monitor --timeout-s 120 \
  || fail "the recorded run did not PASS (exit $?)"
run=$work/run
[ -s "$run/run.mcap" ] || fail "no $run/run.mcap"

# 2.
summary=$(node "$work/reader/mcap_check.mjs" check "$run/run.mcap" "$run/recording.json") \
  || fail "the reference reader refused run.mcap or found other channels or counts than recording.json"
echo "test_record_monitor_set: reference reader: $summary"
python3 - "$run" <<'PY'
import json, sys
run = sys.argv[1]
channels = json.load(open(f"{run}/recording.json"))["channels"]
summary = json.load(open(f"{run}/summary.json"))
problems = []
expected = {"/swa/truth", "/swa/events", "/swa/monitor/metrics"} | {f"/swa/uav{i}/state" for i in range(4)}
if set(channels) != expected:
    problems.append(f"channels {sorted(channels)}, expected exactly {sorted(expected)}")
count = lambda topic: channels.get(topic, {}).get("messages", -1)
if count("/swa/truth") != summary["truth_samples"] or summary["truth_samples"] < 40:
    problems.append(f"{count('/swa/truth')} truth messages recorded, the monitor scored {summary['truth_samples']}")
states = sum(count(f"/swa/uav{i}/state") for i in range(4))
if states != summary["state_samples"] or states < 4 * 40:
    problems.append(f"{states} state messages recorded, the monitor took {summary['state_samples']}")
if count("/swa/monitor/metrics") != summary["steps"]:
    problems.append(f"{count('/swa/monitor/metrics')} metrics messages, {summary['steps']} scored steps")
for p in problems:
    print("test_record_monitor_set: FAIL:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
PY

# 3.
for mode in "--check" "--lockstep --speed 0 --wait-s 5"; do
  set +e
  # shellcheck disable=SC2086
  timeout 60 "$bin/swa_replay" "$run/run.mcap" $mode >"$work/replay.out" 2>"$work/replay.err"
  status=$?
  set -e
  [ "$status" -eq 2 ] || fail "swa_replay $mode on a monitor-only recording exited $status, expected 2"
  grep -q "is a 'monitor' recording .*swa_replay needs a complete recording" "$work/replay.err" \
    || fail "swa_replay $mode does not say why: $(cat "$work/replay.err")"
done
channels=$(python3 -c "import json, sys; print(len(json.load(open(sys.argv[1]))['channels']))" "$run/recording.json")
echo "test_record_monitor_set: PASS ($channels channels)"
