#!/usr/bin/env bash
# ctest containers_swarm_4[_px4|_ardupilot]: builds the images from the binaries in BIN_DIR, runs dropout_4.yaml for
# 60 s of simulated time (lockstep) as 4 agent containers + simulator + monitor (with VEHICLE px4 or ardupilot also 4
# bridge containers, the simulator playing each UAV's autopilot), and checks cohesion in the monitor's summary.json
# (deploy/containers.sh test). Leaves no container or network behind, also on failure or timeout.
#
#   test_containers.sh BIN_DIR WORK_DIR [VEHICLE]
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"

if [ $# -ne 2 ] && [ $# -ne 3 ]; then
  echo "usage: test_containers.sh BIN_DIR WORK_DIR [direct|px4|ardupilot]" >&2
  exit 2
fi
bin_dir=$1
work=$2
vehicle=${3:-direct}
# A project name of its own: teardown removes exactly this test's containers and network (by compose label),
# including those of an earlier run of this test that was killed before its cleanup.
project=swa-ctest
# Below the ctest TIMEOUT (900 s), so that the cleanup below still runs when a step hangs.
budget_s=800

# shellcheck disable=SC2317  # run by the EXIT trap
cleanup() {
  bash "$root/deploy/containers.sh" down --project "$project" || true
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# The containers' fixed DDS domain (42, deploy/containers/compose.yaml), held against the tests that reserve domains
# of their own (tests/script_tools.sh): a test beside this one that looks at its whole domain never sees them.
hold_test_domain 42 120

rm -rf "$work"
mkdir -p "$work"
start=$SECONDS
rc=0
timeout "$budget_s" bash "$root/deploy/containers.sh" test --bin-dir "$bin_dir" --run-dir "$work/run" \
  --project "$project" --uavs 4 --vehicle "$vehicle" --scenario "$root/deploy/scenarios/dropout_4.yaml" \
  --set duration_s=60 --timeout-s 300 || rc=$?
echo "containers_swarm_4 ($vehicle): exit $rc after $((SECONDS - start)) s; run directory $work/run"

# deploy/containers/README.md, "By hand with podman-compose": its block, run as written once the images exist (issue
# #30, docs that run), with this test's project and run directory for `swa` and `/abs/run`, and 20 s simulated
# (SWA_SET in the environment, which the block leaves to the caller). `podman wait` prints the monitor's exit code.
by_hand() {
  local block
  block=$(awk '/^## By hand with podman-compose/ { s = 1 } s && /^```sh/ { b = 1; next } b && /^```/ { exit } b' \
    "$root/deploy/containers/README.md")
  [ -n "$block" ] || fail "no sh block under 'By hand with podman-compose' in deploy/containers/README.md"
  block=$(sed -E "s#/abs/run#$work/by_hand#g; s/-p swa /-p $project /; s/--project swa\b/--project $project/;
    s/\bswa_monitor_1\b/${project}_monitor_1/" <<<"$block")
  mkdir -p "$work/by_hand"
  local status=0 out
  out=$(cd "$root" && SWA_SET=duration_s=20 timeout 300 bash -e -c "$block" 2>&1) || status=$?
  echo "$out" | tail -n 5
  [ "$status" -eq 0 ] || fail "the README's by-hand block exits $status:"$'\n'"$block"$'\n'"$out"
  # The monitor's exit code, printed by `podman wait`: 0 PASS.
  grep -qx 0 <<<"$out" || fail "the README's by-hand block: the monitor did not exit 0 (PASS):"$'\n'"$out"
  [ -s "$work/by_hand/monitor/summary.json" ] || fail "the README's by-hand block wrote no monitor/summary.json"
  echo "containers_swarm_4: the README's by-hand block: PASS"
}
if [ "$rc" -eq 0 ] && [ "$vehicle" = direct ]; then by_hand; fi
if [ "$rc" -eq 124 ]; then
  echo "containers_swarm_4: FAILED: not finished within $budget_s s" >&2
fi
if [ "$rc" -ne 0 ]; then
  for f in "$work"/run/logs/*.log; do
    [ -f "$f" ] || continue
    echo "---- last lines of $f"
    tail -n 15 "$f"
  done
fi
exit "$rc"
