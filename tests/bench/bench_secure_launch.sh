#!/usr/bin/env bash
# How reliably does a secured swarm start (issue #46)? Secure launches one after another, each beside the same launch
# without security, so the discovery times compare on the same machine at the same moment; not a ctest (the suite keeps
# one secure launch per vehicle kind, tests/security/test_security.cpp); results in BENCHMARKS.md.
#
#   bench_secure_launch.sh [--bin DIR] [--kinds LIST] [--uavs LIST] [--keep DIR] RUNS
#     --bin DIR      the programs (default: build/bin)
#     --kinds LIST   comma-separated, of direct, px4, ardupilot (default: all three)
#     --uavs LIST    comma-separated swarm sizes (default: 4,8)
#     --keep DIR     keep every run's directory there (default: only the failed runs', in a temporary folder named
#                    at the end)
#     --launch-args "ARGS"
#                    more swa_launch arguments for every secure run, e.g. "--stagger-s 0" (word-split); the plain
#                    twin is always the default launch
#     RUNS           secure launches per kind and size (and as many plain ones)
#
# A run is `swa_launch --secure` of deploy/scenarios/dropout_8.yaml with uav_count N, 30 s simulated, with
# SWA_DDS_TRACE=1 (every process logs whom it discovered and authenticated). Printed per kind and size:
#   secure pass        runs that exited 0 (PASS) / runs
#   discovery          time to full discovery: from the launch until the simulator has matched every agent (or
#                      bridge) and the monitor (it steps only then); median and max over the runs, secure and plain,
#                      and the ratio of the medians
#   agent CPU          CPU seconds an agent spent before its first sample (median over a run's agents, then over
#                      the runs): what its handshakes cost it
#   reconnections      participants re-created by the product's own recovery (agents, bridges, monitor, simulator),
#                      in all secure runs together, and in the plain ones
# Then one line per failed run with its cause: the launch's last words, and from the trace every pair still
# discovered but never authenticated when the run ended (a stalled handshake) or refused.
# A run costs 10-40 s of wall time (direct lockstep / autopilots in realtime); RUNS = 50 of all six cases with their
# plain twins is about 5 h. Nothing else should run on the machine meanwhile.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"

usage() { sed -n '2,/^# shellcheck/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; }
bin=$root/build/bin
kinds=direct,px4,ardupilot
sizes=4,8
keep=
runs=
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --bin) bin=${2:?--bin needs a directory}; shift 2 ;;
    --kinds) kinds=${2:?--kinds needs a list}; shift 2 ;;
    --uavs) sizes=${2:?--uavs needs a list}; shift 2 ;;
    --keep) keep=${2:?--keep needs a directory}; shift 2 ;;
    --launch-args) read -r -a extra <<< "${2?--launch-args needs arguments}"; shift 2 ;;
    -h | --help) usage; exit 0 ;;
    -*) echo "bench_secure_launch: unknown option $1 (--help)" >&2; exit 2 ;;
    *) [ -z "$runs" ] || { echo "bench_secure_launch: one RUNS only (--help)" >&2; exit 2; }; runs=$1; shift ;;
  esac
done
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "bench_secure_launch: RUNS must be a positive number (--help)" >&2; exit 2; }
for k in ${kinds//,/ }; do
  case $k in direct | px4 | ardupilot) ;; *) echo "bench_secure_launch: unknown kind $k (--help)" >&2; exit 2 ;; esac
done
for n in ${sizes//,/ }; do
  [[ $n =~ ^[1-9][0-9]*$ ]] || { echo "bench_secure_launch: bad swarm size $n (--help)" >&2; exit 2; }
done
for b in swa_launch swa_sim swa_agent swa_monitor swa_px4_bridge; do
  [ -x "$bin/$b" ] || fail "no $bin/$b (bash deploy/build.sh)"
done

work=$(mktemp -d /tmp/swa_bench_secure.XXXXXX)
[ -z "$keep" ] || mkdir -p "$keep"
# Private keys never outlive the benchmark; failed runs' logs do.
trap 'rm -rf "$work/creds_"* "$work/ok"' EXIT
reserve_test_domain 191
log "domain $TEST_DOMAIN; $runs run(s) of each of kinds $kinds, sizes $sizes; work in $work"

for n in ${sizes//,/ }; do
  bash "$root/deploy/security/make-credentials.sh" --bridges "$work/creds_$n" "$n" > "$work/creds_$n.log" 2>&1 ||
    { cat "$work/creds_$n.log" >&2; fail "make-credentials.sh for $n UAVs"; }
done

# launch KIND N SECURE(0/1) RUN: one launch; its directory is $work/ok/... or, failed, $work/failed/...
launch() {
  local kind=$1 n=$2 secure=$3 k=$4 name out status=0 args=()
  name=${kind}_${n}_$([ "$secure" = 1 ] && echo secure || echo plain)_$k
  out=$work/ok/$name
  mkdir -p "$work/ok"
  [ "$kind" = direct ] || args+=(--vehicle "$kind")
  [ "$secure" = 0 ] || args+=(--secure "$work/creds_$n" "${extra[@]}")
  local t0 pid discovered=""
  t0=$(date +%s.%N)
  SWA_DDS_TRACE=1 "$bin/swa_launch" "${args[@]}" --scenario "$root/deploy/scenarios/dropout_8.yaml" \
    --set "uav_count=$n" --set duration_s=30 --domain "$TEST_DOMAIN" --out "$out" --timeout-s 150 \
    > "$out.log" 2>&1 &
  pid=$!
  # Time to full discovery, from the launch: when the simulator says it has matched every agent (or bridge) and the
  # monitor, which it waits for before its first step; whatever order the launcher starts them in.
  while kill -0 "$pid" 2> /dev/null; do
    if [ -z "$discovered" ] && grep -q "agent(s) discovered in" "$out/logs/sim.log" 2> /dev/null; then
      discovered=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    fi
    sleep 0.1
  done
  wait "$pid" || status=$?
  echo "$status" > "$out.status"
  if [ "$status" != 0 ]; then
    mkdir -p "$work/failed"
    mv "$out" "$out.log" "$out.status" "$work/failed/"
  elif [ -n "$keep" ]; then
    cp -r "$out" "$out.log" "$out.status" "$keep/"
  fi
  # The figures the table needs, kept after the run's directory is gone: status, discovery, reconnections.
  local dir=$work/ok/$name
  [ -d "$dir" ] || dir=$work/failed/$name
  local reconnections cpu
  reconnections=$(cat "$dir"/logs/*.log 2>/dev/null | grep -c "re-creating the participant" || true)
  # CPU time an agent spent before its first sample (its handshakes' share), the median over the run's agents.
  cpu=$(cat "$dir"/logs/agent_*.log 2>/dev/null |
    sed -n 's/^swa_agent [0-9]*: first IMU sample .*, \([0-9.]*\) s of CPU time before it.*/\1/p' | sort -n |
    awk '{ v[NR] = $1 } END { if (NR) printf "%.3f", (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }')
  echo "$kind $n $secure $k $status ${discovered:-none} $reconnections ${cpu:-none}" >> "$work/runs.txt"
  [ "$status" = 0 ] && [ -z "$keep" ] && rm -rf "$dir" "$dir.log" "$dir.status"
  log "$name: status $status, discovery ${discovered:-none} s, $reconnections reconnection(s), agent CPU ${cpu:-none} s"
}

for k in $(seq 1 "$runs"); do
  for kind in ${kinds//,/ }; do
    for n in ${sizes//,/ }; do
      launch "$kind" "$n" 1 "$k"
      launch "$kind" "$n" 0 "$k"
    done
  done
done

# A failed run's cause from its trace: in each process's log, the participants it discovered (by name and GUID) and
# never authenticated nor lost again; and the refusals.
cause() {
  local dir=$1
  echo "    launch: $(grep -v '^\s*$' "$dir.log" | tail -2 | tr '\n' ' ')"
  for f in "$dir"/logs/*.log; do
    [ -f "$f" ] || continue
    awk -v self="$(basename "$f" .log)" '
      / \[dds trace\] participant / {
        if ($0 ~ / discovered \(/) { n = $0; sub(/.* participant /, "", n); sub(/ discovered.*/, "", n)
                                    g = $0; sub(/.*\(/, "", g); sub(/\).*/, "", g); name[g] = n; open[g] = 1 }
        else if ($0 ~ / authenticated$/) { g = $0; sub(/.* participant /, "", g); sub(/ authenticated$/, "", g)
                                           delete open[g] }
        else if ($0 ~ /REFUSED/) { print "    " self ": " $0 }
        else if ($0 ~ / (removed|dropped)/) { g = $0; sub(/.*\(/, "", g); sub(/\).*/, "", g); delete open[g] }
      }
      END { s = ""; for (g in open) s = s " " name[g]; if (s != "") print "    " self " never authenticated:" s }
    ' "$f"
  done
}

echo
python3 - "$work/runs.txt" <<'EOF'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
def med(xs): return f"{statistics.median(xs):.2f}" if xs else "-"
def mx(xs): return f"{max(xs):.2f}" if xs else "-"
print(f"{'kind':>9} {'N':>2}  {'secure pass':>11}  {'plain pass':>10}  {'discovery s, secure median / max':>32}  "
      f"{'plain median / max':>18}  {'ratio':>5}  {'reconnections secure / plain':>28}"
      f"  {'agent CPU s secure / plain':>26}")
seen = []
for r in rows:
    if (r[0], r[1]) not in seen: seen.append((r[0], r[1]))
for kind, n in seen:
    def of(secure): return [r for r in rows if r[0] == kind and r[1] == n and r[2] == secure]
    s, p = of("1"), of("0")
    def disc(rs): return [float(r[5]) for r in rs if r[5] != "none"]
    def cpu(rs): return [float(r[7]) for r in rs if r[7] != "none"]
    ds, dp = disc(s), disc(p)
    ratio = f"{statistics.median(ds) / statistics.median(dp):.2f}" if ds and dp else "-"
    print(f"{kind:>9} {n:>2}  {sum(r[4] == '0' for r in s):>4} / {len(s):<4}  {sum(r[4] == '0' for r in p):>3} / {len(p):<4}"
          f"  {med(ds) + ' / ' + mx(ds):>32}  {med(dp) + ' / ' + mx(dp):>18}  {ratio:>5}"
          f"  {sum(int(r[6]) for r in s):>14} / {sum(int(r[6]) for r in p):<11}"
          f"  {med(cpu(s)):>12} / {med(cpu(p)):<11}")
EOF

failed=0
if [ -d "$work/failed" ]; then
  echo
  echo "failed runs (directories in $work/failed):"
  for status in "$work"/failed/*.status; do
    dir=${status%.status}
    echo "  $(basename "$dir"): status $(cat "$status")"
    cause "$dir"
    failed=1
  done
else
  rm -rf "$work"
fi
exit "$failed"
