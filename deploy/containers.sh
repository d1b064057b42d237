#!/usr/bin/env bash
# SWA in containers: one container per UAV (swa_agent), the simulator and the monitor on one bridge network,
# with podman (runc) from Debian 12 packages. See --help.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
here=$root/deploy/containers

# Our podman settings (runc, ulimits, cgroupfs) for every podman call of this script and of podman-compose,
# without touching the machine's own containers.conf.
export CONTAINERS_CONF=$here/containers.conf

base_image=localhost/swa-debian-base:bookworm
bin_dir=$root/build/bin
uavs=4
scenario=$root/deploy/scenarios/dropout_4.yaml
sets=()
run_dir=$root/out/containers
project=swa
timeout_s=600
rebuild_base=0
vehicle=direct

usage() {
  cat <<'EOF'
Usage: deploy/containers.sh COMMAND [options]

The swarm in containers (podman with runc, images from Debian 12 packages only, no registry needed):
swa_sim, one swa_agent container per UAV (its UAV id in SWA_UAV_ID) and swa_monitor on one bridge network,
talking UDPv4 only (SWA_TRANSPORT=network, multicast discovery, DDS domain 42).

Commands:
  install   apt-get install what is missing: podman, runc, netavark, aardvark-dns, iptables, debootstrap,
            podman-compose (root; apt is not contacted when nothing is missing)
  build     install, then the Debian base image (debootstrap + import, once; --rebuild-base to redo it), then the
            images localhost/swa-{agent,sim,monitor,bridge,batch}:latest with the binaries of --bin-dir
  compose N print the compose file for N UAVs (deploy/containers/compose.yaml is N = 4; with --vehicle px4 or
            ardupilot that variant, deploy/containers/compose-px4.yaml or compose-ardupilot.yaml for N = 4)
  up        start the swarm in the background (images must be built): writes RUN/agent.yaml for the scenario,
            then compose up
  wait      wait for the monitor's verdict (at most --timeout-s), stop the swarm, save every container's log
            and exit code in RUN/logs/; exit with the verdict
  down      stop (SIGTERM, 10 s grace) and remove the project's containers and its network
  run       build, down (leftovers of the project), up, wait, down; exit with the monitor's verdict
  test      run dropout_4.yaml for 60 s on 4 UAVs (unless --scenario / --set / --uavs say otherwise) and
            check cohesion in the monitor's summary.json: verdict PASS, d_NB within 10 % of r, no collision,
            one group; also the simulator's run (completed, no dead agent), clean agent exits, no shared memory
            used, and (lockstep) every summary key equal to swa_batch's for the same scenario and seed (needs
            swa_batch in --bin-dir). Exit 0 = pass

Options:
  --bin-dir DIR     where swa_agent, swa_sim, swa_monitor, swa_px4_bridge and swa_batch are (build; default
                    build/bin)
  --uavs N          number of agent containers (up, run, test; default 4); sets the scenario's uav_count to N
  --vehicle V       direct (default), px4 or ardupilot: one swa_px4_bridge container per UAV too (with
                    --autopilot ardupilot for ArduPilot), the simulator playing each UAV's autopilot
                    (vehicle.interface=V); test then compares d_NB with swa_batch's direct loop (within
                    0.05 m) instead of every summary key
  --scenario FILE   scenario YAML (default deploy/scenarios/dropout_4.yaml), copied into RUN
  --set key=value   scenario override for the simulator and the monitor alike (repeatable; no spaces)
  --run-dir DIR     run directory RUN (default out/containers): agent.yaml, scenario.yaml, compose.yaml,
                    monitor/ (summary.json, report.html, ...), sim_summary.json, logs/
  --project NAME    compose project (default swa): containers are NAME_<service>_1, the network NAME_swa
  --timeout-s S     wait / run / test: give up waiting for the verdict after S seconds (default 600)
  --rebuild-base    build: rebuild the base image even if present
  -h, --help        this text

Exit status: run / wait: 0 PASS, 1 FAIL, 3 INCOMPLETE (also: no verdict in time, simulator failed);
             test: 0 all checks passed, 1 a check failed; 2 bad arguments or a failed step before the run.

Examples:
  bash deploy/containers.sh run                                   # 4 UAVs, dropout_4.yaml, 120 s simulated
  bash deploy/containers.sh run --uavs 8 --scenario deploy/scenarios/dropout_8.yaml
  bash deploy/containers.sh up && bash deploy/containers.sh wait  # the same in two steps
  bash deploy/containers.sh test --bin-dir build/bin              # what ctest -L containers runs
  bash deploy/containers.sh run --vehicle px4                     # the same swarm through PX4 bridges
  bash deploy/containers.sh run --vehicle ardupilot               # ... through ArduPilot bridges
EOF
}

log() { echo "containers: $*" >&2; }

# Runs on every exit, also on errors and SIGTERM / SIGINT (ctest's timeout, Ctrl-C).
temp_dirs=()
down_on_exit=0
on_exit() {
  local rc=$?
  [ "$down_on_exit" -eq 0 ] || down || true
  [ ${#temp_dirs[@]} -eq 0 ] || rm -rf "${temp_dirs[@]}"
  return "$rc"
}
trap on_exit EXIT
die() {
  log "$*"
  exit 2
}

# ---------------------------------------------------------------------------------------------------- install

install_packages() {
  # runc named explicitly: podman depends on "crun | runc", and crun fails on this kind of host's cgroups.
  # netavark: podman's network stack; iptables: netavark's firewall rules; aardvark-dns: compose's service names.
  local packages=(podman runc netavark aardvark-dns iptables debootstrap debian-archive-keyring podman-compose
    python3)
  local missing=() p
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  [ "$(id -u)" -eq 0 ] || die "missing packages ${missing[*]}: run as root to install them"
  log "installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
}

# ------------------------------------------------------------------------------------------------------ build

image_name() { echo "localhost/swa-$1:latest"; }

build_images() {
  install_packages
  [ "$(id -u)" -eq 0 ] || die "build needs root (debootstrap, rootful podman)"
  local b
  for b in swa_agent swa_sim swa_monitor swa_px4_bridge swa_batch; do
    [ -x "$bin_dir/$b" ] || die "$bin_dir/$b not found: build first (bash deploy/build.sh) or pass --bin-dir"
  done
  # Inside a container only SWA_TRANSPORT=network keeps shared memory out; binaries from before it would try
  # shared memory between containers and silently test something else.
  # The help captured first: `grep -q` stops reading at the match, and the rest of a help longer than one pipe write
  # would end the program with SIGPIPE (a failed pipeline under pipefail).
  local help
  help=$("$bin_dir/swa_sim" --help 2>&1) || die "$bin_dir/swa_sim --help failed: rebuild the project"
  grep -q SWA_TRANSPORT <<<"$help" || die "$bin_dir/swa_sim does not know SWA_TRANSPORT: rebuild the project"

  local base_args=(--engine podman --image "$base_image")
  [ "$rebuild_base" -eq 0 ] || base_args+=(--rebuild)
  timeout 600 bash "$here/build-base.sh" "${base_args[@]}" || die "base image not built"

  local context
  context=$(mktemp -d /var/tmp/swa-image-context.XXXXXX)
  temp_dirs+=("$context")
  mkdir -p "$context/bin" "$context/scenarios"
  # install -m: the modes in the image must not depend on how the checkout or the build set them.
  install -m 0755 "$bin_dir/swa_agent" "$bin_dir/swa_sim" "$bin_dir/swa_monitor" "$bin_dir/swa_px4_bridge" \
    "$bin_dir/swa_batch" "$here/swa-entrypoint" "$context/bin/"
  install -m 0644 "$root/deploy/dds/profiles.xml" "$context/"
  install -m 0644 "$root"/deploy/scenarios/*.yaml "$context/scenarios/"

  local target start
  for target in agent sim monitor bridge batch; do
    start=$SECONDS
    # Host network for the build only: apt-get in the runtime stage must reach the Debian archive; the swarm
    # itself runs on its internal bridge.
    if ! timeout 600 podman build --network host --build-arg "BASE_IMAGE=$base_image" --target "$target" \
      -t "$(image_name "$target")" -f "$here/Dockerfile" "$context" > "$context/build-$target.log" 2>&1; then
      tail -n 40 "$context/build-$target.log" >&2
      die "image $target not built"
    fi
    log "image $(image_name "$target") ready ($((SECONDS - start)) s)"
  done
  rm -rf "$context"
}

# --------------------------------------------------------------------------------------------------- up/down

project_containers() { podman ps -a -q --filter "label=io.podman.compose.project=$project"; }

down() {
  local ids nets
  ids=$(project_containers)
  if [ -n "$ids" ]; then
    # SIGTERM first: every SWA process then deletes its DDS entities and exits 0; SIGKILL only after 10 s.
    # shellcheck disable=SC2086
    podman stop -t 10 $ids > /dev/null 2>&1 || true
    # shellcheck disable=SC2086
    podman rm -f $ids > /dev/null
  fi
  # podman-compose 1.0.3's own `down` leaves the network behind; remove it by the project label it set.
  nets=$(podman network ls -q --filter "label=io.podman.compose.project=$project")
  if [ -n "$nets" ]; then
    # shellcheck disable=SC2086
    podman network rm -f $nets > /dev/null
  fi
  if [ -n "$(project_containers)" ] ||
    [ -n "$(podman network ls -q --filter "label=io.podman.compose.project=$project")" ]; then
    log "project $project: containers or network still present after down"
    return 1
  fi
  if [ -n "$ids" ]; then
    log "project $project: down, $(echo "$ids" | wc -l) container(s) and the network removed"
  else
    log "project $project: down (nothing was running)"
  fi
}

# "uav_count=N" first, so the scenario runs exactly as many UAVs as there are agent containers; through an
# autopilot the interface too, so that a --set of an autopilot's key (vehicle.com_of_loss_t_s) is judged against it
# everywhere (the agents' exported configuration, swa_batch's reference run), not only in the simulator's container.
swa_set() {
  local all=("uav_count=$uavs")
  if [ "$vehicle" != direct ]; then all+=("vehicle.interface=$vehicle"); fi
  all+=(${sets[@]+"${sets[@]}"})
  echo "${all[*]}"
}

compose_file() {
  if [ "$uavs" -eq 4 ]; then
    if [ "$vehicle" = direct ]; then echo "$here/compose.yaml"; else echo "$here/compose-$vehicle.yaml"; fi
  else
    bash "$here/gen-compose.sh" "$uavs" --vehicle "$vehicle" > "$run_dir/compose.yaml"
    echo "$run_dir/compose.yaml"
  fi
}

# The images a run needs.
needed_images() { if [ "$vehicle" = direct ]; then echo agent sim monitor; else echo agent sim monitor bridge; fi; }

up() {
  install_packages
  local t
  for t in $(needed_images); do
    podman image exists "$(image_name "$t")" || die "image $(image_name "$t") missing: run deploy/containers.sh build"
  done
  [ -z "$(project_containers)" ] || die "project $project is already up: deploy/containers.sh down --project $project"
  [ -r "$scenario" ] || die "scenario $scenario not readable"

  mkdir -p "$run_dir"
  run_dir=$(cd "$run_dir" && pwd)
  rm -rf "$run_dir/monitor" "$run_dir/logs" "$run_dir/sim_summary.json" "$run_dir/agent.yaml" "$run_dir/compose.yaml"
  mkdir -p "$run_dir/logs"
  cp "$scenario" "$run_dir/scenario.yaml"
  local set_list
  set_list=$(swa_set)

  # The agents' parameters are the scenario's agent section, with the same overrides: written by the simulator's
  # image itself (no host binary needed), in a container without network.
  if ! podman run --rm --network none -v "$run_dir:/swa/run" -e SWA_SCENARIO=/swa/run/scenario.yaml \
    -e "SWA_SET=$set_list" "$(image_name sim)" --export-agent-config /swa/run/agent.yaml \
    > "$run_dir/logs/export-agent-config.log" 2>&1; then
    cat "$run_dir/logs/export-agent-config.log" >&2
    die "scenario $scenario with overrides '$set_list' rejected"
  fi

  local file
  file=$(compose_file)
  log "project $project: $uavs agent(s) ($vehicle), $(basename "$scenario") with '$set_list', run directory $run_dir"
  if ! SWA_RUN_DIR=$run_dir SWA_SCENARIO=/swa/run/scenario.yaml SWA_SET=$set_list \
    SWA_MONITOR_TIMEOUT_S=$timeout_s podman-compose -f "$file" -p "$project" up -d \
    > "$run_dir/logs/compose-up.log" 2>&1; then
    cat "$run_dir/logs/compose-up.log" >&2
    down || true
    die "compose up failed"
  fi
  # Counted, not required to be running: a short scenario can be over before compose up returns.
  local expected=$((uavs + 2)) created
  [ "$vehicle" = direct ] || expected=$((2 * uavs + 2))
  created=$(project_containers | wc -l)
  if [ "$created" -ne "$expected" ]; then
    cat "$run_dir/logs/compose-up.log" >&2
    down || true
    die "only $created of $expected containers created"
  fi
}

# ------------------------------------------------------------------------------------------------------- wait

state() { podman inspect --format '{{.State.Status}} {{.State.ExitCode}}' "$1" 2>/dev/null || echo "missing -1"; }

# Saves each container's log as RUN/logs/<service>.log and "<service> <exit code>" lines in RUN/logs/exit_codes.
save_logs() {
  local id service
  : > "$run_dir/logs/exit_codes"
  for id in $(project_containers); do
    service=$(podman inspect --format '{{index .Config.Labels "com.docker.compose.service"}}' "$id")
    podman logs "$id" > "$run_dir/logs/$service.log" 2>&1 || true
    echo "$service $(podman inspect --format '{{.State.ExitCode}}' "$id")" >> "$run_dir/logs/exit_codes"
  done
  sort -o "$run_dir/logs/exit_codes" "$run_dir/logs/exit_codes"
}

# Waits for the monitor's verdict; returns it (0 PASS, 1 FAIL, 3 INCOMPLETE).
wait_verdict() {
  mkdir -p "$run_dir/logs"
  local monitor=${project}_monitor_1 sim=${project}_sim_1
  local deadline=$((SECONDS + timeout_s)) verdict=3 m s s_code
  while :; do
    read -r m _ <<< "$(state "$monitor")"
    [ "$m" = running ] || break
    read -r s s_code <<< "$(state "$sim")"
    if [ "$s" != running ] && [ "$s_code" != 0 ]; then
      # The monitor would wait for an end event that never comes: stop it, it then writes its INCOMPLETE report.
      log "simulator exited with $s_code before the end of the scenario: stopping the monitor"
      podman stop -t 10 "$monitor" > /dev/null || true
    elif [ "$SECONDS" -ge "$deadline" ]; then
      log "no verdict within $timeout_s s: stopping the monitor"
      podman stop -t 10 "$monitor" > /dev/null || true
    fi
    sleep 1
  done
  read -r m verdict <<< "$(state "$monitor")"
  [ "$m" != missing ] || {
    log "monitor container $monitor not found"
    verdict=3
  }
  # The simulator exits right after the end event and its writers are acknowledged (seconds at most).
  local sim_deadline=$((SECONDS + 30))
  while [ "$(state "$sim" | cut -d' ' -f1)" = running ] && [ "$SECONDS" -lt "$sim_deadline" ]; do sleep 1; done
  # Evidence of the transport: Fast DDS's shared-memory transport leaves fastrtps_* segments in the container's
  # /dev/shm while a participant uses it; with SWA_TRANSPORT=network there must be none.
  local id service
  for id in $(podman ps -q --filter "label=io.podman.compose.project=$project"); do
    service=$(podman inspect --format '{{index .Config.Labels "com.docker.compose.service"}}' "$id")
    podman exec "$id" ls -A /dev/shm > "$run_dir/logs/dev_shm.$service" 2>&1 || true
  done
  # Agents run until SIGTERM: stop everything now so that their exit codes tell whether they shut down cleanly.
  local ids
  ids=$(project_containers)
  # shellcheck disable=SC2086
  [ -z "$ids" ] || podman stop -t 10 $ids > /dev/null 2>&1 || true
  save_logs
  case $verdict in
    0) log "verdict PASS" ;;
    1) log "verdict FAIL" ;;
    3) log "verdict INCOMPLETE" ;;
    *)
      log "monitor exited with $verdict (no verdict)"
      verdict=3
      ;;
  esac
  log "monitor report: $run_dir/monitor/report.html; logs and exit codes: $run_dir/logs/"
  return "$verdict"
}

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

# ------------------------------------------------------------------------------------------------------- main

[ $# -ge 1 ] || {
  usage >&2
  exit 2
}
command=$1
shift
case $command in
  -h|--help|help) usage; exit 0 ;;
esac
compose_n=
if [ "$command" = compose ]; then
  [ $# -ge 1 ] || die "compose needs the number of UAVs"
  compose_n=$1
  shift
fi
while [ $# -gt 0 ]; do
  case $1 in
    --bin-dir | --uavs | --scenario | --set | --run-dir | --project | --timeout-s | --vehicle)
      [ $# -ge 2 ] || die "$1 needs a value (see --help)" ;;
  esac
  case $1 in
    --bin-dir) bin_dir=$2; shift 2 ;;
    --uavs) uavs=$2; shift 2 ;;
    --vehicle) vehicle=$2; shift 2 ;;
    --scenario) scenario=$2; shift 2 ;;
    --set) sets+=("$2"); shift 2 ;;
    --run-dir) run_dir=$2; shift 2 ;;
    --project) project=$2; shift 2 ;;
    --timeout-s) timeout_s=$2; shift 2 ;;
    --rebuild-base) rebuild_base=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
[[ $uavs =~ ^[1-9][0-9]*$ ]] || die "--uavs must be a positive integer, got '$uavs'"
[[ $vehicle =~ ^(direct|px4|ardupilot)$ ]] || die "--vehicle must be direct, px4 or ardupilot, got '$vehicle'"
[[ $timeout_s =~ ^[1-9][0-9]*$ ]] || die "--timeout-s must be a positive integer, got '$timeout_s'"
[[ $project =~ ^[a-z0-9][a-z0-9_-]*$ ]] || die "--project must match [a-z0-9][a-z0-9_-]*, got '$project'"
for kv in ${sets[@]+"${sets[@]}"}; do
  [[ $kv =~ ^[A-Za-z0-9_.]+=[^[:space:]]+$ ]] || die "--set '$kv' is not key=value without spaces"
  [[ $kv != uav_count=* ]] || die "--set uav_count: use --uavs N (it sets uav_count and the number of agents)"
  [[ $kv != vehicle.interface=* ]] || die "--set vehicle.interface: use --vehicle (it also starts the bridges)"
done

case $command in
  install) install_packages ;;
  build) build_images ;;
  compose) bash "$here/gen-compose.sh" "$compose_n" --vehicle "$vehicle" ;;
  up) up ;;
  wait)
    rc=0
    wait_verdict || rc=$?
    exit "$rc"
    ;;
  down) down ;;
  run | test)
    if [ "$command" = test ]; then
      [ ${#sets[@]} -gt 0 ] || sets=(duration_s=60)
      [ -x "$bin_dir/swa_batch" ] || die "$bin_dir/swa_batch not found: test compares the run with it"
    fi
    build_images
    down
    down_on_exit=1
    up
    rc=0
    wait_verdict || rc=$?
    if [ "$command" = run ]; then
      exit "$rc"
    fi
    rc_down=0
    down || rc_down=$?
    down_on_exit=0
    run_oracle
    rc_check=0
    check_run "$rc" "$rc_down" || rc_check=$?
    exit "$rc_check"
    ;;
  *) die "unknown command '$command' (see --help)" ;;
esac
