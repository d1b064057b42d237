#!/usr/bin/env bash
# Soak (issue #11; not in CI, figures in BENCHMARKS.md): a long realtime run under swa_launch with every process's
# resident memory, threads and open file descriptors sampled at a fixed period, and their growth after a warm-up.
#
# Usage: bash tests/soak/soak.sh [--uavs N] [--duration-s S] [--period-s P] [--warmup-s W] [--out DIR]
#   defaults: 8 UAVs, 600 s, every 30 s, warm-up 120 s, out/soak. Needs a Release build in build/ (deploy/build.sh).
# The warm-up covers what fills up by design: the simulator's truth writer keeps the last 100 s for a restarted
# monitor (idl/runtime/dds/profiles.xml), so its memory grows for the first ~100 s. The monitor keeps the run's time
# series and trajectories for its summary and report (~2 kB/s at 8 UAVs): that growth is proportional to the run.
# Writes DIR/samples.csv (t_s,process,pid,rss_kb,threads,fds) and DIR/growth.csv, the launch's run directory in
# DIR/run, and prints a table: per process the value at the end of the warm-up, at the end, and the growth in
# between (also per hour). Exit status: the launch's verdict (0 PASS), or 1 if a process restarted meanwhile (its
# figures would mix two processes) or no sample was taken.
#
# The run is a swarm of its own (swa_launch names one) on the domain given by $SWA_DOMAIN (default 0), so another
# swarm on the same domain is neither disturbed nor counted; only the launcher's own children are sampled.

# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
uavs=8
duration=600
period=30
warmup=120
out=$root/out/soak
while [[ $# -gt 0 ]]; do
  case $1 in
    --uavs) uavs=$2; shift 2 ;;
    --duration-s) duration=$2; shift 2 ;;
    --period-s) period=$2; shift 2 ;;
    --warmup-s) warmup=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "soak: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
for v in "$uavs" "$duration" "$period" "$warmup"; do
  [[ $v =~ ^[0-9]+$ && $v -gt 0 ]] || { echo "soak: '$v' is not a positive whole number" >&2; exit 2; }
done
((warmup < duration)) || { echo "soak: the warm-up must be shorter than the run" >&2; exit 2; }
launcher=$root/build/bin/swa_launch
[[ -x $launcher ]] || { echo "soak: $launcher missing: run bash deploy/build.sh first" >&2; exit 2; }

mkdir -p "$out"
rm -rf "$out/run"
samples=$out/samples.csv
echo "t_s,process,pid,rss_kb,threads,fds" >"$samples"

"$launcher" --scenario "$root/deploy/scenarios/dropout_8.yaml" --set "uav_count=$uavs" --set clock.mode=realtime \
  --set "duration_s=$duration" --out "$out/run" >"$out/launch.log" 2>&1 &
launch_pid=$!
trap 'kill -TERM $launch_pid 2>/dev/null || true; wait $launch_pid 2>/dev/null || true' EXIT

label() {  # the process name of a launcher child: swa_sim, swa_monitor, agent_<I>
  local cmd
  cmd=$({ tr '\0' ' ' <"/proc/$1/cmdline"; } 2>/dev/null) || return 1  # (it may have exited meanwhile)
  case $cmd in
    *swa_agent*) sed -E 's/.*--id ([0-9]+).*/agent_\1/' <<<"$cmd" ;;
    *swa_sim*) echo swa_sim ;;
    *swa_monitor*) echo swa_monitor ;;
    *) return 1 ;;
  esac
}

sample() {  # one row per live child of the launcher (and the launcher itself)
  local t=$1 pid name rss threads fds
  for pid in $launch_pid $(pgrep -P "$launch_pid" || true); do
    if [[ $pid == "$launch_pid" ]]; then name=swa_launch; else name=$(label "$pid") || continue; fi
    rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null) || continue
    threads=$(awk '/^Threads:/ {print $2}' "/proc/$pid/status" 2>/dev/null) || continue
    fds=$(ls "/proc/$pid/fd" 2>/dev/null | wc -l)
    [[ -n $rss ]] && echo "$t,$name,$pid,$rss,$threads,$fds" >>"$samples"
  done
}

# Wait until every process is up (the simulator starts once all are discovered), then sample from t = 0.
for _ in $(seq 1 600); do
  [[ $(pgrep -P "$launch_pid" | wc -l) -ge $((uavs + 2)) ]] && break
  kill -0 "$launch_pid" 2>/dev/null || break
  sleep 0.1
done
start=$SECONDS
next=0
while kill -0 "$launch_pid" 2>/dev/null; do
  t=$((SECONDS - start))
  if ((t >= next && t < duration)); then  # (at t = duration the processes are already shutting down)
    sample "$t"
    next=$((next + period))
  fi
  sleep 1
done
status=0
wait "$launch_pid" || status=$?
trap - EXIT

# Growth per process: from the first sample at or after the warm-up to the last one. A process whose pid changed
# (restarted) is reported and makes the soak fail.
awk -F, -v warm="$warmup" -v out="$out/growth.csv" '
  NR == 1 { next }
  {
    n = $2
    if (!(n in first_pid)) first_pid[n] = $3
    if ($3 != first_pid[n]) restarted[n] = 1
    if ($1 >= warm && !(n in w_t)) { w_t[n] = $1; w_rss[n] = $4; w_thr[n] = $5; w_fd[n] = $6 }
    e_t[n] = $1; e_rss[n] = $4; e_thr[n] = $5; e_fd[n] = $6
    names[n] = 1
  }
  END {
    print "process,warm_t_s,end_t_s,rss_warm_mb,rss_end_mb,rss_growth_mb,rss_growth_mb_per_h,threads_warm,threads_end,fds_warm,fds_end,restarted" > out
    printf "%-12s %8s %8s %9s %9s %9s %11s %7s %7s %5s %5s\n", "process", "t_warm", "t_end", "RSS_warm", "RSS_end",
           "growth", "growth/h", "thr", "thr", "fds", "fds"
    printf "%-12s %8s %8s %9s %9s %9s %11s %7s %7s %5s %5s\n", "", "[s]", "[s]", "[MB]", "[MB]", "[MB]", "[MB/h]",
           "warm", "end", "warm", "end"
    bad = 0
    for (n in names) {
      if (!(n in w_t)) { printf "%-12s no sample after the warm-up\n", n; bad = 1; continue }
      dt = e_t[n] - w_t[n]
      g = (e_rss[n] - w_rss[n]) / 1024
      gh = dt > 0 ? g * 3600 / dt : 0
      printf "%-12s %8d %8d %9.1f %9.1f %9.2f %11.2f %7d %7d %5d %5d%s\n", n, w_t[n], e_t[n], w_rss[n] / 1024,
             e_rss[n] / 1024, g, gh, w_thr[n], e_thr[n], w_fd[n], e_fd[n], (n in restarted) ? "  RESTARTED" : ""
      printf "%s,%d,%d,%.1f,%.1f,%.2f,%.2f,%d,%d,%d,%d,%d\n", n, w_t[n], e_t[n], w_rss[n] / 1024, e_rss[n] / 1024, g,
             gh, w_thr[n], e_thr[n], w_fd[n], e_fd[n], (n in restarted) ? 1 : 0 > out
      if (n in restarted) bad = 1
    }
    exit bad
  }' "$samples" | { IFS= read -r h1; IFS= read -r h2; echo "$h1"; echo "$h2"; sort; } || status=1
[[ $(wc -l <"$samples") -gt 1 ]] || { echo "soak: no sample taken (see $out/launch.log)" >&2; status=1; }
tail -n 2 "$out/launch.log"
echo "soak: samples in $samples, growth in $out/growth.csv, run in $out/run"
exit "$status"
