#!/usr/bin/env bash
# Multi-host without multiple hosts (issue #5, ctest label `netns`).
#
# Every agent runs in a network namespace of its own, the simulator and the monitor share another one, the Fast DDS
# Discovery Server has a third; all hang off one Linux bridge through veth pairs, so every sample and every discovery
# message between them crosses a real (virtual) Ethernet segment, like separate hosts on a LAN.
#
#   1. multicast          SWA_TRANSPORT=network: UDPv4 only, SPDP multicast discovery across the bridge
#   2. multicast blocked  an nftables `bridge` rule drops IPv4 multicast on the bridge; the same multicast run must
#                         now fail to discover any agent within a short startup timeout (proof that the block works)
#   3. discovery server   SWA_TRANSPORT=discovery-server, block still in place: discovery through
#                         fast-discovery-server, unicast only
#
# Cases 1 and 3 must stay cohesive: swa_monitor exits 0 (PASS), its summary.json has d_NB within ±10 % of r = 10 m,
# 0 collisions, one group, and the simulator saw no agent die.
#
# Usage: netns_swarm.sh BIN_DIR SOURCE_DIR [OUT_DIR]
#   BIN_DIR     directory with swa_sim, swa_agent, swa_monitor (built with SWA_TRANSPORT support)
#   SOURCE_DIR  the repository (for deploy/scenarios/dropout_4.yaml)
#   OUT_DIR     logs, monitor outputs and summaries (default ./netns-out); kept after the run for inspection
# Environment: SWA_NETNS_DURATION_S (simulated seconds per cohesive run, default 40).
# Needs root (network namespaces, bridge, nftables, tmpfs mounts). Installs missing Debian packages with apt-get.
#
# Isolation from anything else on the machine: the bridge and every veth live inside namespaces named after this
# script's PID, nothing is added to the host's own network namespace, and each process gets a private tmpfs on
# /dev/shm, so Fast DDS shared memory can neither connect two "hosts" nor leave files in the host's /dev/shm.
# An EXIT trap stops every process and deletes every namespace (with them the bridge, the veths and the nftables
# table); a later run also removes namespaces left by a run that was killed outright (SIGKILL skips the trap).

# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"

readonly NS_TAG=swant                     # namespace names: swant<PID>-<role>
readonly SUBNET=10.77.0                   # private to this run's bridge: no route to it exists outside
readonly SIM_IP=$SUBNET.1
readonly DS_IP=$SUBNET.2
readonly DS_PORT=11811
readonly FORMATION_RADIUS_M=10            # dropout_4.yaml: formation.spacing_m
readonly TOLERANCE=0.10
readonly STARTUP_TIMEOUT_S=30             # cohesive runs: generous, discovery normally takes about a second
readonly PROOF_TIMEOUT_S=10               # blocked run: at least twice what unblocked discovery is allowed to take
readonly STOP_GRACE_S=12                  # agents wait up to the 4 s participant lease for unacknowledged writers
readonly RUN_TIMEOUT_S=90                 # wall bound for one simulator / monitor run (about 2 s here)

BIN_DIR=""
SRC_DIR=""
OUT_DIR=""
SCENARIO=""
DURATION_S=""
N_AGENTS=0
DOMAIN=0
RUN_ID=""
HUB_NS=""
SIM_NS=""
DS_NS=""
NFT_TABLE=""
AGENT_NS=()
AGENT_PIDS=()
DS_PID=""
MULTICAST_DISCOVERY_S=""
CASE_DISCOVERY_S=""
MY_NAMESPACES=()                          # created by this run, deleted by cleanup
declare -A PROC_LABEL=()                  # pid -> label of every process this run started and has not reaped
RESULTS=()
CASE_ENV=()
LAST_PID=0
T_START=$SECONDS

# ---------------------------------------------------------------------------------------------------------- output

TEST_TAG=netns
section() { printf '\nnetns: ===== %s =====\n' "$*"; }
equals() { [[ $1 == "$2" ]]; }

# ------------------------------------------------------------------------------------------------- prerequisites

parse_args() {
  if [[ $# -lt 2 || $# -gt 3 ]]; then
    sed -n '/^# Usage:/,/^# Environment:/p' "$0" >&2
    exit 2
  fi
  BIN_DIR=$(cd "$1" && pwd)
  SRC_DIR=$(cd "$2" && pwd)
  OUT_DIR=${3:-$PWD/netns-out}
  SCENARIO=$SRC_DIR/deploy/scenarios/dropout_4.yaml
  DURATION_S=${SWA_NETNS_DURATION_S:-40}
  [[ -f $SCENARIO ]] || die "scenario $SCENARIO not found"
  N_AGENTS=$(awk '/^uav_count:/ { print $2 }' "$SCENARIO")
  [[ $N_AGENTS =~ ^[0-9]+$ && $N_AGENTS -ge 2 && $N_AGENTS -le 200 ]] || die "no usable uav_count in $SCENARIO"
  RUN_ID=$NS_TAG$$
  # The namespaces keep this run's traffic private already; a PID-derived domain is a second fence against any other
  # run. 1..232: the range Fast DDS's UDP port formula allows.
  DOMAIN=$(($$ % 232 + 1))
  HUB_NS=$RUN_ID-hub
  SIM_NS=$RUN_ID-sim
  DS_NS=$RUN_ID-ds
  NFT_TABLE=swa_netns_$$
  local i
  for ((i = 0; i < N_AGENTS; i++)); do AGENT_NS+=("$RUN_ID-a$i"); done
}

install_missing() {
  [[ $(id -u) -eq 0 ]] || die "needs root (network namespaces, bridge, nftables); run as root"
  local -A need=([ip]=iproute2 [nft]=nftables [jq]=jq [ping]=iputils-ping [fast-discovery-server]=fastdds-tools)
  local tool packages=()
  for tool in "${!need[@]}"; do command -v "$tool" >/dev/null 2>&1 || packages+=("${need[$tool]}"); done
  [[ ${#packages[@]} -eq 0 ]] && return 0
  log "installing missing Debian packages: ${packages[*]}"
  export DEBIAN_FRONTEND=noninteractive
  if ! apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null; then
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
  fi
  for tool in "${!need[@]}"; do command -v "$tool" >/dev/null 2>&1 || die "$tool still missing after apt-get"; done
}

check_binaries() {
  local b help
  for b in swa_sim swa_agent swa_monitor; do
    [[ -x $BIN_DIR/$b ]] || die "$BIN_DIR/$b not found or not executable (build first)"
  done
  # Every node documents the variables it honours in --help; a binary from before SWA_TRANSPORT would silently run
  # the default transport (shared memory + UDP) and the test would not test what it claims.
  for b in swa_sim swa_agent swa_monitor; do
    # Captured first: `grep -q` stops reading at the match, and a longer help would end the program with SIGPIPE.
    help=$("$BIN_DIR/$b" --help 2>&1) || die "$BIN_DIR/$b --help failed"
    grep -q SWA_TRANSPORT <<<"$help" ||
      die "$BIN_DIR/$b does not know SWA_TRANSPORT (built before the transport profiles of issue #5?)"
  done
}

# --------------------------------------------------------------------------------------------------- processes

alive() {
  local state
  state=$(sed 's/.*) //' "/proc/$1/stat" 2>/dev/null | cut -d' ' -f1) || return 1
  [[ -n $state && $state != Z ]]
}

# spawn LABEL NS LOG CMD...: starts CMD in namespace NS in the background with the case's environment; LAST_PID is
# its PID (ip netns exec, sh and env all exec, so it is the program's own PID). The tmpfs on /dev/shm lives in the
# mount namespace `ip netns exec` creates for the process and disappears with it.
spawn() {
  local label=$1 ns=$2 logfile=$3
  shift 3
  ip netns exec "$ns" sh -c 'mount -t tmpfs -o size=64m,mode=1777 swa-netns-shm /dev/shm && exec "$@"' sh \
    env -u ROS_DISCOVERY_SERVER -u SWA_SECURITY_DIR -u SWA_DISCOVERY_SERVER \
    SWA_DOMAIN="$DOMAIN" "${CASE_ENV[@]}" "$@" >"$logfile" 2>&1 &
  LAST_PID=$!
  PROC_LABEL[$LAST_PID]=$label
}

# wait_exit PID SECONDS: the process's exit status, 124 if it is still running after SECONDS.
wait_exit() {
  local pid=$1 deadline=$((SECONDS + $2)) rc=0
  while alive "$pid"; do
    ((SECONDS < deadline)) || return 124
    sleep 0.1
  done
  wait "$pid" 2>/dev/null || rc=$?
  unset "PROC_LABEL[$pid]"
  return "$rc"
}

# stop PID...: SIGTERM (SIGINT for the discovery server, which handles only that), a bounded wait, then SIGKILL.
stop() {
  local pid deadline=$((SECONDS + STOP_GRACE_S)) any
  for pid in "$@"; do
    if alive "$pid"; then
      if [[ ${PROC_LABEL[$pid]:-} == discovery-server ]]; then kill -INT "$pid" 2>/dev/null || true; else
        kill -TERM "$pid" 2>/dev/null || true
      fi
    fi
  done
  while :; do
    any=0
    for pid in "$@"; do if alive "$pid"; then any=1; fi; done
    ((any && SECONDS < deadline)) || break
    sleep 0.1
  done
  for pid in "$@"; do
    if alive "$pid"; then
      log "  ${PROC_LABEL[$pid]:-pid $pid} did not stop within ${STOP_GRACE_S} s: SIGKILL"
      kill -KILL "$pid" 2>/dev/null || true
    fi
    wait "$pid" 2>/dev/null || true
    unset "PROC_LABEL[$pid]"
  done
}

stop_all() {
  local pids=("${!PROC_LABEL[@]}")
  [[ ${#pids[@]} -eq 0 ]] || stop "${pids[@]}"
}

# Fast DDS shared-memory files in the private /dev/shm of a running process (seen through /proc/PID/root).
shm_files() {
  local pid=$1
  find "/proc/$pid/root/dev/shm" -maxdepth 1 \( -name 'fastrtps_*' -o -name 'sem.fastrtps_*' \) 2>/dev/null | wc -l
}

# ------------------------------------------------------------------------------------------------------ network

# Namespaces of an earlier run of this script whose shell is gone: it was killed before its trap could run. Anything
# still running in them was started by that run.
remove_stale_namespaces() {
  local ns owner pid
  while read -r ns _; do
    [[ $ns =~ ^${NS_TAG}([0-9]+)- ]] || continue
    owner=${BASH_REMATCH[1]}
    if [[ $owner != "$$" ]] && kill -0 "$owner" 2>/dev/null; then continue; fi
    for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
    if ip netns del "$ns" 2>/dev/null; then
      log "removed namespace $ns left by an earlier run (pid $owner) that was killed"
    fi
  done < <(ip netns list 2>/dev/null)
  return 0
}

add_namespace() {
  ip netns add "$1" || die "cannot create network namespace $1 (needs root and CAP_SYS_ADMIN)"
  MY_NAMESPACES+=("$1")
  ip -n "$1" link set lo up
}

# attach NS PORT IP: a veth pair from the bridge (port PORT in the hub) to eth0 in NS, with a multicast route.
attach() {
  local ns=$1 port=$2 ip=$3
  add_namespace "$ns"
  ip -n "$HUB_NS" link add "$port" type veth peer name eth0 netns "$ns"
  ip -n "$HUB_NS" link set "$port" master br0 up
  ip -n "$ns" addr add "$ip/24" dev eth0
  ip -n "$ns" link set eth0 up
  # A participant sends SPDP to 239.255.0.1; without a route for it the send fails with ENETUNREACH.
  ip -n "$ns" route add 224.0.0.0/4 dev eth0
}

setup_network() {
  add_namespace "$HUB_NS"
  # Snooping off: the bridge floods multicast to every port, like a plain switch; with IGMP snooping and no querier
  # delivery would depend on report timing.
  ip -n "$HUB_NS" link add br0 type bridge mcast_snooping 0 stp_state 0
  ip -n "$HUB_NS" link set br0 up
  attach "$SIM_NS" vsim "$SIM_IP"
  attach "$DS_NS" vds "$DS_IP"
  local i
  for ((i = 0; i < N_AGENTS; i++)); do attach "${AGENT_NS[$i]}" "va$i" "$(agent_ip "$i")"; done

  # Accounting only (policy accept), ahead of the block added later: the UDP multicast offered to the bridge is
  # Fast DDS's SPDP (239.255.0.1); the rest of the IPv4 multicast is the kernel's IGMP reports.
  ip netns exec "$HUB_NS" nft -f - <<EOF
table bridge $NFT_TABLE {
  chain forward {
    type filter hook forward priority 0; policy accept;
    ip daddr 224.0.0.0/4 ip protocol udp counter comment "udp-multicast"
  }
}
EOF

  # Participants enumerate interfaces when they are created: every link must be up before any process starts.
  local ns deadline=$((SECONDS + 10))
  for ns in "$SIM_NS" "$DS_NS" "${AGENT_NS[@]}"; do
    until ip -n "$ns" link show eth0 | grep -q 'state UP'; do
      ((SECONDS < deadline)) || die "eth0 in $ns did not come up"
      sleep 0.1
    done
  done
  local ok=0
  for ((i = 0; i < N_AGENTS; i++)); do
    if ip netns exec "$SIM_NS" ping -c 1 -W 2 -q "$(agent_ip "$i")" >/dev/null 2>&1; then ok=$((ok + 1)); fi
  done
  check "unicast sim namespace -> every agent namespace (ping)" "$ok/$N_AGENTS answered" equals "$ok" "$N_AGENTS"
  log "bridge br0 in $HUB_NS; $SIM_NS ($SIM_IP: swa_sim, swa_monitor), $DS_NS ($DS_IP: discovery server),"
  log "agents ${AGENT_NS[0]}..${AGENT_NS[$((N_AGENTS - 1))]} ($(agent_ip 0)..$(agent_ip $((N_AGENTS - 1)))); DDS domain $DOMAIN"
}

agent_ip() { echo "$SUBNET.$((10 + $1))"; }

# nft_counter COMMENT: packets counted by the rule with that comment (0 for a rule not installed yet).
nft_counter() {
  ip netns exec "$HUB_NS" nft -j list table bridge "$NFT_TABLE" |
    jq -r --arg c "$1" '[.nftables[] | .rule? | select(. != null and .comment == $c) | .expr[] | .counter? |
      select(. != null) | .packets] | first // 0'
}

block_multicast() {
  ip netns exec "$HUB_NS" nft add rule bridge "$NFT_TABLE" forward ip daddr 224.0.0.0/4 counter drop \
    comment '"multicast-blocked"'
  log "installed: nft bridge table $NFT_TABLE, chain forward: ip daddr 224.0.0.0/4 counter drop"
}

cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  set +e
  stop_all
  local ns pid
  for ns in "${MY_NAMESPACES[@]}"; do
    # Anything still inside is ours (e.g. a process whose PID the script lost when it was interrupted).
    for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
  done
  if [[ -n $HUB_NS ]]; then ip netns exec "$HUB_NS" nft delete table bridge "$NFT_TABLE" 2>/dev/null; fi
  # Deleting the hub deletes the bridge and the hub ends of the veths; deleting the others, their eth0 ends.
  for ns in "${MY_NAMESPACES[@]}"; do ip netns del "$ns" 2>/dev/null || true; done
  local left
  left=$(ip netns list 2>/dev/null | awk -v p="$RUN_ID-" 'index($1, p) == 1 { print $1 }')
  if [[ -n $left ]]; then
    printf 'netns: ERROR: namespaces left behind: %s\n' "$left" >&2
    rc=1
  elif [[ ${#MY_NAMESPACES[@]} -gt 0 ]]; then
    log "cleanup: ${#MY_NAMESPACES[@]} namespaces (with bridge, veths, nft table) removed; no process left"
  fi
  exit "$rc"
}

# --------------------------------------------------------------------------------------------------------- cases

start_agents() {  # start_agents DIR: fills AGENT_PIDS
  local dir=$1 i
  AGENT_PIDS=()
  for ((i = 0; i < N_AGENTS; i++)); do
    spawn "agent $i" "${AGENT_NS[$i]}" "$dir/agent$i.log" "$BIN_DIR/swa_agent" --id "$i" --config "$OUT_DIR/agent.yaml"
    AGENT_PIDS+=("$LAST_PID")
  done
}

# Each agent process must really be in its own namespace (ip netns identify reads /proc/PID/ns/net; a process
# spawned a moment ago may still be `ip` before its setns).
check_placement() {
  local i ok=0 ns deadline
  for ((i = 0; i < N_AGENTS; i++)); do
    deadline=$((SECONDS + 3))
    while :; do
      ns=$(ip netns identify "${AGENT_PIDS[$i]}" 2>/dev/null || true)
      [[ $ns == "${AGENT_NS[$i]}" ]] && { ok=$((ok + 1)); break; }
      ((SECONDS < deadline)) || break
      sleep 0.05
    done
  done
  check "every agent process in its own network namespace" "$ok/$N_AGENTS" equals "$ok" "$N_AGENTS"
}

check_no_shm() {
  local total=0 pid
  for pid in "$@"; do if alive "$pid"; then total=$((total + $(shm_files "$pid"))); fi; done
  check "no Fast DDS shared-memory files (UDP only)" "$total file(s) in the processes' /dev/shm" equals "$total" 0
}

# cohesive_run LABEL: the monitor, the agents and the simulator of one full run with CASE_ENV; checks the result.
cohesive_run() {
  local label=$1 dir=$OUT_DIR/$1 t0=$SECONDS
  mkdir -p "$dir"
  local sets=(--set "duration_s=$DURATION_S")
  spawn monitor "$SIM_NS" "$dir/monitor.log" "$BIN_DIR/swa_monitor" --scenario "$SCENARIO" "${sets[@]}" \
    --out "$dir/monitor" --label "netns-$label" --timeout-s "$RUN_TIMEOUT_S" --quiet
  local monitor_pid=$LAST_PID
  start_agents "$dir"
  check_placement
  spawn simulator "$SIM_NS" "$dir/sim.log" "$BIN_DIR/swa_sim" --scenario "$SCENARIO" "${sets[@]}" \
    --wait-monitors 1 --startup-timeout-s "$STARTUP_TIMEOUT_S" --summary-out "$dir/sim.json"
  local sim_pid=$LAST_PID sim_rc=0 monitor_rc=0
  wait_exit "$sim_pid" "$RUN_TIMEOUT_S" || sim_rc=$?
  [[ $sim_rc -eq 124 ]] && stop "$sim_pid"
  wait_exit "$monitor_pid" 20 || monitor_rc=$?
  [[ $monitor_rc -eq 124 ]] && stop "$monitor_pid"
  check_no_shm "${AGENT_PIDS[@]}"
  stop "${AGENT_PIDS[@]}"
  local wall=$((SECONDS - t0))

  local summary=$dir/monitor/summary.json sim_json=$dir/sim.json
  local verdict="" d_nb="" r="" collisions="" groups="" completed="" min_sep="" uavs=""
  local discovery="" sim_wall="" dead="" dead_end="" p50="" p99=""
  if [[ -s $summary ]]; then
    read -r verdict d_nb r collisions groups completed min_sep uavs < <(jq -r '[.verdict, .mean_neighbor_distance_m,
      .formation_radius_m, .collisions, .groups, .completed, .min_separation_m, .uav_count] | map(tostring) | join(" ")' \
      "$summary") || true
  fi
  if [[ -s $sim_json ]]; then
    read -r discovery sim_wall dead dead_end p50 p99 < <(jq -r '[.discovery_s, .wall_time_s, .agent_dead_events,
      (.dead_at_end | length), .latency_p50_us, .latency_p99_us] | map(tostring) | join(" ")' "$sim_json") || true
  fi
  local lo hi
  lo=$(awk -v r="$FORMATION_RADIUS_M" -v t="$TOLERANCE" 'BEGIN { print r * (1 - t) }')
  hi=$(awk -v r="$FORMATION_RADIUS_M" -v t="$TOLERANCE" 'BEGIN { print r * (1 + t) }')
  check "swa_sim exit status 0" "exit $sim_rc ($dir/sim.log)" equals "$sim_rc" 0
  check "swa_monitor exit status 0 (PASS)" "exit $monitor_rc ($dir/monitor.log)" equals "$monitor_rc" 0
  check "summary.json verdict PASS, run completed" "verdict ${verdict:-none}, completed ${completed:-?}" \
    equals "$verdict/$completed" PASS/true
  check "summary.json uav_count = $N_AGENTS, r = $FORMATION_RADIUS_M m" "uav_count ${uavs:-?}, formation_radius_m ${r:-?}" \
    equals "${uavs:-}/${r:-}" "$N_AGENTS/$FORMATION_RADIUS_M"
  check "final d_NB within r ± $(awk -v t="$TOLERANCE" 'BEGIN { print 100 * t }') % [$lo, $hi] m" \
    "d_NB $(fmt "$d_nb" 3) m" within "$lo" "$hi" "$d_nb"
  check "0 collisions, one group" "collisions ${collisions:-?}, groups ${groups:-?}, min separation $(fmt "$min_sep" 2) m" \
    equals "${collisions:-}/${groups:-}" 0/1
  check "no agent declared dead by the simulator" "agent_dead_events ${dead:-?}, dead at end ${dead_end:-?}" \
    equals "${dead:-}/${dead_end:-}" 0/0
  log "  $label: discovery $(fmt "$discovery" 2) s, $DURATION_S s simulated in $(fmt "$sim_wall" 1) s wall" \
    "(lockstep), loop latency p50 $(fmt "$p50" 0) us p99 $(fmt "$p99" 0) us; case wall time ${wall} s"
  RESULTS+=("$(printf '%-18s %-17s %-9s %-10s %-8s %-9s %-10s %s' "$label" "${CASE_ENV[0]#SWA_TRANSPORT=}" \
    "$(fmt "$discovery" 2) s" "${verdict:-none}" "$(fmt "$d_nb" 3)" "$(fmt "$min_sep" 2)" "${collisions:-?}" \
    "${wall} s")")
  CASE_DISCOVERY_S=$discovery
}

fmt() { awk -v x="$1" -v d="$2" 'BEGIN { if (x == "" || x == "null") print "?"; else printf "%.*f", d, x }'; }

case_multicast() {
  section "case 1: UDPv4 multicast discovery across the bridge (SWA_TRANSPORT=network)"
  CASE_ENV=(SWA_TRANSPORT=network)
  local before after
  before=$(nft_counter udp-multicast)
  cohesive_run multicast
  after=$(nft_counter udp-multicast)
  local offered=$((${after:-0} - ${before:-0}))
  check "discovery crossed the bridge as UDP multicast" "$offered UDP multicast packet(s) forwarded" \
    greater 0 "$offered"
  MULTICAST_DISCOVERY_S=$CASE_DISCOVERY_S
  check "multicast discovery well within the blocked run's timeout" \
    "$(fmt "$MULTICAST_DISCOVERY_S" 2) s <= $((PROOF_TIMEOUT_S / 2)) s" at_most "$((PROOF_TIMEOUT_S / 2))" \
    "$MULTICAST_DISCOVERY_S"
}

gave_up_on_discovery() { [[ $1 -eq 1 ]] && grep -q 'discovery incomplete' "$2"; }

# The same multicast setup as case 1, with the block installed: nothing of any agent may be discovered.
case_blocked() {
  section "case 2: multicast blocked on the bridge; plain multicast discovery must fail"
  block_multicast
  CASE_ENV=(SWA_TRANSPORT=network)
  local dir=$OUT_DIR/blocked t0=$SECONDS udp_before dropped_before
  mkdir -p "$dir"
  udp_before=$(nft_counter udp-multicast)
  dropped_before=$(nft_counter multicast-blocked)
  start_agents "$dir"
  spawn simulator "$SIM_NS" "$dir/sim.log" "$BIN_DIR/swa_sim" --scenario "$SCENARIO" --set "duration_s=$DURATION_S" \
    --wait-monitors 0 --startup-timeout-s "$PROOF_TIMEOUT_S"
  local sim_pid=$LAST_PID sim_rc=0
  wait_exit "$sim_pid" $((PROOF_TIMEOUT_S + 30)) || sim_rc=$?
  [[ $sim_rc -eq 124 ]] && stop "$sim_pid"
  local running=0 pid
  for pid in "${AGENT_PIDS[@]}"; do if alive "$pid"; then running=$((running + 1)); fi; done
  stop "${AGENT_PIDS[@]}"

  # swa_sim lists at most 12 unmatched endpoints, then "... and N more". Per agent: swa/uav<i>/sensors (the simulator's
  # frames: imu, detections and gnss in one message) and cmd_vel.
  local shown more unmatched expected=$((2 * N_AGENTS)) offered dropped
  shown=$(grep -cE '^  swa/uav[0-9]+/' "$dir/sim.log" || true)
  more=$(sed -nE 's/^  \.\.\. and ([0-9]+) more$/\1/p' "$dir/sim.log" | tail -n 1)
  unmatched=$((shown + ${more:-0}))
  offered=$(($(nft_counter udp-multicast) - udp_before))
  dropped=$(($(nft_counter multicast-blocked) - dropped_before))
  check "swa_sim exit 1 with 'discovery incomplete'" "exit $sim_rc after ${PROOF_TIMEOUT_S} s startup timeout" \
    gave_up_on_discovery "$sim_rc" "$dir/sim.log"
  check "no endpoint of any agent discovered" "$unmatched/$expected agent endpoints unmatched" \
    equals "$unmatched" "$expected"
  check "the agents were running all along" "$running/$N_AGENTS alive when swa_sim gave up" \
    equals "$running" "$N_AGENTS"
  check "the block dropped all multicast, SPDP included" "$offered UDP multicast packet(s) offered, $dropped dropped" \
    block_held "$offered" "$dropped"
  log "  blocked: $unmatched/$expected agent endpoints unmatched after ${PROOF_TIMEOUT_S} s (unblocked: all matched" \
    "in $(fmt "$MULTICAST_DISCOVERY_S" 2) s); case wall time $((SECONDS - t0)) s"
  RESULTS+=("$(printf '%-18s %-17s %s' "multicast blocked" network \
    "$unmatched/$expected agent endpoints unmatched after ${PROOF_TIMEOUT_S} s, $dropped multicast packets dropped")")
}

# The agents did try multicast discovery, and the drop rule (after the accounting rule) caught at least that much.
block_held() { (($1 > 0 && $2 >= $1)); }

case_discovery_server() {
  section "case 3: Fast DDS Discovery Server, multicast still blocked (SWA_TRANSPORT=discovery-server)"
  CASE_ENV=()
  local dir=$OUT_DIR/discovery_server deadline
  mkdir -p "$dir"
  # The server keeps Fast DDS's default transports; its shared memory stays in its private /dev/shm.
  spawn discovery-server "$DS_NS" "$dir/discovery_server.log" fast-discovery-server -i 0 -l "$DS_IP" -p "$DS_PORT"
  DS_PID=$LAST_PID
  deadline=$((SECONDS + 10))
  until grep -q 'Server is running' "$dir/discovery_server.log" 2>/dev/null; do
    if ! alive "$DS_PID" || ((SECONDS >= deadline)); then
      die "fast-discovery-server did not start: $(cat "$dir/discovery_server.log")"
    fi
    sleep 0.1
  done
  log "  fast-discovery-server -i 0 -l $DS_IP -p $DS_PORT running in $DS_NS"
  CASE_ENV=(SWA_TRANSPORT=discovery-server "SWA_DISCOVERY_SERVER=$DS_IP:$DS_PORT")
  local udp_before dropped_before
  udp_before=$(nft_counter udp-multicast)
  dropped_before=$(nft_counter multicast-blocked)
  cohesive_run discovery_server
  check "discovery server still running at the end" "pid $DS_PID" alive "$DS_PID"
  stop "$DS_PID"
  DS_PID=""
  # Not even an attempt: with the block lifted the run would be the same.
  local offered=$(($(nft_counter udp-multicast) - udp_before))
  check "no UDP multicast sent at all (client discovery only)" "$offered UDP multicast packet(s) offered to the bridge" \
    equals "$offered" 0
  log "  IPv4 multicast dropped meanwhile: $(($(nft_counter multicast-blocked) - dropped_before)) packet(s)" \
    "(none of it UDP; the block stays in place)"
}

main() {
  parse_args "$@"
  install_missing
  check_binaries
  trap cleanup EXIT
  trap 'exit 130' INT
  trap 'exit 143' TERM
  remove_stale_namespaces
  mkdir -p "$OUT_DIR"
  rm -rf "$OUT_DIR/multicast" "$OUT_DIR/blocked" "$OUT_DIR/discovery_server"
  "$BIN_DIR/swa_sim" --scenario "$SCENARIO" --set "duration_s=$DURATION_S" --export-agent-config "$OUT_DIR/agent.yaml"

  section "network: $((N_AGENTS + 3)) namespaces, one bridge"
  setup_network
  case_multicast
  case_blocked
  case_discovery_server

  section "summary ($((SECONDS - T_START)) s; outputs in $OUT_DIR)"
  printf 'netns: %-18s %-17s %-9s %-10s %-8s %-9s %-10s %s\n' case transport discovery verdict d_NB/m "min sep" \
    collisions wall
  local line
  for line in "${RESULTS[@]}"; do printf 'netns: %s\n' "$line"; done
  report_checks || exit 1
  log "all checks passed"
}

main "$@"
