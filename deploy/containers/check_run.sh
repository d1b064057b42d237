# Sourced by deploy/containers.sh (its variables and log/die): the `test` command's comparison of a finished run
# with swa_batch's in-process loop.
# ------------------------------------------------------------------------------------------------------- test

# The same scenario, overrides and seed in swa_batch's in-process closed loop (host binary), into RUN/batch/.
# In lockstep the containers must reproduce it exactly, like the processes on one host do (tests/launch):
# containers, UDP and the bridge may change timing, never the experiment.
run_oracle() {
  rm -rf "$run_dir/batch"
  local args=(--scenario "$run_dir/scenario.yaml" --seeds 1 --out "$run_dir/batch") kv
  for kv in $(swa_set); do args+=(--set "$kv"); done
  "$bin_dir/swa_batch" "${args[@]}" > "$run_dir/logs/swa_batch.log" 2>&1 ||
    log "swa_batch failed (see $run_dir/logs/swa_batch.log)"
}

# Checks the finished run in RUN (monitor's exit code $1, down's $2); prints one line per check; returns 1 if any
# failed.
check_run() {
  local monitor_code=$1 down_code=$2
  python3 - "$run_dir" "$monitor_code" "$uavs" "$root" "$down_code" "$vehicle" <<'EOF'
import json, os, subprocess, sys

run_dir, monitor_code, uavs, root = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
down_code = int(sys.argv[5])
vehicle = sys.argv[6]
failures = 0

def check(ok, what):
    global failures
    print(("ok     " if ok else "FAILED ") + what)
    if not ok:
        failures += 1

def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        check(False, f"{path} readable JSON ({e})")
        return None

check(monitor_code == 0, f"monitor exit code 0 (PASS), got {monitor_code}")
s = load(os.path.join(run_dir, "monitor", "summary.json"))
if s is not None:
    r = s.get("formation_radius_m")
    d = s.get("mean_neighbor_distance_m")
    tol = 0.10
    check(s.get("verdict") == "PASS", f"summary.json verdict PASS, got {s.get('verdict')} {s.get('verdict_reasons')}")
    check(s.get("completed") is True, f"scenario completed (end_reason {s.get('end_reason')})")
    check(s.get("uav_count") == uavs, f"uav_count {uavs}, got {s.get('uav_count')}")
    check(r == 10.0, f"r = formation_radius_m 10 m, got {r}")
    ok = isinstance(d, (int, float)) and isinstance(r, (int, float)) and abs(d - r) <= tol * r
    check(ok, f"d_NB (mean_neighbor_distance_m, last 5 s) {d} m within r ± 10 % = [{0.9 * r if r else '?'}, "
              f"{1.1 * r if r else '?'}] m")
    check(s.get("collisions") == 0, f"collisions 0, got {s.get('collisions')} "
                                    f"(min_separation_m {s.get('min_separation_m')})")
    check(s.get("groups") == 1, f"one group, got {s.get('groups')}")
    check(isinstance(s.get("steps"), (int, float)) and s["steps"] > 0, f"scored steps > 0, got {s.get('steps')}")

sim = load(os.path.join(run_dir, "sim_summary.json"))
if sim is not None:
    check(sim.get("completed") is True, "simulator completed the scenario")
    check(sim.get("agent_dead_events") == 0 and sim.get("dead_at_end") == [],
          f"no agent declared dead (events {sim.get('agent_dead_events')}, dead at end {sim.get('dead_at_end')})")

codes = {}
try:
    with open(os.path.join(run_dir, "logs", "exit_codes")) as f:
        for line in f:
            name, code = line.split()
            codes[name] = int(code)
except OSError as e:
    check(False, f"exit codes recorded ({e})")
agents = sorted(k for k in codes if k.startswith("agent"))
check(len(agents) == uavs, f"{uavs} agent containers ran, got {len(agents)}")
check(codes.get("sim") == 0, f"simulator container exit code 0, got {codes.get('sim')}")
bad = {k: codes[k] for k in agents if codes[k] != 0}
check(not bad, f"every agent exited 0 on SIGTERM (clean DDS shutdown), not: {bad}")
if vehicle != "direct":
    bridges = sorted(k for k in codes if k.startswith("bridge"))
    check(len(bridges) == uavs, f"{uavs} bridge containers ran, got {len(bridges)}")
    bad = {k: codes[k] for k in bridges if codes[k] != 0}
    check(not bad, f"every bridge exited 0 on SIGTERM, not: {bad}")
    agents += bridges  # their /dev/shm is inspected too

shm = {}
for a in agents:
    try:
        with open(os.path.join(run_dir, "logs", "dev_shm." + a)) as f:
            shm[a] = f.read().split()
    except OSError:
        shm[a] = None
missing = [a for a in agents if shm[a] is None]
used = {a: v for a, v in shm.items() if v and any(x.startswith(("fastrtps", "sem.fastrtps")) for x in v)}
check(not missing and not used, "UDP only: no Fast DDS shared-memory segment in any running agent container"
      + (f" (not inspected: {missing})" if missing else "") + (f" (found: {used})" if used else ""))

batch_path = os.path.join(run_dir, "batch", "summary.json")
if s is not None and sim is not None and os.path.exists(batch_path):
    if sim.get("clock_mode") != "lockstep":
        print(f"skip   comparison with swa_batch: {sim.get('clock_mode')} runs are not deterministic")
    elif vehicle != "direct":
        # Through an autopilot its messages' float32 (PX4), the mode before the bridge engages it and the quaternion
        # for the attitude make it another run.
        b = load(batch_path)
        d_batch = b["runs"][0]["seeds"][0].get("mean_neighbor_distance_m") if b else None
        d = s.get("mean_neighbor_distance_m")
        ok = isinstance(d, (int, float)) and isinstance(d_batch, (int, float)) and abs(d - d_batch) <= 0.05
        check(ok, f"through {vehicle} in containers, d_NB {d} m within 0.05 m of swa_batch's direct loop ({d_batch} m)")
    else:
        b = load(batch_path)
        entry = b["runs"][0]["seeds"][0] if b else {}
        keys = [k for k in entry if k not in ("seed", "rejected_inputs")]
        differ = {k: (s.get(k, "missing"), entry[k]) for k in keys if s.get(k, "missing") != entry[k]}
        check(len(keys) >= 20 and not differ,
              f"lockstep in containers = swa_batch in one process, all {len(keys)} summary keys equal"
              + (f"; differ (containers, swa_batch): {differ}" if differ else ""))
else:
    check(False, f"swa_batch's summary for comparison ({batch_path})")

if uavs == 4:
    for name, extra in (("compose.yaml", []), ("compose-px4.yaml", ["--vehicle", "px4"]),
                        ("compose-ardupilot.yaml", ["--vehicle", "ardupilot"])):
        gen = subprocess.run(["bash", os.path.join(root, "deploy/containers/gen-compose.sh"), "4"] + extra,
                             capture_output=True, text=True, check=True).stdout
        with open(os.path.join(root, "deploy/containers", name)) as f:
            check(f.read() == gen, f"deploy/containers/{name} is what gen-compose.sh 4 {' '.join(extra)} writes")

check(down_code == 0, "every container and the network removed by down")

if s is not None and sim is not None:
    print(f"d_NB {s.get('mean_neighbor_distance_m')} m (r {s.get('formation_radius_m')} m), "
          f"min separation {s.get('min_separation_m')} m, collisions {s.get('collisions')}, groups {s.get('groups')}, "
          f"drift {s.get('drift_velocity_mps')} m/s, verdict {s.get('verdict')}; simulator: {sim.get('steps')} "
          f"steps in {sim.get('wall_time_s')} s wall, discovery {sim.get('discovery_s')} s, loop latency p50 / p99 "
          f"{sim.get('latency_p50_us')} / {sim.get('latency_p99_us')} us")
sys.exit(1 if failures else 0)
EOF
}
