# shellcheck shell=bash
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
