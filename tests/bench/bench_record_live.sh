#!/usr/bin/env bash
# What recording and the live view cost the monitor (issue #14): realtime runs of 8 UAVs, in turn without and with
# --record --live and one Foxglove client subscribed for the whole run (not a ctest; results in BENCHMARKS.md).
#
#   bench_record_live.sh [BIN_DIR] [DURATION_S] [ROUNDS]     (defaults: build/bin, 60, 3)
#
# Per run: the monitor's CPU time (user + system, its own getrusage at exit: monitor.log), the simulator's late
# commands (sim_summary.json: answers after their step's deadline), and with the live view the messages sent and
# dropped. The table shows each run, the medians, and the ratio of the medians (with / without).
#
# Issue #24: a complete recording has to receive every sample, so the recording run also has a bare Fast DDS reader
# beside the monitor (bench_record_reader: the same topics, reader profiles, participant code, swarm partition and
# domain; it only counts), started before the launcher and stopped after it. Its own getrusage gives the baseline;
# the ratio monitor / bare reader is the issue's figure. Sample counts: the bare reader's per topic, the recording's
# per channel (read back from run.mcap with SWA's McapReader), and where the simulator's summary implies one, the
# expected count (IMU and clock: one per simulated step).
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=${1:-$root/build/bin}
duration=${2:-60}
rounds=${3:-3}
work=$(mktemp -d /tmp/swa_bench_record_live.XXXXXX)
client_pid=""
reader_pid=""
cleanup() {
  if [ -n "$client_pid" ]; then kill "$client_pid" 2>/dev/null || true; fi
  if [ -n "$reader_pid" ]; then kill "$reader_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT

for b in swa_launch swa_sim swa_agent swa_monitor bench_record_reader; do
  [ -x "$bin/$b" ] || { echo "bench_record_live: no $bin/$b (bash deploy/build.sh)" >&2; exit 2; }
done
install_npm_folder "$root/tests/live/live_client" "$work/client" live_check.mjs

run() {  # run WITH(0|1) ROUND
  local out=$work/run_$1_$2 extra=() domain=$((160 + $2)) swarm=benchrec$$r$1x$2
  if [ "$1" = 1 ]; then
    extra=(--record --live 0)
    # The bare reader joins first, so like the monitor it has matched every writer before the simulator starts.
    SWA_SWARM=$swarm "$bin/bench_record_reader" --uav-count 8 --domain "$domain" >"$work/reader_$2.json" \
      2>"$work/reader_$2.log" &
    reader_pid=$!
    sleep 2
  fi
  "$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_8.yaml" --set "duration_s=$duration" \
    --set clock.mode=realtime --domain "$domain" --swarm "$swarm" --out "$out" "${extra[@]}" >"$out.log" 2>&1 &
  local launch=$!
  if [ "$1" = 1 ]; then
    local port=""
    for _ in $(seq 300); do
      if [ -f "$out/logs/monitor.log" ]; then
        port=$(sed -n 's|.*live view at http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$out/logs/monitor.log" | head -n1)
      fi
      if [ -n "$port" ]; then break; fi
      sleep 0.1
    done
    # Subscribed to every channel it is offered until the run ends (it then reports the closed connection).
    node "$work/client/live_check.mjs" "ws://127.0.0.1:$port/" "$work/client_$2.json" --messages 1000000 \
      --timeout-s 30 >/dev/null 2>&1 &
    client_pid=$!
  fi
  wait "$launch" || { echo "bench_record_live: run $1 $2 failed:" >&2; tail -5 "$out.log" >&2; exit 1; }
  if [ -n "$client_pid" ]; then
    wait "$client_pid" 2>/dev/null || true
    client_pid=""
  fi
  if [ -n "$reader_pid" ]; then
    kill -TERM "$reader_pid"
    if ! wait "$reader_pid"; then
      echo "bench_record_live: the bare reader failed:" >&2
      cat "$work/reader_$2.log" >&2
      exit 1
    fi
    reader_pid=""
    "$bin/bench_record_reader" --count-mcap "$out/run.mcap" >"$work/recording_$2.json"
  fi
}

for ((r = 1; r <= rounds; r++)); do
  run 0 "$r"
  run 1 "$r"
done

python3 - "$work" "$rounds" "$duration" <<'PY'
import glob, json, re, statistics, sys
work, rounds, duration = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def figures(with_, r):
    d = f"{work}/run_{with_}_{r}"
    log = open(f"{d}/logs/monitor.log").read()
    cpu = float(re.search(r"([0-9.]+) s of CPU time", log).group(1))
    late = json.load(open(f"{d}/sim_summary.json"))["late_commands"]
    m = re.search(r"live view: .* (\d+) message\(s\) sent, (\d+) dropped", log)
    return cpu, late, (int(m.group(1)), int(m.group(2))) if m else None
rows = {w: [figures(w, r) for r in range(1, rounds + 1)] for w in (0, 1)}
print(f"8 UAVs, realtime, {duration} s simulated, {rounds} rounds in turn")
print(f"{'run':<28}{'monitor CPU [s]':>16}{'late commands':>15}{'live sent / dropped':>22}")
for w, label in ((0, "plain"), (1, "--record --live + client")):
    for r, (cpu, late, live) in enumerate(rows[w], 1):
        live_text = f"{live[0]} / {live[1]}" if live else "-"
        print(f"{label + ' #' + str(r):<28}{cpu:>16.3f}{late:>15}{live_text:>22}")
plain = statistics.median(c for c, _, _ in rows[0])
with_ = statistics.median(c for c, _, _ in rows[1])
print(f"median monitor CPU: plain {plain:.3f} s, with {with_:.3f} s, ratio {with_ / plain:.3f}")
print(f"late commands: plain {sum(l for _, l, _ in rows[0])}, with {sum(l for _, l, _ in rows[1])}")

# Issue #24: the recording monitor against the bare reader of the same run.
readers = [json.load(open(f"{work}/reader_{r}.json")) for r in range(1, rounds + 1)]
recordings = [json.load(open(f"{work}/recording_{r}.json")) for r in range(1, rounds + 1)]
print()
print(f"{'round':<8}{'monitor --record --live [s]':>29}{'bare reader [s] (user+sys)':>28}{'ratio':>8}")
for r in range(rounds):
    m, b = rows[1][r][0], readers[r]
    split = f"({b['user_s']:.2f}+{b['system_s']:.2f})"
    print(f"{'#' + str(r + 1):<8}{m:>29.3f}{b['cpu_s']:>13.3f} {split}{'':>3}{m / b['cpu_s']:>8.2f}")
bare = statistics.median(b["cpu_s"] for b in readers)
print(f"median: monitor {with_:.3f} s, bare reader {bare:.3f} s, ratio {with_ / bare:.3f} (issue #24 target <= 1.3)")

def kind(topic):
    leaf = topic.rsplit("/", 1)[-1]
    return leaf if "/uav" in topic else topic
print()
print("samples per kind (all UAVs), each round: bare reader / recording / published (imu, clock: the steps; cmd_vel, "
      "state: the agents' own counts)")
for r in range(rounds):
    sim = json.load(open(f"{work}/run_1_{r + 1}/sim_summary.json"))
    steps = sim["steps"]
    totals = {}
    for source, counts in (("reader", readers[r]["counts"]), ("recording", recordings[r]["counts"])):
        for topic, n in counts.items():
            totals.setdefault(kind(topic), {}).setdefault(source, 0)
            totals[kind(topic)][source] += n
    # What was published: the steps for the simulator's topics, and for the agents' commands and states what each
    # agent says it wrote when it stops ("... 12001 commands, 1201 states ..."). The simulator's own count of
    # received commands (applied + ignored) is printed beside it: it stops listening after the last step.
    published = {"commands": 0, "states": 0}
    for log_path in glob.glob(f"{work}/run_1_{r + 1}/logs/agent_*.log"):
        # One line per process that wrote to this log: a restarted agent appends its own.
        counts = re.findall(r"(\d+) commands, (\d+) states", open(log_path).read())
        if not counts:
            sys.exit(f"bench_record_live: no command count in {log_path}")
        published["commands"] += sum(int(c) for c, _ in counts)
        published["states"] += sum(int(s) for _, s in counts)
    expected = {"imu": 8 * (steps + 1), "/swa/clock": steps + 1, "cmd_vel": published["commands"],
                "state": published["states"]}
    lost = []
    cells = []
    for k in sorted(totals):
        if k == "/swa/monitor/metrics":  # the monitor's own, on no DDS topic
            continue
        a, b = totals[k].get("reader", 0), totals[k].get("recording", 0)
        e = expected.get(k)
        cells.append(f"{k} {a}/{b}" + (f"/{e}" if e is not None else ""))
        if a != b or (e is not None and (a != e or b != e)):
            lost.append(k)
    received = sim["applied_commands"] + sim["ignored_commands"]
    print(f"#{r + 1} (sim steps {steps}, commands the simulator received {received}, missing answers "
          f"{sim['missing_answers']}, truncated {recordings[r]['truncated']}): " + ", ".join(cells))
    print(f"   differ: {', '.join(lost) if lost else 'none'}")
PY
