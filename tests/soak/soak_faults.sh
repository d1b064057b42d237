#!/usr/bin/env bash
# Soak with faults (issue #46; a benchmark, not a ctest; figures in BENCHMARKS.md): a realtime swarm that records
# everything while a fault strikes it every period, from a schedule drawn from a seed.
#
# Usage: bash tests/soak/soak_faults.sh [--duration-s S] [--fault-period-s P] [--seed N] [--uavs N]
#          [--vehicle px4|ardupilot|direct] [--out DIR]
#   defaults: 3600 s, a fault every 120 s, seed 1, 8 UAVs, px4, out/soak_faults. The by-hand variant: --duration-s 600.
#   Needs root (a network namespace, iptables) and a Release build in build/ (deploy/build.sh); installs iptables
#   and jq with apt-get if missing.
#
# The faults, each at its scheduled time t, on a UAV drawn from the seed, in a seeded order that uses every kind
# before it repeats one:
#   agent_kill       SIGKILL of that UAV's swa_agent; the launcher restarts it
#   bridge_kill      SIGKILL of its swa_px4_bridge (not with --vehicle direct); the launcher restarts it
#   loss_burst       30 s of 30 % UDP loss (20 +- 10 ms delay on the rest) on every link: swa_netem behind an
#                    iptables NFQUEUE rule, as in tests/loss
#   monitor_restart  SIGKILL of swa_monitor; the launcher restarts it, which records into run_restart<K>.mcap
#   gnss_window      every UAV without GNSS for 60 s of simulated time (gnss.windows; GNSS is otherwise valid)
#   rogue_agent      a second swa_agent for that UAV, in the same swarm: it must refuse to run (exit 3)
#
# The run: `swa_launch --record --transport network` (UDP only: NFQUEUE sees only UDP) in a network namespace of
# the script's own with its own /dev/shm, so no other DDS user of the host sees it or disturbs it. Printed at the end:
#   - every process's resident memory at the start (after a 120 s warm-up) and at the end, and its growth, for those
#     that ran through (a restarted one is a new process: its figures are given but not judged);
#   - the restarts the launcher made against the kills;
#   - the monitor's verdict (PASS, or INCOMPLETE after a monitor restart, said honestly);
#   - recording completeness: per second of simulated time, the distinct stamps the recordings hold (all files of
#     the run together) of every UAV's IMU samples and states, of the clock and the truth, against the rate they are
#     published at, outside the fault windows (a window: from 2 s before a fault to 10 s after it ends; a GNSS window
#     is no transport fault and excuses nothing); judged. Also reported, not judged: what a fault cost topics it
#     should not touch (a kill another UAV's or the clock, a refused rogue agent anything);
#   - bad commands: commands a bridge received non-finite or had to clamp (each bridge's final counts).
# Files: DIR/schedule.csv, DIR/faults.log, DIR/rss.csv (every 30 s), DIR/run (the launch), DIR/completeness.json.
# Exit status: 0 when every judged figure meets issue #46's targets (PASS or INCOMPLETE; RSS growth <= 10 %; no
# sample lost outside the windows; 0 bad commands; every kill restarted; every rogue refused), else 1; 2 bad use.

# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
TEST_TAG=soak_faults
duration=3600
period=120
seed=1
uavs=8
vehicle=px4
out=$root/out/soak_faults
while [[ $# -gt 0 ]]; do
  case $1 in
    --duration-s) duration=$2; shift 2 ;;
    --fault-period-s) period=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --uavs) uavs=$2; shift 2 ;;
    --vehicle) vehicle=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,35p' "$0"; exit 0 ;;
    *) echo "soak_faults: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
for v in "$duration" "$period" "$seed" "$uavs"; do
  [[ $v =~ ^[0-9]+$ && $v -gt 0 ]] || { echo "soak_faults: '$v' is not a positive whole number" >&2; exit 2; }
done
[[ $vehicle =~ ^(px4|ardupilot|direct)$ ]] || { echo "soak_faults: --vehicle is px4, ardupilot or direct" >&2; exit 2; }
((uavs >= 2)) || { echo "soak_faults: at least 2 UAVs" >&2; exit 2; }
((period >= 90)) || { echo "soak_faults: --fault-period-s must be at least 90 (a GNSS window is 60 s)" >&2; exit 2; }
((duration >= 2 * period)) || { echo "soak_faults: --duration-s must be at least twice the fault period" >&2; exit 2; }
[[ $(id -u) -eq 0 ]] || { echo "soak_faults: needs root (a network namespace, iptables)" >&2; exit 2; }
bin=$root/build/bin
for b in swa_launch swa_agent swa_sim swa_monitor swa_px4_bridge swa_netem bench_record_reader; do
  [[ -x $bin/$b ]] || { echo "soak_faults: $bin/$b missing: run bash deploy/build.sh first" >&2; exit 2; }
done
ensure_packages iptables jq

# The warm-up covers what fills by design: the simulator's truth writer keeps the last 100 s for a restarted monitor
# (idl/runtime/dds/profiles.xml), so its memory grows for the first ~100 s (tests/soak/soak.sh).
readonly WARMUP_S=120 QUEUE=9 SWARM=soak
ns=swasoak$$
rm -rf "$out"
mkdir -p "$out"
faults_log=$out/faults.log
: >"$faults_log"
note() { printf '%s %s\n' "$(date -u +%H:%M:%S)" "$*" | tee -a "$faults_log"; }

# ---------------------------------------------------------------------------------------------------- schedule
# t_s,kind,uav,window_s: one fault per period from t = period on, the last one ending at least 30 s before the end.
python3 - "$seed" "$duration" "$period" "$uavs" "$vehicle" >"$out/schedule.csv" <<'EOF'
import random, sys
seed, duration, period, uavs, vehicle = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
window = {"agent_kill": 15, "bridge_kill": 15, "loss_burst": 30, "monitor_restart": 15, "gnss_window": 60,
          "rogue_agent": 20}
kinds = [k for k in window if vehicle != "direct" or k != "bridge_kill"]
rng = random.Random(seed)
order = []
print("t_s,kind,uav,window_s")
t = period
while True:
    if not order:
        order = kinds[:]
        rng.shuffle(order)
    kind = order[0]
    if t + window[kind] > duration - 30:
        break
    order.pop(0)
    print(f"{t},{kind},{rng.randrange(uavs)},{window[kind]}")
    t += period
EOF
log "schedule (seed $seed): $(tail -n +2 "$out/schedule.csv" | cut -d, -f2 | sort | uniq -c | awk '{printf "%s %s, ", $1, $2}')"
gnss_windows=$(awk -F, -v n="$uavs" 'NR > 1 && $2 == "gnss_window" {
  for (u = 0; u < n; ++u) printf "%s{uav: %d, start_s: %d, end_s: %d}", (k++ ? ", " : ""), u, $1, $1 + $4 }' \
  "$out/schedule.csv")

# ------------------------------------------------------------------------------------------ namespace, cleanup
launch_pid=""
netem_pid=""
cleanup() {
  ip netns exec "$ns" iptables -F OUTPUT 2>/dev/null || true
  if [[ -n $netem_pid ]]; then kill -TERM "$netem_pid" 2>/dev/null || true; fi
  if [[ -n $launch_pid ]]; then kill -TERM "$launch_pid" 2>/dev/null || true; fi
  local pids
  for _ in $(seq 1 200); do
    pids=$(ip netns pids "$ns" 2>/dev/null || true)
    [[ -z $pids ]] && break
    sleep 0.1
  done
  # shellcheck disable=SC2086  # one pid per word
  if [[ -n $pids ]]; then kill -KILL $pids 2>/dev/null || true; fi
  ip netns del "$ns" 2>/dev/null || true
}
trap cleanup EXIT
# Namespaces of soaks killed outright (their trap never ran) whose script is gone.
for old in $(ip netns list 2>/dev/null | awk '{print $1}' | grep '^swasoak[0-9]*$' || true); do
  kill -0 "${old#swasoak}" 2>/dev/null || ip netns del "$old" 2>/dev/null || true
done
ip netns add "$ns"
ip netns exec "$ns" ip link set lo up
ip netns exec "$ns" ip link set lo multicast on  # Fast DDS discovers over UDP multicast
ip netns exec "$ns" ip route add 224.0.0.0/4 dev lo

# ------------------------------------------------------------------------------------------------------ launch
run=$out/run
sets=(--set "uav_count=$uavs" --set clock.mode=realtime --set "duration_s=$duration" --set gnss.dropout_start_s=1e6)
[[ -n $gnss_windows ]] && sets+=(--set "gnss.windows=[$gnss_windows]")
note "launch: $uavs UAVs through $vehicle, ${duration} s realtime, recording, UDP only, namespace $ns"
ip netns exec "$ns" sh -c 'mount -t tmpfs -o size=256m,mode=1777 swa-soak-shm /dev/shm && exec "$@"' sh \
  env -u SWA_SECURITY_DIR -u SWA_DISCOVERY_SERVER -u SWA_TRANSPORT -u SWA_SWARM \
  "$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_8.yaml" "${sets[@]}" --vehicle "$vehicle" \
  --transport network --domain 0 --swarm "$SWARM" --record --max-restarts 1000 \
  --timeout-s $((duration + 600)) --out "$run" >"$out/launch.log" 2>&1 &
launch_pid=$!

# The processes of the run: pid and name (swa_sim, swa_monitor, agent_<I>, bridge_<I>), from the namespace.
processes() {
  local pid cmd
  for pid in $(ip netns pids "$ns" 2>/dev/null); do
    cmd=$({ tr '\0' ' ' <"/proc/$pid/cmdline"; } 2>/dev/null) || continue
    case $cmd in
      *swa_agent*--id*) [[ -n ${rogue_pid:-} && $pid == "$rogue_pid" ]] ||
                          echo "$pid agent_$(sed -E 's/.*--id ([0-9]+).*/\1/' <<<"$cmd")" ;;
      *swa_px4_bridge*--id*) echo "$pid bridge_$(sed -E 's/.*--id ([0-9]+).*/\1/' <<<"$cmd")" ;;
      *swa_sim*) echo "$pid swa_sim" ;;
      *swa_monitor*) echo "$pid swa_monitor" ;;
      *swa_launch*) echo "$pid swa_launch" ;;
    esac
  done
}
pid_of() { processes | awk -v n="$1" '$2 == n {print $1; exit}'; }
rss_csv=$out/rss.csv
echo "t_s,process,pid,rss_kb" >"$rss_csv"
sample_rss() {
  local pid name rss
  while read -r pid name; do
    rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null) || continue
    [[ -n $rss ]] && echo "$1,$name,$pid,$rss" >>"$rss_csv"
  done < <(processes)
}

# The clock starts when the simulator has discovered everyone: the schedule counts from there.
for _ in $(seq 1 1200); do
  grep -q "agent(s) discovered in" "$run/logs/sim.log" 2>/dev/null && break
  kill -0 "$launch_pid" 2>/dev/null || break
  sleep 0.1
done
grep -q "agent(s) discovered in" "$run/logs/sim.log" 2>/dev/null ||
  { tail -5 "$out/launch.log" >&2; fail "the simulator never started (see $out/launch.log)"; }
t0=$(date +%s.%N)
now_s() { awk -v a="$(date +%s.%N)" -v b="$t0" 'BEGIN { printf "%.1f", a - b }'; }
wait_until() {  # seconds since the clock started; false if the launch ended first
  while awk -v n="$(now_s)" -v t="$1" 'BEGIN { exit !(n < t) }'; do
    kill -0 "$launch_pid" 2>/dev/null || return 1
    sleep 0.2
  done
}

declare -A killed=()  # process name -> kills
rogue_pid=""
rogue_status=()
loss_counts=()
next_rss=0
mapfile -t schedule < <(tail -n +2 "$out/schedule.csv")
k=0
while kill -0 "$launch_pid" 2>/dev/null; do
  t=$(now_s)
  if awk -v n="$t" -v r="$next_rss" -v e="$((duration - 5))" 'BEGIN { exit !(n >= r && n < e) }'; then
    sample_rss "${t%.*}"
    next_rss=$((next_rss + 30))
  fi
  if ((k < ${#schedule[@]})); then
    IFS=, read -r ft kind uav win <<<"${schedule[k]}"
    if awk -v n="$t" -v f="$ft" 'BEGIN { exit !(n >= f) }'; then
      k=$((k + 1))
      case $kind in
        agent_kill|bridge_kill)
          name=$([[ $kind == agent_kill ]] && echo "agent_$uav" || echo "bridge_$uav")
          pid=$(pid_of "$name")
          if [[ -n $pid ]]; then
            kill -KILL "$pid" && killed[$name]=$((${killed[$name]:-0} + 1))
            note "t=$t s: $kind: SIGKILL $name (pid $pid)"
          else
            note "t=$t s: $kind: $name not running (restarting?): nothing killed"
          fi ;;
        monitor_restart)
          pid=$(pid_of swa_monitor)
          [[ -n $pid ]] && kill -KILL "$pid" && killed[swa_monitor]=$((${killed[swa_monitor]:-0} + 1))
          note "t=$t s: monitor_restart: SIGKILL swa_monitor (pid ${pid:-none})" ;;
        loss_burst)
          ip netns exec "$ns" "$bin/swa_netem" --queue "$QUEUE" --loss 0.30 --delay-ms 20 --jitter-ms 10 \
            --seed "$((seed + k))" >"$out/netem_$k.log" 2>&1 &
          netem_pid=$!
          for _ in $(seq 1 50); do grep -q "^swa_netem: queue" "$out/netem_$k.log" && break; sleep 0.1; done
          ip netns exec "$ns" iptables -A OUTPUT -p udp -j NFQUEUE --queue-num "$QUEUE"
          note "t=$t s: loss_burst: 30 % UDP loss for ${win} s"
          wait_until "$((ft + win))" || true
          ip netns exec "$ns" iptables -F OUTPUT  # the rule first: a queued datagram nobody reads is dropped
          kill -TERM "$netem_pid" 2>/dev/null || true
          wait "$netem_pid" 2>/dev/null || true
          netem_pid=""
          loss_counts+=("$(grep '^swa_netem: seen' "$out/netem_$k.log" || echo 'swa_netem: no count')")
          note "t=$(now_s) s: loss_burst over: ${loss_counts[-1]}" ;;
        gnss_window)
          note "t=$t s: gnss_window: every UAV without GNSS for ${win} s (scenario gnss.windows)" ;;
        rogue_agent)
          ip netns exec "$ns" env SWA_SWARM="$SWARM" SWA_TRANSPORT=network "$bin/swa_agent" --id "$uav" \
            --scenario "$run/scenario.yaml" --domain 0 >"$out/rogue_$k.log" 2>&1 &
          rogue_pid=$!
          note "t=$t s: rogue_agent: a second swa_agent --id $uav (pid $rogue_pid)"
          status=""
          for _ in $(seq 1 $((win * 5))); do
            kill -0 "$rogue_pid" 2>/dev/null || break
            sleep 0.2
          done
          if kill -0 "$rogue_pid" 2>/dev/null; then
            kill -KILL "$rogue_pid" 2>/dev/null || true
            wait "$rogue_pid" 2>/dev/null || true
            status="still running after ${win} s (killed)"
          else
            s=0
            wait "$rogue_pid" || s=$?
            status="exit $s"
          fi
          rogue_status+=("$status")
          rogue_pid=""
          note "t=$(now_s) s: rogue_agent: $status" ;;
      esac
      continue
    fi
  fi
  # The end sample: the processes are still flying 5 s before the end.
  if awk -v n="$t" -v e="$((duration - 5))" 'BEGIN { exit !(n >= e) }' && [[ -z ${end_sampled:-} ]]; then
    sample_rss "${t%.*}"
    end_sampled=1
  fi
  sleep 0.5
done
status=0
wait "$launch_pid" || status=$?
launch_pid=""
note "launch exited $status"
tail -n 3 "$out/launch.log"

# --------------------------------------------------------------------------------------------------- judgement
mapfile -t recordings < <(ls "$run"/run*.mcap 2>/dev/null)
[[ ${#recordings[@]} -gt 0 ]] || fail "no recording in $run"
"$bin/bench_record_reader" --stamps-per-second "${recordings[@]}" >"$out/stamps.json"
bad_commands=0
for f in "$run"/logs/bridge_*.log; do
  [[ -f $f ]] || continue
  n=$(grep -oE '[0-9]+ non-finite, [0-9]+ clamped' "$f" | awk '{s += $1 + $3} END {print s + 0}')
  bad_commands=$((bad_commands + n))
done
killed_list=""
for name in "${!killed[@]}"; do killed_list+="$name=${killed[$name]} "; done
python3 - "$out" "$run" "$duration" "$uavs" "$WARMUP_S" "$status" "$bad_commands" "$killed_list" \
  "${#rogue_status[@]}" "$(printf '%s;' "${rogue_status[@]:-}")" "$(printf '%s;' "${loss_counts[@]:-}")" <<'EOF'
import csv, json, sys
out, run, duration, uavs, warmup, status, bad = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), \
    int(sys.argv[5]), int(sys.argv[6]), int(sys.argv[7])
killed = dict(kv.split("=") for kv in sys.argv[8].split())
rogues = [s for s in sys.argv[10].split(";") if s]
losses = [s for s in sys.argv[11].split(";") if s]
problems = []

# Memory: the first sample at or after the warm-up, and the last, per process name.
rows = list(csv.DictReader(open(f"{out}/rss.csv")))
names = sorted({r["process"] for r in rows})
print(f"{'process':<12}{'pid start':>10}{'pid end':>9}{'RSS start [MB]':>16}{'RSS end [MB]':>14}{'growth':>9}  judged")
for n in names:
    mine = [r for r in rows if r["process"] == n]
    start = next((r for r in mine if int(r["t_s"]) >= warmup), None)
    end = mine[-1]
    if start is None:
        print(f"{n:<12} no sample after the {warmup} s warm-up")
        continue
    a, b = int(start["rss_kb"]) / 1024, int(end["rss_kb"]) / 1024
    same = start["pid"] == end["pid"] and n not in killed
    growth = (b - a) / a * 100 if a > 0 else 0.0
    verdict = "yes" if same else "no: restarted"
    if same and growth > 10.0:
        problems.append(f"{n}: RSS grew {growth:.1f} % (> 10 %)")
        verdict = "yes: > 10 %"
    print(f"{n:<12}{start['pid']:>10}{end['pid']:>9}{a:>16.1f}{b:>14.1f}{growth:>8.1f}%  {verdict}")

# Restarts: every kill restarted by the launcher (restarts.csv: a row per restart, uav -1 for the monitor?).
restarts = {}
try:
    for r in csv.DictReader(open(f"{run}/logs/restarts.csv")):
        restarts[r.get("process") or r.get("uav")] = restarts.get(r.get("process") or r.get("uav"), 0) + 1
except FileNotFoundError:
    pass
total_kills = sum(int(v) for v in killed.values())
total_restarts = sum(restarts.values())
print(f"kills {total_kills} ({', '.join(f'{k} {v}' for k, v in sorted(killed.items())) or 'none'}); "
      f"restarts the launcher recorded {total_restarts}")
if total_restarts < total_kills:
    problems.append(f"{total_kills} kills but {total_restarts} restarts recorded")

# Verdict.
summary = json.load(open(f"{run}/summary.json")) if status in (0, 1, 3) else {}
verdict = summary.get("verdict", f"none (exit {status})")
print(f"verdict {verdict} (swa_launch exit {status})")
if verdict not in ("PASS", "INCOMPLETE"):
    problems.append(f"verdict {verdict}")

# Rogue agents: each must have been refused (exit 3).
print(f"rogue agents {len(rogues)}: {', '.join(rogues) or '-'}")
problems += [f"a rogue agent: {s}" for s in rogues if s != "exit 3"]
print(f"loss bursts {len(losses)}: {'; '.join(losses) or '-'}")
print(f"bad commands (non-finite or clamped, every bridge) {bad}")
if bad:
    problems.append(f"{bad} bad commands")

# Recording completeness outside the fault windows.
schedule = list(csv.DictReader(open(f"{out}/schedule.csv")))
stamps = json.load(open(f"{out}/stamps.json"))
per_second = stamps["stamps_per_second"]
rate = 100  # dynamics.rate_hz of dropout_8.yaml: IMU and clock each step
expected = {"imu": rate, "state": 10, "/swa/clock": rate, "/swa/truth": rate // 10}
def in_window(second):
    return any(f["kind"] != "gnss_window" and int(f["t_s"]) - 2 <= second < int(f["t_s"]) + int(f["window_s"]) + 10
               for f in schedule)
def touches(f, topic):  # a fault excuses the topics it acts on: a kill only its own UAV's
    kind, uav = f["kind"], int(f["uav"])
    if kind in ("loss_burst", "monitor_restart"):
        return True
    return f"/uav{uav}/" in topic and (kind == "bridge_kill" or (kind == "agent_kill" and topic.endswith("/state")))
def side_effect(topic, second):  # in a window of a fault that should not touch this topic
    windows = [f for f in schedule if f["kind"] != "gnss_window" and
               int(f["t_s"]) - 2 <= second < int(f["t_s"]) + int(f["window_s"]) + 10]
    return bool(windows) and not any(touches(f, topic) for f in windows)
lost, side = {}, {}
judged = 0
for topic, seconds in per_second.items():
    leaf = topic.rsplit("/", 1)[-1] if "/uav" in topic else topic
    if leaf not in expected or ("/uav" in topic and int(topic.split("/uav")[1].split("/")[0]) >= uavs):
        continue
    for s in range(10, duration - 5):  # the first seconds: every process still settling in; the last: shutting down
        short = expected[leaf] - int(seconds.get(str(s), 0))
        if in_window(s):
            if short > 0 and side_effect(topic, s):
                side.setdefault(topic, []).append(f"{s} s: {short}")
            continue
        judged += 1
        if short > 0:
            lost.setdefault(topic, []).append(f"{s} s: {short}")
count = lambda d: sum(int(x.split(": ")[1]) for v in d.values() for x in v)
print(f"recording: {len(stamps['files'])} file(s), truncated {len(stamps['truncated'])}; {judged} topic-seconds judged "
      f"outside the fault windows, samples missing there: {count(lost)}"
      + (" (" + "; ".join(f"{t} at {', '.join(v[:4])}" for t, v in sorted(lost.items())[:6]) + ")" if lost else ""))
print(f"  inside the windows, on topics the fault should not touch (not judged): {count(side)}"
      + (" (" + "; ".join(f"{t} at {', '.join(v[:4])}" for t, v in sorted(side.items())[:6]) + ")" if side else ""))
if lost:
    problems.append(f"{count(lost)} recorded samples missing outside the fault windows")
json.dump({"judged_topic_seconds": judged, "missing": lost, "side_effects": side}, open(f"{out}/completeness.json", "w"), indent=1)
if problems:
    print("soak_faults: FAIL: " + "; ".join(problems))
    sys.exit(1)
print("soak_faults: every judged figure within issue #46's targets")
EOF
