#!/usr/bin/env bash
# The bridge hop (issues #13, #27): what going through an autopilot's topics and one swa_px4_bridge per UAV adds to the
# control loop, measured in realtime runs of the shipped scenarios (not a ctest; results in BENCHMARKS.md).
#
#   bench_px4_bridge.sh [BIN_DIR] [DURATION_S] [ROUNDS] [VEHICLES]     (defaults: build/bin, 30, 3, "px4 ardupilot")
#
# For N = 4 and 8 UAVs, ROUNDS times each, in turn: a direct run and a run through each of VEHICLES, DURATION_S
# simulated seconds each in realtime. Per run:
#   - the simulator's loop latency (sim_summary.json, p50 / p99 over every UAV): direct, IMU published -> cmd_vel
#     received; through PX4, vehicle_attitude published -> trajectory_setpoint received; through ArduPilot, the IMU
#     message published -> cmd_vel received;
#   - in a run through an autopilot, each bridge's own timing (logs/bridge_<i>_summary.json, the median over the
#     bridges): attitude in -> setpoint out, of which the agent's loop (imu out -> cmd_vel in, as on the direct
#     interface) and the bridge's part (the difference), all in the same run.
# The table shows the median over the rounds of each figure, and the ratio to direct of the simulator's loop (pairs of
# the same round).
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=${1:-$root/build/bin}
duration=${2:-30}
rounds=${3:-3}
vehicles=${4:-px4 ardupilot}
work=$(mktemp -d /tmp/swa_bench_px4.XXXXXX)
trap 'rm -rf "$work"' EXIT

for b in swa_launch swa_sim swa_agent swa_monitor swa_px4_bridge; do
  [ -x "$bin/$b" ] || { echo "bench_px4_bridge: no $bin/$b (bash deploy/build.sh)" >&2; exit 2; }
done

run() {  # run N VEHICLE ROUND
  local out=$work/$1_$2_$3
  "$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_$1.yaml" --vehicle "$2" \
    --set "duration_s=$duration" --set clock.mode=realtime --domain "$((150 + $3))" --out "$out" > "$out.log" 2>&1 ||
    { echo "bench_px4_bridge: run $1 $2 $3 failed:" >&2; tail -5 "$out.log" >&2; exit 1; }
}

for n in 4 8; do
  for ((r = 1; r <= rounds; r++)); do
    run "$n" direct "$r"
    for v in $vehicles; do run "$n" "$v" "$r"; done
  done
done

python3 - "$work" "$rounds" $vehicles <<'EOF'
import glob, json, os, statistics, sys
work, rounds, vehicles = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
def load(p):
    with open(p) as f:
        return json.load(f)
print(f"{'UAVs':>4}  {'vehicle':>9}  {'loop direct p50/p99 [us]':>25}  {'loop via it p50/p99 [us]':>25}  "
      f"{'ratio p50':>9}  {'bridge: in->out p50/p99':>24}  {'agent p50/p99':>14}  {'bridge part p50/p99':>20}")
for n in (4, 8):
    for v in vehicles:
        rows = []
        for r in range(1, rounds + 1):
            d = load(os.path.join(work, f"{n}_direct_{r}", "sim_summary.json"))
            p = load(os.path.join(work, f"{n}_{v}_{r}", "sim_summary.json"))
            bridges = [load(f) for f in glob.glob(os.path.join(work, f"{n}_{v}_{r}", "logs", "bridge_*_summary.json"))]
            med = lambda key: statistics.median(b[key] for b in bridges)
            rows.append((d["latency_p50_us"], d["latency_p99_us"], p["latency_p50_us"], p["latency_p99_us"],
                         med("hop_p50_us"), med("hop_p99_us"), med("agent_loop_p50_us"), med("agent_loop_p99_us"),
                         med("bridge_part_p50_us"), med("bridge_part_p99_us"),
                         p["latency_p50_us"] / d["latency_p50_us"]))
        m = [statistics.median(col) for col in zip(*rows)]
        print(f"{n:>4}  {v:>9}  {m[0]:>12.0f} / {m[1]:<10.0f}  {m[2]:>12.0f} / {m[3]:<10.0f}  {m[10]:>9.2f}  "
              f"{m[4]:>11.0f} / {m[5]:<10.0f}  {m[6]:>5.0f} / {m[7]:<6.0f}  {m[8]:>8.0f} / {m[9]:<9.0f}")
print(f"(median of {rounds} rounds per row; each round a direct run and one through each vehicle, in turn)")
EOF
