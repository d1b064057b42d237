#!/usr/bin/env bash
# The bridge hop (issue #13): what going through PX4's topics and one swa_px4_bridge per UAV adds to the control loop,
# measured in realtime runs of the shipped scenarios (not a ctest; results in BENCHMARKS.md).
#
#   bench_px4_bridge.sh [BIN_DIR] [DURATION_S] [ROUNDS]     (defaults: build/bin, 30, 3)
#
# For N = 4 and 8 UAVs, ROUNDS times each, in turn: a direct run and a run through PX4, DURATION_S simulated seconds
# each in realtime. Per run:
#   - the simulator's loop latency (sim_summary.json, p50 / p99 over every UAV): direct, IMU published -> cmd_vel
#     received; through PX4, vehicle_attitude published -> trajectory_setpoint received;
#   - in the PX4 run, each bridge's own timing (logs/bridge_<i>_summary.json, the median over the bridges): attitude
#     in -> setpoint out, of which the agent's loop (imu out -> cmd_vel in, as on the direct interface) and the
#     bridge's part (the difference), all in the same run.
# The table shows the median over the rounds of each figure, and the ratio PX4 / direct of the simulator's loop.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=${1:-$root/build/bin}
duration=${2:-30}
rounds=${3:-3}
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
    run "$n" px4 "$r"
  done
done

python3 - "$work" "$rounds" <<'EOF'
import glob, json, os, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
def load(p):
    with open(p) as f:
        return json.load(f)
print(f"{'UAVs':>4}  {'loop direct p50/p99 [us]':>25}  {'loop via PX4 p50/p99 [us]':>26}  {'ratio p50':>9}  "
      f"{'bridge: in->out p50/p99':>24}  {'agent p50/p99':>14}  {'bridge part p50/p99':>20}")
for n in (4, 8):
    rows = []
    for r in range(1, rounds + 1):
        d = load(os.path.join(work, f"{n}_direct_{r}", "sim_summary.json"))
        p = load(os.path.join(work, f"{n}_px4_{r}", "sim_summary.json"))
        bridges = [load(f) for f in glob.glob(os.path.join(work, f"{n}_px4_{r}", "logs", "bridge_*_summary.json"))]
        med = lambda key: statistics.median(b[key] for b in bridges)
        rows.append((d["latency_p50_us"], d["latency_p99_us"], p["latency_p50_us"], p["latency_p99_us"],
                     med("hop_p50_us"), med("hop_p99_us"), med("agent_loop_p50_us"), med("agent_loop_p99_us"),
                     med("bridge_part_p50_us"), med("bridge_part_p99_us"), p["latency_p50_us"] / d["latency_p50_us"]))
    m = [statistics.median(col) for col in zip(*rows)]
    print(f"{n:>4}  {m[0]:>12.0f} / {m[1]:<10.0f}  {m[2]:>13.0f} / {m[3]:<10.0f}  {m[10]:>9.2f}  "
          f"{m[4]:>11.0f} / {m[5]:<10.0f}  {m[6]:>5.0f} / {m[7]:<6.0f}  {m[8]:>8.0f} / {m[9]:<9.0f}")
print(f"(median of {rounds} rounds per row; each round a direct and a PX4 run of the same scenario in turn)")
EOF
