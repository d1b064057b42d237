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
dry_run=0

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
  --dry-run         check the arguments, the programs in --bin-dir and the scenario with every override (up, run,
                    test), print what COMMAND would do, and exit 0; calls neither podman nor apt
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

# Installing podman and building the images (images.sh); checking a finished run against swa_batch (check_run.sh).
# shellcheck source=containers/images.sh
source "$here/images.sh"
# shellcheck source=containers/check_run.sh
source "$here/check_run.sh"

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

# What COMMAND would do, after the checks that need neither podman nor root: the programs the images carry, and the
# scenario with every override as the simulator's image would read it (the same --export-agent-config step as up).
dry_run() {
  local steps
  case $command in
    install) steps="apt-get install what is missing of podman, runc, netavark, aardvark-dns, iptables, debootstrap, podman-compose" ;;
    build) steps="install; the base image $base_image (once); images $(image_name '{agent,sim,monitor,bridge,batch}') from $bin_dir" ;;
    compose) steps="print the compose file for $compose_n UAV(s)" ;;
    up) steps="start project $project: $uavs agent(s) ($vehicle), $(basename "$scenario") with '$(swa_set)', run directory $run_dir" ;;
    wait) steps="wait at most $timeout_s s for the verdict of project $project, save the logs into $run_dir/logs, stop it" ;;
    down) steps="stop and remove the containers and the network of project $project" ;;
    run | test) steps="build; down; up ($uavs agent(s), $vehicle, $(basename "$scenario") with '$(swa_set)'); wait at most $timeout_s s; down" ;;
    *) die "unknown command '$command' (see --help)" ;;
  esac
  if [[ $command =~ ^(build|run|test)$ ]]; then require_binaries; fi
  if [ "$command" = compose ] || [[ $command =~ ^(up|run|test)$ && $uavs -ne 4 ]]; then
    bash "$here/gen-compose.sh" "${compose_n:-$uavs}" --vehicle "$vehicle" > /dev/null || die "no compose file"
  fi
  if [[ $command =~ ^(up|run|test)$ ]]; then
    [ -r "$scenario" ] || die "scenario $scenario not readable"
    [ -x "$bin_dir/swa_sim" ] || die "$bin_dir/swa_sim not found: it checks the scenario (pass --bin-dir)"
    local check set_args=() kv
    check=$(mktemp -d)
    temp_dirs+=("$check")
    for kv in $(swa_set); do set_args+=(--set "$kv"); done
    "$bin_dir/swa_sim" --scenario "$scenario" "${set_args[@]}" --export-agent-config "$check/agent.yaml" \
      > "$check/log" 2>&1 || {
      cat "$check/log" >&2
      die "scenario $scenario with overrides '$(swa_set)' rejected"
    }
  fi
  log "--dry-run: $command would: $steps"
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
    --dry-run) dry_run=1; shift ;;
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

[ "$dry_run" -eq 0 ] || {
  dry_run
  exit 0
}

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
