#!/usr/bin/env bash
# A run recorded by swa_launch --record, read back by the reference MCAP reader (issue #14):
#   test_mcap_record.sh BIN_DIR WORK_DIR
# 1. installs Node.js and npm from Debian if missing, and the reader's npm packages (mcap_reader/package-lock.json:
#    @mcap/core, @foxglove/rosmsg, @foxglove/rosmsg2-serialization) into WORK_DIR;
# 2. records a 4-UAV run (lockstep, 30 s) and checks with @mcap/core that every channel, schema and message count
#    is what the monitor wrote (recording.json) and saw (summary.json), and that every CDR payload decodes against
#    the .msg definitions stored in the file, every metrics message against its JSON Schema;
# 3. recovers a copy cut at 60 % (a crash mid-chunk) with the reference streaming reader;
# 4. kills the recording monitor with SIGKILL during a realtime run and recovers what it left.
# Every run uses the launcher's own swarm partition, so another swarm on the domain neither disturbs nor is disturbed.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=$1
work=$2
scenario=$root/deploy/scenarios/dropout_4.yaml

rm -rf "$work"
install_npm_folder "$here/mcap_reader" "$work/reader" mcap_check.mjs
check() { node "$work/reader/mcap_check.mjs" "$@"; }
reserve_test_domain $((120 + RANDOM % 100))
domain=$TEST_DOMAIN

# 2. A whole run.
"$bin/swa_launch" --scenario "$scenario" --set duration_s=30 --domain "$domain" --out "$work/run" --record \
  --timeout-s 240 || fail "the recorded run did not PASS (exit $?)"
run=$work/run
[ -s "$run/run.mcap" ] || fail "no $run/run.mcap"
summary=$(check check "$run/run.mcap" "$run/recording.json") || fail "the reference reader refused run.mcap"
echo "test_mcap_record: reference reader: $summary"
python3 - "$run" "$summary" <<'PY'
import json, sys
run, reader = sys.argv[1], json.loads(sys.argv[2])
manifest = json.load(open(f"{run}/recording.json"))
summary = json.load(open(f"{run}/summary.json"))
channels = manifest["channels"]
problems = []
expected = {"/swa/truth", "/swa/events", "/swa/clock", "/swa/monitor/metrics"}
for i in range(4):
    expected |= {f"/swa/uav{i}/{t}" for t in ("detections", "imu", "gnss", "cmd_vel", "state", "bridge_state")}
if set(channels) != expected:
    problems.append(f"channels {sorted(set(channels) ^ expected)} differ from the run's topics")
def count(topic):
    return channels.get(topic, {}).get("messages", -1)
# What the monitor saw, counted by its own scoring path, against what it recorded.
if count("/swa/truth") != summary["truth_samples"]:
    problems.append(f"{count('/swa/truth')} truth messages recorded, the monitor scored {summary['truth_samples']}")
states = sum(count(f"/swa/uav{i}/state") for i in range(4))
if states != summary["state_samples"]:
    problems.append(f"{states} state messages recorded, the monitor took {summary['state_samples']}")
if count("/swa/monitor/metrics") != summary["steps"]:
    problems.append(f"{count('/swa/monitor/metrics')} metrics messages, {summary['steps']} scored steps")
# 30 s of a lockstep run: 100 Hz IMU and commands, 10 Hz detections and GNSS, all of them.
for i in range(4):
    for topic, n in (("imu", 3001), ("cmd_vel", 3001), ("detections", 301), ("gnss", 301)):
        if count(f"/swa/uav{i}/{topic}") != n:
            problems.append(f"/swa/uav{i}/{topic}: {count(f'/swa/uav{i}/{topic}')} messages, expected {n}")
    if count(f"/swa/uav{i}/bridge_state") != 0:
        problems.append(f"bridge_state of UAV {i} recorded without a bridge")
if manifest["unstamped"] != 0:
    problems.append(f"{manifest['unstamped']} payloads without a readable header stamp")
total = sum(c["messages"] for c in channels.values())
if reader["messages"] != total or reader["decoded_cdr"] + reader["json"] != total or reader["chunks"] < 2:
    problems.append(f"the reader saw {reader}, the monitor wrote {total} messages")
for p in problems:
    print("test_mcap_record: FAIL:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
PY

# 3. A file cut in the middle of a chunk, as a crash leaves it.
size=$(stat -c %s "$run/run.mcap")
head -c $((size * 6 / 10)) "$run/run.mcap" >"$work/cut.mcap"
recovered=$(check recover "$work/cut.mcap") || fail "the reference reader cannot read the cut file"
echo "test_mcap_record: cut at 60 %: ${recovered:0:160}..."
python3 - "$run/recording.json" "$recovered" <<'PY'
import json, sys
full = json.load(open(sys.argv[1]))["channels"]
got = json.loads(sys.argv[2])
total = sum(c["messages"] for c in full.values())
problems = []
if got["error"] is not None:
    problems.append(f"the reader failed on the cut file: {got['error']}")
# Everything before the cut chunk: 60 % of the bytes hold roughly 60 % of the messages.
if not 0.45 * total <= got["messages"] < 0.6 * total + 1:
    problems.append(f"recovered {got['messages']} of {total} messages from 60 % of the file")
for topic, n in got["channels"].items():
    if n > full[topic]["messages"]:
        problems.append(f"{topic}: {n} recovered, more than the {full[topic]['messages']} recorded")
for p in problems:
    print("test_mcap_record: FAIL:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
PY

# 4. SIGKILL of the recording monitor in a realtime run: the launcher restarts it (into run_restart1.mcap); the file
#    of the killed one is readable up to its last chunk, which is at most about a second old. The launch has a /dev/shm
#    of its own (a new mount namespace with a tmpfs there): the files Fast DDS leaves of the killed monitor are never
#    seen by a test running beside this one.
unshare --mount --propagation private sh -c 'mount -t tmpfs -o mode=1777,size=1g swa-test-shm /dev/shm && exec "$@"' sh \
  "$bin/swa_launch" --scenario "$scenario" --set duration_s=12 --set clock.mode=realtime --domain "$domain" \
  --out "$work/killed" --record --timeout-s 120 >"$work/killed.log" 2>&1 &
launch=$!
monitor=""
for _ in $(seq 100); do
  monitor=$(pgrep -f "swa_monitor .*--out $work/killed " | head -n1 || true)
  [ -n "$monitor" ] && [ -s "$work/killed/run.mcap" ] && break
  sleep 0.1
done
[ -n "$monitor" ] || { kill "$launch" 2>/dev/null; fail "no recording monitor started"; }
sleep 5
kill -9 "$monitor"
wait "$launch" || true
recovered=$(check recover "$work/killed/run.mcap") || fail "the reference reader cannot read the killed monitor's file"
echo "test_mcap_record: killed after 5 s: ${recovered:0:160}..."
python3 - "$recovered" <<'PY'
import json, sys
got = json.loads(sys.argv[1])
ch = got["channels"]
problems = []
if got["error"] is not None:
    problems.append(f"the reader failed: {got['error']}")
# About 5 s of a realtime run minus at most the last second's open chunk (discovery takes a part of the 5 s).
truth = ch.get("/swa/truth", 0)
if truth < 15:
    problems.append(f"only {truth} truth messages recovered from about 5 s of run")
if ch.get("/swa/uav0/imu", 0) < 10 * truth - 20:
    problems.append(f"imu of UAV 0: {ch.get('/swa/uav0/imu', 0)} messages for {truth} truth samples")
for p in problems:
    print("test_mcap_record: FAIL:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
PY
grep -q "restarting it" "$work/killed.log" || fail "the launcher did not restart the killed monitor"
echo "test_mcap_record: PASS"
