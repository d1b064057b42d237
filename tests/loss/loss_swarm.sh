#!/usr/bin/env bash
# Packet loss between the processes of a swarm (issue #11, ctest label `loss`).
#
# The same realtime scenario (6 UAVs, GNSS lost at 10 s) runs three times, each in a network namespace of this
# script's own where every process talks UDP only (SWA_TRANSPORT=network) over that namespace's loopback:
#   clean    no impairment: the reference
#   loss10   10 % of UDP datagrams dropped, the rest delayed 20 +- 10 ms (uniform), in both directions of every link
#   loss30   30 % dropped, 20 +- 10 ms
# The kernel has no netem qdisc and no nftables queue expression; an iptables NFQUEUE rule (x_tables) hands every UDP
# datagram leaving a process to swa_netem, which drops or holds it (tests/loss/impairment.h, seeded).
#
# Checks for each impaired run: the impairment really happened (the fraction swa_netem dropped, and the loop latency
# the simulator measured is at least the two one-way delays); the monitor's verdict is PASS and complete (no
# INCOMPLETE, no truth missed, at most 1 % of steps with a state missing); cohesion as clean (d_NB within 3 % of r of
# the clean run's, no collision, one group, minimum separation at least 80 % of the clean run's).
#
# Usage: loss_swarm.sh BIN_DIR SWA_NETEM SOURCE_DIR [OUT_DIR]
#   BIN_DIR     directory with swa_launch, swa_sim, swa_agent, swa_monitor
#   SWA_NETEM   the loss emulator (tests/loss/swa_netem.cpp)
#   SOURCE_DIR  the repository (for deploy/scenarios/dropout_8.yaml)
#   OUT_DIR     run directories and logs (default ./loss-out), kept for inspection
# Environment: SWA_LOSS_DURATION_S (simulated seconds per run, default 45), SWA_LOSS_UAVS (default 6).
# Needs root (network namespaces, iptables); installs iptables and jq with apt-get if missing.
#
# Isolation: nothing is added to the host's network namespace; a namespace of our own has its own loopback and its
# own netfilter tables, so no other DDS user on the host sees (or disturbs) these runs, and each process gets a
# private tmpfs on /dev/shm. An EXIT trap stops every process in the namespaces and deletes them; a later run removes
# namespaces left by a run that was killed outright.

# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"

readonly NS_TAG=swaloss
readonly QUEUE=7
readonly MAX_INCOMPLETE=0.01    # fraction of steps with a live agent's state missing
readonly DNB_TOLERANCE_M=0.3    # 3 % of r = 10 m (dropout_8.yaml)
readonly MIN_SEP_RATIO=0.8

if [[ $# -lt 3 || $# -gt 4 ]]; then
  sed -n '/^# Usage:/,/^# Needs root/p' "$0" >&2
  exit 2
fi
BIN_DIR=$(cd "$1" && pwd)
NETEM=$2
SRC_DIR=$(cd "$3" && pwd)
OUT_DIR=${4:-$PWD/loss-out}
DURATION_S=${SWA_LOSS_DURATION_S:-45}
UAVS=${SWA_LOSS_UAVS:-6}
SCENARIO=$SRC_DIR/deploy/scenarios/dropout_8.yaml
declare -A VALUE=()

TEST_TAG=loss

[[ $(id -u) -eq 0 ]] || die "needs root (network namespaces, iptables)"
[[ -x $NETEM ]] || die "$NETEM not found (build tests/loss first)"
for b in swa_launch swa_sim swa_agent swa_monitor; do [[ -x $BIN_DIR/$b ]] || die "$BIN_DIR/$b missing"; done
missing=()
command -v iptables >/dev/null 2>&1 || missing+=(iptables)
command -v jq >/dev/null 2>&1 || missing+=(jq)
if [[ ${#missing[@]} -gt 0 ]]; then
  log "installing missing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null ||
    { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; }
fi

# ------------------------------------------------------------------------------------------ namespaces, cleanup

MY_NS=()
stop_namespace() {
  local ns=$1 pids
  pids=$(ip netns pids "$ns" 2>/dev/null || true)
  [[ -n $pids ]] && kill -TERM $pids 2>/dev/null || true
  for _ in $(seq 1 100); do
    pids=$(ip netns pids "$ns" 2>/dev/null || true)
    [[ -z $pids ]] && break
    sleep 0.1
  done
  [[ -n $pids ]] && kill -KILL $pids 2>/dev/null || true
  ip netns del "$ns" 2>/dev/null || true
}
cleanup() {
  local ns
  for ns in "${MY_NS[@]}"; do stop_namespace "$ns"; done
}
trap cleanup EXIT
# Namespaces of runs killed outright (their trap never ran) whose script is gone.
for ns in $(ip netns list 2>/dev/null | awk '{print $1}' | grep "^${NS_TAG}[0-9]*-" || true); do
  owner=${ns#"$NS_TAG"}
  owner=${owner%%-*}
  kill -0 "$owner" 2>/dev/null || { log "removing namespace $ns left by an earlier run"; stop_namespace "$ns"; }
done

# run_case NAME LOSS DELAY_MS JITTER_MS: one launch in a namespace of its own; VALUE[NAME.key] gets its figures.
run_case() {
  local name=$1 loss=$2 delay=$3 jitter=$4
  local ns=$NS_TAG$$-$name dir=$OUT_DIR/$name netem_pid=""
  rm -rf "$dir"
  mkdir -p "$dir"
  ip netns add "$ns"
  MY_NS+=("$ns")
  ip netns exec "$ns" ip link set lo up
  # Fast DDS discovers over UDP multicast; the namespace's loopback carries it once it accepts multicast.
  ip netns exec "$ns" ip link set lo multicast on
  ip netns exec "$ns" ip route add 224.0.0.0/4 dev lo
  if [[ $name != clean ]]; then
    ip netns exec "$ns" "$NETEM" --queue "$QUEUE" --loss "$loss" --delay-ms "$delay" --jitter-ms "$jitter" --seed 1 \
      >"$dir/netem.log" 2>&1 &
    netem_pid=$!
    for _ in $(seq 1 50); do grep -q "^swa_netem: queue" "$dir/netem.log" && break; sleep 0.1; done
    grep -q "^swa_netem: queue" "$dir/netem.log" || die "swa_netem did not start: $(cat "$dir/netem.log")"
    ip netns exec "$ns" iptables -A OUTPUT -p udp -j NFQUEUE --queue-num "$QUEUE"
  fi
  log "run $name: $UAVS UAVs, $DURATION_S s realtime, loss $loss, delay $delay +- $jitter ms"
  local rc=0
  ip netns exec "$ns" sh -c 'mount -t tmpfs -o size=64m,mode=1777 swa-loss-shm /dev/shm && exec "$@"' sh \
    env -u SWA_SECURITY_DIR -u SWA_DISCOVERY_SERVER -u SWA_TRANSPORT -u SWA_SWARM \
    "$BIN_DIR/swa_launch" --scenario "$SCENARIO" --transport network --domain 0 \
    --set clock.mode=realtime --set "duration_s=$DURATION_S" --set "uav_count=$UAVS" \
    --timeout-s $((DURATION_S + 180)) --out "$dir" >"$dir/launch.log" 2>&1 || rc=$?
  if [[ -n $netem_pid ]]; then
    # The rule first: a datagram queued with nobody reading the queue would be dropped by the kernel.
    ip netns exec "$ns" iptables -F OUTPUT
    kill -TERM "$netem_pid" 2>/dev/null || true
    wait "$netem_pid" 2>/dev/null || true
    local counts
    counts=$(grep "^swa_netem: seen" "$dir/netem.log" || true)
    VALUE[$name.seen]=$(awk '{print $3}' <<<"$counts")
    VALUE[$name.dropped]=$(awk '{print $5}' <<<"$counts")
  fi
  stop_namespace "$ns"
  VALUE[$name.rc]=$rc
  local s=$dir/summary.json sim=$dir/sim_summary.json
  [[ -f $s && -f $sim ]] || { tail -5 "$dir/launch.log" >&2; die "run $name wrote no summary (exit $rc)"; }
  VALUE[$name.verdict]=$(jq -r .verdict "$s")
  VALUE[$name.steps]=$(jq -r .steps "$s")
  VALUE[$name.incomplete]=$(jq -r .steps_incomplete "$s")
  VALUE[$name.missing_states]=$(jq -r .missing_states "$s")
  VALUE[$name.truth_missed_ms]=$(jq -r .truth_missed_ms "$s")
  VALUE[$name.late_states]=$(jq -r .dropped_state_late "$s")
  VALUE[$name.d_nb]=$(jq -r .mean_neighbor_distance_m "$s")
  VALUE[$name.min_sep]=$(jq -r .min_separation_m "$s")
  VALUE[$name.collisions]=$(jq -r .collisions "$s")
  VALUE[$name.groups]=$(jq -r .groups "$s")
  VALUE[$name.drift]=$(jq -r .drift_velocity_mps "$s")
  VALUE[$name.p50_us]=$(jq -r .latency_p50_us "$sim")
  VALUE[$name.max_us]=$(jq -r .latency_max_us "$sim")
  VALUE[$name.dead]=$(jq -r .agent_dead_events "$sim")
  printf 'loss: %s: exit %s, %s, d_NB %.3f m, min sep %.2f m, drift %.3f m/s, %s/%s steps incomplete, %s states missing (%s late), loop latency p50 %.1f ms max %.1f ms, %s agent(s) declared dead%s\n' \
    "$name" "$rc" "${VALUE[$name.verdict]}" "${VALUE[$name.d_nb]}" "${VALUE[$name.min_sep]}" "${VALUE[$name.drift]}" \
    "${VALUE[$name.incomplete]}" "${VALUE[$name.steps]}" "${VALUE[$name.missing_states]}" \
    "${VALUE[$name.late_states]}" "$(awk -v x="${VALUE[$name.p50_us]}" 'BEGIN{print x/1000}')" \
    "$(awk -v x="${VALUE[$name.max_us]}" 'BEGIN{print x/1000}')" "${VALUE[$name.dead]}" \
    "$([[ -n ${VALUE[$name.seen]:-} ]] && echo ", swa_netem dropped ${VALUE[$name.dropped]} of ${VALUE[$name.seen]} datagrams")"
}

mkdir -p "$OUT_DIR"
run_case clean 0 0 0
run_case loss10 0.10 20 10
run_case loss30 0.30 20 10

log "checks"
check "clean run passes" "exit ${VALUE[clean.rc]}, ${VALUE[clean.verdict]}" test "${VALUE[clean.rc]}" -eq 0
for name in loss10 loss30; do
  p=$([[ $name == loss10 ]] && echo 0.10 || echo 0.30)
  seen=${VALUE[$name.seen]:-0}
  frac=$(awk -v d="${VALUE[$name.dropped]:-0}" -v s="$seen" 'BEGIN { if (s > 0) print d / s; else print "" }')
  check "$name: the emulator saw the run's traffic" "$seen datagrams" at_least 10000 "$seen"
  check "$name: dropped fraction is $p +- 0.01" "$frac" within "$(awk -v p="$p" 'BEGIN{print p-0.01}')" \
    "$(awk -v p="$p" 'BEGIN{print p+0.01}')" "$frac"
  check "$name: loop latency p50 >= 40 ms (sensor and command each delayed)" "${VALUE[$name.p50_us]} us" \
    at_least 40000 "${VALUE[$name.p50_us]}"
  check "$name: verdict PASS, complete" "exit ${VALUE[$name.rc]}, ${VALUE[$name.verdict]}" \
    test "${VALUE[$name.rc]}" -eq 0
  check "$name: no truth missed" "${VALUE[$name.truth_missed_ms]} ms" at_most 0 "${VALUE[$name.truth_missed_ms]}"
  check "$name: steps with a state missing <= 1 %" "${VALUE[$name.incomplete]} of ${VALUE[$name.steps]}" \
    at_most "$(awk -v s="${VALUE[$name.steps]}" -v f=$MAX_INCOMPLETE 'BEGIN{print s*f}')" "${VALUE[$name.incomplete]}"
  check "$name: d_NB as clean (+-${DNB_TOLERANCE_M} m)" "${VALUE[$name.d_nb]} vs ${VALUE[clean.d_nb]} m" \
    within "$(awk -v c="${VALUE[clean.d_nb]}" -v t=$DNB_TOLERANCE_M 'BEGIN{print c-t}')" \
    "$(awk -v c="${VALUE[clean.d_nb]}" -v t=$DNB_TOLERANCE_M 'BEGIN{print c+t}')" "${VALUE[$name.d_nb]}"
  check "$name: no collision, one group" "${VALUE[$name.collisions]} collision(s), ${VALUE[$name.groups]} group(s)" \
    test "${VALUE[$name.collisions]}" -eq 0 -a "${VALUE[$name.groups]}" -eq 1
  check "$name: min separation >= ${MIN_SEP_RATIO} x clean" "${VALUE[$name.min_sep]} vs ${VALUE[clean.min_sep]} m" \
    at_least "$(awk -v c="${VALUE[clean.min_sep]}" -v r=$MIN_SEP_RATIO 'BEGIN{print c*r}')" "${VALUE[$name.min_sep]}"
done

report_checks || exit 1
log "all checks passed; run directories in $OUT_DIR"
