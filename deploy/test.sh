#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test, and the sanitizer stage (the labels
# unit, closedloop and fuzz again, built with ASan + UBSan: deploy/test-sanitize.sh). Ends with what each stage took.
#   bash deploy/test.sh                      everything (what CI runs)
#   bash deploy/test.sh [ctest args...]      the Release build and those ctest arguments only, e.g. -L unit
#
# The sanitizer build and its in-process tests run beside the Release tests, at the lowest CPU and I/O priority
# (nice 19, ionice idle): much of the Release suite's time is realtime runs that wait, and a nice-19 process gets
# about 1.5 % of a core that a test wants (CFS weights 15 against 1024), so it takes mostly idle time (measured: the
# suite 9 % longer beside the build, BENCHMARKS.md "Build and test time").
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

# Beside the Release tests: the check that every header compiles on its own (swa_headers_alone, in the Release build
# tree, once), then the sanitizer stage: its build, then its labels unit and closedloop (in-process runs, nothing on
# the wall clock), all in a session of their own (setsid, so that a failure here ends all of it, compilers and
# tests included). A new session is a new scheduler autogroup where the kernel has them (sched_autogroup_enabled):
# autogroups share the CPU evenly whatever their members' nice, so the group itself gets nice 19 too. Its label fuzz
# runs after the Release tests: its rogue publisher drives an agent in realtime, which is not for nice 19 on a busy
# host.
san_log=$(mktemp /tmp/swa-sanitize.XXXXXX.log)
san_times=$(mktemp /tmp/swa-sanitize.XXXXXX.times)
# The header check runs beside the sanitizer build, one compiler at a time (ninja's default would start four): the
# two together cost what the sanitizer build with the header check in it did, without the sanitizer's instrumentation.
setsid bash -c '{ echo 19 >/proc/self/autogroup; } 2>/dev/null
  date +%s >"$2"
  { nice -n 19 ionice -c 3 cmake --build "$3" --target swa_headers_alone -j 1 && date +%s >"$2.headers"; } &
  headers=$!
  nice -n 19 ionice -c 3 bash "$1" --build-only || exit 1
  wait "$headers" || exit 3
  cat "$2.headers" >>"$2"
  date +%s >>"$2"
  nice -n 19 ionice -c 3 bash "$1" --test-only --in-process || exit 2
  date +%s >>"$2"' _ "$root/deploy/test-sanitize.sh" "$san_times" "$build" >"$san_log" 2>&1 &
san_pid=$!
trap 'kill -TERM -- "-$san_pid" 2>/dev/null || true; rm -f "$san_log" "$san_times" "$san_times.headers"' EXIT
trap 'exit 130' INT  # so that the EXIT trap above also runs on Ctrl-C and on a CI job's SIGTERM
trap 'exit 143' TERM

timed "Release tests" ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
suite_end=$(date +%s)
san_rc=0
wait "$san_pid" || san_rc=$?
if [ "$san_rc" -ne 0 ]; then
  case "$san_rc" in
    3) what="the header check (swa_headers_alone)" ;;
    1) what="the sanitizer build" ;;
    *) what="the sanitizer tests (labels unit and closedloop)" ;;
  esac
  echo "test.sh: $what failed; its output:" >&2
  cat "$san_log" >&2
  exit 1
fi
grep -E "tests passed|Total Test time" "$san_log" || true
mapfile -t at <"$san_times"  # start, header check done, both builds done, tests done (epoch seconds)
after=$((at[3] > suite_end ? at[3] - suite_end : 0))
beside="header check $(duration $((at[1] - at[0]))) beside the sanitizer build $(duration $((at[2] - at[0])))"
stages+=("$beside and tests $(duration $((at[3] - at[2]))), beside the Release tests ($(duration "$after") after them)")
timed "sanitizer fuzz" bash "$root/deploy/test-sanitize.sh" --test-only --fuzz
summary
