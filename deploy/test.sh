#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test, then the sanitizer stage (the labels
# unit, closedloop and fuzz again, built with ASan + UBSan: deploy/test-sanitize.sh). Ends with what each stage took.
#   bash deploy/test.sh                      everything (what CI runs)
#   bash deploy/test.sh [ctest args...]      the Release build and those ctest arguments only, e.g. -L unit
#
# The sanitizer build runs beside the Release tests, at the lowest CPU and I/O priority (nice 19, ionice idle): most
# of the Release suite's time is realtime runs that wait, and a nice-19 compiler gets about 1.5 % of a core that a
# test wants (CFS weights 15 against 1024), so it takes mostly idle time (measured: the suite 9 % longer beside it,
# BENCHMARKS.md "Build and test time").
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SWA_BUILD_DIR:-$root/build}

stages=()
duration() { echo "$(($1 / 60)) min $(($1 % 60)) s"; }
timed() {  # timed NAME COMMAND...: runs it, notes its wall time
  local name=$1 start=$SECONDS
  shift
  "$@"
  stages+=("$name $(duration $((SECONDS - start)))")
}
summary() { echo "test.sh: $(IFS=';'; echo "${stages[*]}" | sed 's/;/, /g'); $(duration $SECONDS) in all"; }
timed build bash "$root/deploy/build.sh"
if [ $# -gt 0 ]; then
  timed "Release tests" ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
  summary
  exit 0
fi

# The sanitizer build in its own session (setsid), so that a failure here ends all of it, compilers included. A new
# session is a new scheduler autogroup where the kernel has them (sched_autogroup_enabled): autogroups share the CPU
# evenly whatever their members' nice, so the group itself gets nice 19 too.
san_log=$(mktemp /tmp/swa-sanitize-build.XXXXXX.log)
san_done=$(mktemp /tmp/swa-sanitize-build.XXXXXX.end)
setsid bash -c '{ echo 19 >/proc/self/autogroup; } 2>/dev/null
  nice -n 19 ionice -c 3 bash "$1" --build-only >"$2" 2>&1; rc=$?; date +%s >"$3"; exit $rc' _ \
  "$root/deploy/test-sanitize.sh" "$san_log" "$san_done" &
san_pid=$!
san_epoch=$(date +%s)
trap 'kill -TERM -- "-$san_pid" 2>/dev/null || true; rm -f "$san_log" "$san_done"' EXIT
trap 'exit 130' INT  # so that the EXIT trap above also runs on Ctrl-C and on a CI job's SIGTERM
trap 'exit 143' TERM

timed "Release tests" ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
waited=$SECONDS
if ! wait "$san_pid"; then
  echo "test.sh: the sanitizer build failed; its output:" >&2
  cat "$san_log" >&2
  exit 1
fi
tail -n 3 "$san_log"
san_took=$(($(cat "$san_done") - san_epoch))
stages+=("sanitizer build $(duration "$san_took") (beside the Release tests, then $(duration $((SECONDS - waited))) alone)")
timed "sanitizer tests" bash "$root/deploy/test-sanitize.sh" --test-only
summary
