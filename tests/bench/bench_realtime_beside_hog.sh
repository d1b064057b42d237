#!/usr/bin/env bash
# Do the realtime tests hold on a busy host (issue #46)? Every test of the suite that runs on the wall clock (those
# holding ctest's resource lock swa_realtime and those that run alone, RUN_SERIAL: tests/CMakeLists.txt) is run RUNS
# times beside a CPU hog, one test at a time; not a ctest (hours of runs); results in BENCHMARKS.md.
#
#   bench_realtime_beside_hog.sh [--build DIR] [--filter REGEX] [--hogs K] RUNS
#     --build DIR     the configured build tree (default: build)
#     --filter REGEX  only the realtime tests whose name matches (grep -E), to split the work across sittings
#     --hogs K        busy loops beside the tests, each worth a whole core while it runs (default: 1)
#     --list          print the realtime tests (after --filter) and exit
#     RUNS            runs of each test
#
# Rounds: each selected test once, then again, RUNS rounds; a round-robin spreads each test's runs over the whole
# sitting. Each run is `ctest -R '^NAME$' --timeout 600` with the hog running at the same (default) priority. Printed
# per test: passes / runs, median and max wall seconds; then each failed run's log (kept in the work folder, named at
# the start and the end). The work folder's runs.txt grows run by run, so a stopped sitting can still be counted.
# The hog is killed on exit, however the script ends.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"

usage() { sed -n '2,/^# shellcheck/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; }
build=$root/build
filter=
hogs=1
runs=
list=0
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=${2:?--build needs a directory}; shift 2 ;;
    --filter) filter=${2:?--filter needs a regular expression}; shift 2 ;;
    --hogs) hogs=${2:?--hogs needs a count}; shift 2 ;;
    --list) list=1; shift ;;
    -h | --help) usage; exit 0 ;;
    -*) echo "bench_realtime_beside_hog: unknown option $1 (--help)" >&2; exit 2 ;;
    *) [ -z "$runs" ] || { echo "bench_realtime_beside_hog: one RUNS only (--help)" >&2; exit 2; }; runs=$1; shift ;;
  esac
done
if ! [[ $hogs =~ ^[0-9]+$ ]] || [ "$hogs" -gt 16 ]; then
  echo "bench_realtime_beside_hog: --hogs in 0..16 (--help)" >&2
  exit 2
fi
[ "$list" = 1 ] || [[ $runs =~ ^[1-9][0-9]*$ ]] ||
  { echo "bench_realtime_beside_hog: RUNS must be a positive number (--help)" >&2; exit 2; }
[ -f "$build/CTestTestfile.cmake" ] || fail "no configured build tree at $build (bash deploy/build.sh)"

# The tests that hold the lock or run alone, from ctest's own description of the suite.
mapfile -t tests < <(ctest --test-dir "$build" --show-only=json-v1 | python3 -c '
import json, sys
for t in json.load(sys.stdin)["tests"]:
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    if "swa_realtime" in props.get("RESOURCE_LOCK", []) or props.get("RUN_SERIAL"):
        print(t["name"])
')
if [ -n "$filter" ]; then
  mapfile -t tests < <(printf '%s\n' "${tests[@]}" | grep -E -- "$filter" || true)
fi
[ "${#tests[@]}" -gt 0 ] || fail "no realtime test${filter:+ matches $filter}"
if [ "$list" = 1 ]; then
  printf '%s\n' "${tests[@]}"
  exit 0
fi

work=$(mktemp -d /tmp/swa_bench_hog.XXXXXX)
hog_pids=()
stop_hogs() { [ "${#hog_pids[@]}" -eq 0 ] || kill "${hog_pids[@]}" 2>/dev/null || true; }
trap stop_hogs EXIT
for ((h = 0; h < hogs; h++)); do
  bash -c 'while :; do :; done' &
  hog_pids+=($!)
done
log "${#tests[@]} realtime test(s), $runs round(s), $hogs hog(s); work in $work"

: > "$work/runs.txt"
for ((r = 1; r <= runs; r++)); do
  for t in "${tests[@]}"; do
    # ctest's -R is a regular expression: the name's own metacharacters (GoogleTest's "/" and quotes are harmless,
    # parentheses and dots are not) are escaped.
    pattern="^$(printf '%s' "$t" | sed 's/[][().*+?^$|\\{}]/\\&/g')\$"
    out="$work/run_${r}_$(printf '%s' "$t" | tr -c 'A-Za-z0-9_.-' '_').log"
    start=$(date +%s.%N)
    status=0
    ctest --test-dir "$build" -R "$pattern" --timeout 600 --output-on-failure > "$out" 2>&1 || status=$?
    end=$(date +%s.%N)
    grep -q "tests passed, 0 tests failed out of 1" "$out" || [ "$status" -ne 0 ] || status=99  # matched nothing
    [ "$status" -ne 0 ] || rm -f "$out"
    printf '%s %d %s %.2f\n' "$t" "$r" "$status" "$(echo "$end - $start" | bc)" >> "$work/runs.txt"
  done
  log "round $r of $runs done: $(awk '$3 != 0' "$work/runs.txt" | wc -l) failed run(s) so far"
done
stop_hogs

python3 - "$work/runs.txt" <<'EOF'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    name, _round, status, wall = line.rsplit(" ", 3)
    rows.setdefault(name, []).append((int(status), float(wall)))
print("| test | passes / runs | wall s, median / max |")
print("|---|---|---|")
for name, runs in rows.items():
    walls = [w for _, w in runs]
    passes = sum(1 for s, _ in runs if s == 0)
    print(f"| {name} | {passes} / {len(runs)} | {statistics.median(walls):.1f} / {max(walls):.1f} |")
total = sum(len(r) for r in rows.values())
failed = sum(1 for r in rows.values() for s, _ in r if s != 0)
print(f"\n{total - failed} of {total} runs passed")
EOF
failed_logs=$(find "$work" -name 'run_*.log' | sort)
[ -z "$failed_logs" ] || log "failed runs' logs: $failed_logs"
log "work in $work"
