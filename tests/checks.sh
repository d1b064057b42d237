# shellcheck shell=bash
# Shared by the scripted tests (tests/netns, tests/loss): log lines tagged with the test's name, and checks that
# collect their failures instead of stopping at the first, so one run reports every problem at once.
# Source it with CHECK_TAG set (the tag of every line, e.g. netns).

FAILED=()

log() { printf '%s: %s\n' "$CHECK_TAG" "$*"; }
die() {
  printf '%s: ERROR: %s\n' "$CHECK_TAG" "$*" >&2
  exit 1
}

# check NAME DETAIL CMD...: runs CMD; its status is the check's outcome.
check() {
  local name=$1 detail=$2
  shift 2
  if "$@"; then
    printf '%s:   PASS  %-62s %s\n' "$CHECK_TAG" "$name" "$detail"
  else
    printf '%s:   FAIL  %-62s %s\n' "$CHECK_TAG" "$name" "$detail"
    FAILED+=("$name ($detail)")
  fi
}

# Float comparisons for check. An empty or "null" value (a field missing from a summary) never passes.
within() { awk -v lo="$1" -v hi="$2" -v x="$3" 'BEGIN { exit !(x != "" && x != "null" && x >= lo && x <= hi) }'; }
at_most() { awk -v max="$1" -v x="$2" 'BEGIN { exit !(x != "" && x != "null" && x <= max) }'; }
at_least() { awk -v min="$1" -v x="$2" 'BEGIN { exit !(x != "" && x != "null" && x >= min) }'; }
greater() { awk -v min="$1" -v x="$2" 'BEGIN { exit !(x != "" && x != "null" && x > min) }'; }

# At the end: every failed check, and status 1 if there was one.
report_checks() {
  [[ ${#FAILED[@]} -eq 0 ]] && return 0
  printf '%s: FAILED %d check(s):\n' "$CHECK_TAG" "${#FAILED[@]}"
  printf '%s:   %s\n' "$CHECK_TAG" "${FAILED[@]}"
  return 1
}
