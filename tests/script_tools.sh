# shellcheck shell=bash disable=SC2034  # here, root and TEST_DOMAIN are for the sourcing script
# Sourced first by every scripted test and benchmark script, as
#   source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
# It sets strict mode (set -euo pipefail) and
#   here, root                      the sourcing script's folder, the source tree
#   TEST_TAG                        names the script in every line (default: its file name; set it to change)
# and gives
#   log MESSAGE...                  "<tag>: MESSAGE" on stdout
#   fail MESSAGE... (die)           "<tag>: FAIL: MESSAGE" on stderr, exit 1
#   ensure_packages PKG...          apt-get install the Debian packages whose program is missing (root); the package
#                                   index is refreshed only if the first attempt fails
#   install_npm_folder SRC DEST [F...]
#                                   DEST gets SRC's package.json, package-lock.json and the files F (default: SRC's
#                                   .mjs files), then `npm ci`: exactly the versions of the lock file (npm's registry
#                                   is reachable, nothing else); Node.js and npm come from Debian if missing
#   reserve_test_domain FIRST, hold_test_domain D WAIT_S
#                                   a DDS domain of the test's own among SWA's tests on this host (below)
#   check NAME DETAIL CMD..., within/at_most/at_least/greater, report_checks
#                                   checks that collect their failures, so one run reports every problem at once

set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[${#BASH_SOURCE[@]}-1]}")" && pwd)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
: "${TEST_TAG:=$(basename "${BASH_SOURCE[${#BASH_SOURCE[@]}-1]}" .sh)}"

log() { printf '%s: %s\n' "$TEST_TAG" "$*"; }
fail() {
  printf '%s: FAIL: %s\n' "$TEST_TAG" "$*" >&2
  exit 1
}
die() { fail "$@"; }

# The program a Debian package provides, where the names differ.
_program_of() {
  case $1 in
    nodejs) echo node ;;
    *) echo "$1" ;;
  esac
}

ensure_packages() {
  local need=() p
  for p in "$@"; do
    command -v "$(_program_of "$p")" >/dev/null || need+=("$p")
  done
  [ ${#need[@]} -eq 0 ] && return 0
  echo "$TEST_TAG: installing ${need[*]} (Debian packages)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null 2>&1 || {
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${need[@]}"
  }
}

install_npm_folder() {
  local src=$1 dest=$2
  shift 2
  ensure_packages nodejs npm
  mkdir -p "$dest"
  cp "$src/package.json" "$src/package-lock.json" "$dest/"
  local f
  if [ $# -eq 0 ]; then
    cp "$src"/*.mjs "$dest/"
  else
    for f in "$@"; do cp "$src/$f" "$dest/"; done
  fi
  (cd "$dest" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
}

# A DDS domain reserved among SWA's tests on this host (the C++ side: tests/integration/test_domain.h). Tests run two
# at a time (ctest -j2), and a test that looks at a whole domain (processes by --domain, an audit's observer) must
# never share one with another; the swarm partition each swa_launch run gets only keeps their samples apart.
#
# reserve_test_domain FIRST: sets TEST_DOMAIN to FIRST or the next domain (1..232, wrapping) whose lock file
# /tmp/swa-test-domain-<d>.lock no other test holds, and holds it (an exclusive flock on a descriptor this shell keeps
# open) until the script ends. Fails when all 232 are taken.
reserve_test_domain() {
  local d=$1 k
  for ((k = 0; k < 232; k++)); do
    d=$(((d - 1) % 232 + 1))
    exec {TEST_DOMAIN_FD}>>"/tmp/swa-test-domain-$d.lock"
    if flock -n "$TEST_DOMAIN_FD"; then
      TEST_DOMAIN=$d
      return 0
    fi
    exec {TEST_DOMAIN_FD}>&-
    d=$((d + 1))
  done
  echo "no free DDS domain: all 232 are reserved by other tests" >&2
  return 1
}

# hold_test_domain D WAIT_S: sets TEST_DOMAIN to D itself and holds it like reserve_test_domain, waiting up to WAIT_S
# seconds for a test that has it to end: for a swarm on a fixed domain (the containers' 42). Fails after that.
hold_test_domain() {
  exec {TEST_DOMAIN_FD}>>"/tmp/swa-test-domain-$1.lock"
  if ! flock -w "$2" "$TEST_DOMAIN_FD"; then
    echo "DDS domain $1 is still reserved by another test after $2 s" >&2
    return 1
  fi
  TEST_DOMAIN=$1
}

FAILED=()

# check NAME DETAIL CMD...: runs CMD; its status is the check's outcome.
check() {
  local name=$1 detail=$2
  shift 2
  if "$@"; then
    printf '%s:   PASS  %-62s %s\n' "$TEST_TAG" "$name" "$detail"
  else
    printf '%s:   FAIL  %-62s %s\n' "$TEST_TAG" "$name" "$detail"
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
  printf '%s: FAILED %d check(s):\n' "$TEST_TAG" "${#FAILED[@]}"
  printf '%s:   %s\n' "$TEST_TAG" "${FAILED[@]}"
  return 1
}
