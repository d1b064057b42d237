#!/usr/bin/env bash
# External odometry (issue #43): does the swarm stay under SWA's control through autopilots that model their
# estimators, once GNSS is lost? Lockstep runs of the shipped GNSS-loss scenarios (GNSS lost at 10 s for good); not a
# ctest (the tests run one seed of each case, tests/px4/test_px4_swarm.cpp); results in BENCHMARKS.md.
#
#   bench_odometry.sh [BIN_DIR] [SEEDS] [DURATION_S]        (defaults: build/bin, "1 2 3", 120)
#
# For N = 4 and 8 UAVs and each seed: the run directly (no autopilot), then through the PX4 and the ArduPilot
# stand-ins with the feed on (vehicle.odometry = gnss-loss, the default) and off (vehicle.odometry = off: the bridges'
# --odometry off). A run without the feed lasts 30 s: the autopilots take over within 9 s of the loss.
# Per case, over the seeds: the verdict (runs that PASS), the largest |d_NB - d_NB direct| of the same seed, the
# collisions, the vehicles that left SWA's control (events.csv control_lost) and the latest time from the loss to it.
# Then, once per autopilot, a killed agent (realtime, 30 s, 4 UAVs, GNSS lost at 10 s, agent 2 killed about 16 s in,
# no restart): its bridge's odometry lines and UAV 2's events, to show that nothing is fed after the agent's last
# state and that the autopilot's own failsafes take the vehicle.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=${1:-$root/build/bin}
seeds=${2:-1 2 3}
duration=${3:-120}
work=$(mktemp -d /tmp/swa_bench_odometry.XXXXXX)
trap 'rm -rf "$work"' EXIT
for b in swa_launch swa_sim swa_agent swa_monitor swa_px4_bridge; do
  [ -x "$bin/$b" ] || fail "no $bin/$b (bash deploy/build.sh)"
done
reserve_test_domain 171

run() {  # run N SEED VEHICLE ODOMETRY DURATION
  local out=$work/$1_$2_$3_$4 status=0 sets=(--set "seed=$2" --set "duration_s=$5")
  [ "$3" = direct ] || sets+=(--set "vehicle.odometry=$4")  # an error for the direct interface
  "$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_$1.yaml" --vehicle "$3" "${sets[@]}" \
    --domain "$TEST_DOMAIN" --out "$out" > "$out.log" 2>&1 || status=$?
  # 0 PASS, 1 FAIL; anything else is the launch's own failure
  [ "$status" -le 1 ] || { tail -5 "$out.log" >&2; fail "run $1 UAVs seed $2 $3 odometry $4: status $status"; }
}

for n in 4 8; do
  for s in $seeds; do
    log "$n UAVs, seed $s"
    run "$n" "$s" direct gnss-loss "$duration"
    for v in px4 ardupilot; do
      run "$n" "$s" "$v" gnss-loss "$duration"
      run "$n" "$s" "$v" off 30
    done
  done
done

python3 - "$work" "$seeds" <<'EOF'
import csv, json, os, sys
work, seeds = sys.argv[1], sys.argv[2].split()
def summary(n, s, v, o):
    with open(os.path.join(work, f"{n}_{s}_{v}_{o}", "summary.json")) as f:
        return json.load(f)
def control_lost(n, s, v, o):
    with open(os.path.join(work, f"{n}_{s}_{v}_{o}", "events.csv")) as f:
        return [float(r["t_s"]) for r in csv.DictReader(f) if r["kind"] == "control_lost"]
print(f"{'UAVs':>4}  {'vehicle':>9}  {'feed':>4}  {'PASS':>5}  {'max |d_NB - direct| [m]':>24}  {'collisions':>10}  "
      f"{'left control':>12}  {'latest loss -> left [s]':>23}")
for n in (4, 8):
    for v in ("px4", "ardupilot"):
        for o in ("gnss-loss", "off"):
            passed, diffs, collisions, left, latest = 0, [], 0, 0, float("nan")
            for s in seeds:
                r = summary(n, s, v, o)
                passed += r["verdict"] == "PASS"
                collisions += int(r["collisions"])
                if o == "gnss-loss":
                    d = summary(n, s, "direct", "gnss-loss")["mean_neighbor_distance_m"]
                    diffs.append(abs(r["mean_neighbor_distance_m"] - d))
                lost = control_lost(n, s, v, o)
                left += len(lost)
                if lost:
                    latest = max(x - 10.0 for x in lost) if latest != latest else max(latest, *(x - 10.0 for x in lost))
            diff = f"{max(diffs):.4f}" if diffs else "-"
            print(f"{n:>4}  {v:>9}  {'on' if o == 'gnss-loss' else 'off':>4}  {passed:>2}/{len(seeds):<2}  {diff:>24}  "
                  f"{collisions:>10}  {left:>5}/{n * len(seeds):<6}  {'-' if latest != latest else f'{latest:.2f}':>23}")
print(f"(seeds {' '.join(seeds)}; GNSS lost at 10 s; runs with the feed off last 30 s)")
EOF

# A killed agent, in real time (the kill is a wall-clock event); the swarm's own partition keeps other runs out.
for v in px4 ardupilot; do
  out=$work/killed_$v
  "$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_4.yaml" --vehicle "$v" --set clock.mode=realtime \
    --set duration_s=30 --max-restarts 0 --domain "$TEST_DOMAIN" --out "$out" > "$out.log" 2>&1 &
  launcher=$!
  sleep 17
  pkill -f -- "swa_agent --id 2 --domain $TEST_DOMAIN " || log "no agent 2 to kill ($v)"
  wait "$launcher" || true
  echo "killed agent 2 through $v: bridge 2's odometry, UAV 2's events"
  grep -E "feeding the agent|odometry to .* stopped|not fusing" "$out/logs/bridge_2.log" | sed 's/^/  /'
  awk -F, 'NR > 1 && $3 == 2 && $2 != "gnss_lost" && $2 != "gnss_regained" && $2 != "control_regained"' \
    "$out/events.csv" | sed 's/^/  /'
done
