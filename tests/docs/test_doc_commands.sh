#!/usr/bin/env bash
# Every command the READMEs give a reader runs (issue #30, "docs that run"):
#   test_doc_commands.sh BIN_DIR BUILD_DIR
# The READMEs: README.md, deploy/README.md, deploy/containers/README.md, idl/runtime/dds/README.md (BENCHMARKS.md is a
# record of measurements, each with the command that made it at its commit, not instructions). The commands are the
# lines of their ```sh blocks (a line ending in '\' goes on; "a; b" and "a && b" are two commands; a trailing
# "# ..." is a comment); a block with a loop or a background job ('&') is one script, run whole. Each is run in
# order, as written, in a scratch folder that holds the
# source tree's deploy/ and BIN_DIR as build/bin (BIN_DIR also first on PATH), so every file a command writes lands
# there. How each command runs is decided by plan_of below; a command it does not know fails the test, so a new
# command in the docs needs a line there. The kinds:
#   run S      run it and expect exit status S, shortened: swa_launch and swa_batch get --set duration_s=3 (a later
#              --set wins), --live PORT becomes --live 0 (a free port), --domain D this test's own domain
#   script     a whole block, run as one script, expecting exit 0: duration_s=N becomes 3, SWA_DOMAIN=N this test's
#              domain, and files under /tmp/ go into the scratch folder
#   dry        a cluster or containers: run it with --dry-run appended (checks every argument and the scenario)
#   ctest      the tests a ctest selection names: listed (ctest -N with the same selection), at least one
#   ci FILE    the command is the test command or part of it: FILE must run it, and CI runs FILE
#   daemon     a server: started on a free port, it must still be up after 2 s; then stopped
#   after C    needs something running first: C is started in the background, stopped afterwards
#   by-test F  run as written by the test script F, which has what it needs (the container images)
#   names R    not run here: ROS 2 tools, Slurm's squeue (not on this machine), a container started by hand on a
#              drone; instead the names it uses (image, variables, topics, package) are checked against the project
# Everything runs in a mount namespace of its own with a private /dev/shm, so no shared-memory file of a stopped
# process outlives the test or meets another one.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
[ $# -eq 2 ] || fail "usage: test_doc_commands.sh BIN_DIR BUILD_DIR"
bin=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)

if [ -z "${SWA_DOC_TEST_INNER:-}" ]; then
  export SWA_DOC_TEST_INNER=1
  # shellcheck disable=SC2016  # $0 and $@ are the inner shell's
  exec unshare --mount --propagation private sh -c \
    'mount -t tmpfs -o mode=1777,size=1g swa-doc-shm /dev/shm && exec bash "$0" "$@"' "${BASH_SOURCE[0]}" "$bin" "$build"
fi

reserve_test_domain 60
export SWA_DOMAIN=$TEST_DOMAIN
export PATH=$bin:$PATH
export USER=${USER:-$(id -un)}
work=$(mktemp -d /tmp/swa-doc-commands.XXXXXX)
background=()
cleanup() {
  local pid
  for pid in ${background[@]+"${background[@]}"}; do kill "$pid" 2>/dev/null || true; done
  for pid in ${background[@]+"${background[@]}"}; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/build"
ln -s "$root/deploy" "$work/deploy"
ln -s "$root/agent" "$work/agent"
ln -s "$bin" "$work/build/bin"

# The commands of one markdown file: "FILE:LINE<TAB>COMMAND" per command; a script block is one record, its lines
# joined by the ASCII unit separator (\037).
commands_of() {
  awk -v file="$1" '
    function emit_block(   k, line, start, pending, n, parts, c, j, body) {
      if (script) {
        body = lines[1]
        for (k = 2; k <= count; ++k) body = body "\037" lines[k]
        printf "%s:%d\tscript:%s\n", file, first, body
        return
      }
      pending = ""
      for (k = 1; k <= count; ++k) {
        line = lines[k]
        if (pending != "") { line = pending " " line } else { start = first + k - 1 }
        if (line ~ /\\[[:space:]]*$/) { sub(/\\[[:space:]]*$/, "", line); pending = line; continue }
        pending = ""
        sub(/[[:space:]]+#.*$/, "", line)          # a trailing comment
        if (line ~ /^[[:space:]]*(#|$)/) continue  # a comment line or nothing
        n = split(line, parts, /[[:space:]]*(;|&&)[[:space:]]+/)
        for (j = 1; j <= n; ++j) {
          c = parts[j]; gsub(/^[[:space:]]+|[[:space:]]+$/, "", c); gsub(/[[:space:]]+/, " ", c)
          if (c != "") printf "%s:%d\t%s\n", file, start, c
        }
      }
    }
    /^```/ {
      if (inside) { inside = 0; emit_block() }
      else if ($0 ~ /^```sh[[:space:]]*$/) { inside = 1; script = 0; count = 0; first = NR + 1 }
      next
    }
    !inside { next }
    {
      lines[++count] = $0
      code = $0
      sub(/[[:space:]]+#.*$/, "", code)
      if (code ~ /(^|[;[:space:]])for[[:space:]]|&[[:space:]]*(done|$)/) script = 1
    }
  ' "$root/$1"
}

# How a command is checked (see the top of this file).
plan_of() {
  case $1 in
    "bash deploy/run.sh") echo "ci .ci/run" ;;
    "bash deploy/test.sh") echo "ci .ci/run" ;;
    "bash deploy/build.sh") echo "ci deploy/test.sh" ;;
    "bash deploy/test-sanitize.sh") echo "ci deploy/test.sh" ;;
    "bash deploy/test.sh "* | "ctest --test-dir build "*) echo ctest ;;
    "./build/bin/test_"*) echo "run 0" ;;
    *"swa_replay "*"--check --set "*) echo "run 1" ;;  # the README shows where the commands then differ
    *"swa_replay "*"--lockstep"*) echo "after swa_agent --id 0 --config out/rec/agent.yaml" ;;
    ./build/bin/swa_* | swa_launch\ *) echo "run 0" ;;
    "bash deploy/security/make-credentials.sh "*) echo "run 0" ;;
    # README "Use SWA in your own stack": install into a prefix, build the example against it, run it.
    "cmake --install build "* | "cmake -S agent/examples/"* | "cmake --build /tmp/"* | "/tmp/embed_agent/"*) echo "run 0" ;;
    # The Debian packages need a clean Debian 12 to install on: the package test's container.
    "cpack -G DEB "* | "apt-get install ./build/swa_"*) echo "by-test tests/package/test_deb.sh" ;;
    "deploy/slurm/submit-study.sh "* | "bash deploy/containers.sh "*) echo dry ;;
    "fast-discovery-server "*) echo daemon ;;
    script:*) echo script ;;
    # deploy/containers/README.md, "By hand with podman-compose": run as written by the containers test, which has
    # the images (a drone's own `podman run -d --network host` stays a names check below).
    "export CONTAINERS_CONF="* | "podman run --rm "* | "SWA_RUN_DIR="*"podman-compose "* | "podman wait "*)
      echo "by-test tests/containers/test_containers.sh" ;;
    "squeue "*) echo "names slurm" ;;
    "podman run "*) echo "names podman" ;;
    "colcon "* | "source install/setup.bash" | "export ROS_DOMAIN_ID="* | "ros2 "*) echo "names ros2" ;;
    *) echo unknown ;;
  esac
}

# The command as this test runs it: shorter runs, a free port, this test's domain; an install goes from the real build
# tree into the scratch folder's tmp/.
shortened() {
  local c=$1
  case $c in
    *swa_launch\ * | *swa_batch\ *) c+=" --set duration_s=3" ;;
    "cmake "* | /tmp/*)
      mkdir -p "$work/tmp"
      # /tmp/ first: the build tree may itself lie under /tmp (a CI clone).
      c=$(sed -E "s#(^| |=)/tmp/#\1$work/tmp/#g; s# build # $build #" <<<"$c")
      ;;
  esac
  c=$(sed -E "s/--live [0-9]+/--live 0/; s/--domain [0-9]+/--domain $TEST_DOMAIN/" <<<"$c")
  echo "$c"
}

# What the README's own first command leaves behind for the commands after it: out/run as deploy/run.sh writes it.
prepare_out_run() {
  [ -d "$work/out/run/standalone" ] && return
  (cd "$work" && swa_launch --scenario deploy/scenarios/dropout_8.yaml --compare standalone --out out/run \
    --set duration_s=3 >"$work/prepare_out_run.log" 2>&1) || {
    cat "$work/prepare_out_run.log" >&2
    fail "could not prepare out/run as deploy/run.sh writes it"
  }
}

# Checks standing in for a command not run here: the names it uses exist in the project.
check_names() {
  local what=$1 command=$2
  case $what in
    slurm) grep -q "squeue" "$root/deploy/slurm/submit-study.sh" || fail "submit-study.sh no longer mentions squeue" ;;
    podman)
      local image var file
      image=$(grep -oE 'localhost/swa-[a-z]+:latest' <<<"$command" || true)
      if [ -n "$image" ]; then
        [[ $image =~ swa-(agent|sim|monitor|bridge|batch): ]] || fail "'$command': image $image is not one containers.sh builds"
      fi
      # shellcheck disable=SC2013  # words: the paths
      for file in $(grep -oE 'deploy/[^ ]+' <<<"$command"); do
        [ -e "$root/$file" ] || fail "'$command': $file does not exist"
      done
      if [[ $command == "podman wait "* ]]; then
        grep -q "^  monitor:" "$root/deploy/containers/compose.yaml" || fail "'$command': compose.yaml has no service monitor"
      fi
      # shellcheck disable=SC2013  # words: the variable names
      for var in $(grep -oE -- '-e [A-Z_]+=' <<<"$command" | sed -E 's/-e ([A-Z_]+)=/\1/'); do
        grep -rq "$var" "$root/deploy/containers/swa-entrypoint" "$root/idl/runtime/dds" "$root/deploy/README.md" ||
          fail "'$command': $var is read by nothing the image runs"
      done
      ;;
    ros2)
      [ -f "$root/idl/swa_msgs/package.xml" ] || fail "idl/swa_msgs is no ROS 2 package (package.xml missing)"
      if [[ $command == ros2\ * ]]; then
        local topic last
        # shellcheck disable=SC2013  # words: the topic names
        for topic in $(grep -oE '/swa/[a-z0-9_/]+' <<<"$command"); do
          last=${topic##*/}
          grep -qE "[\"/]$last\"" "$root/idl/runtime/dds/include/swa/dds/topics.h" ||
            fail "'$command': topic $topic is not one SWA writes (swa/dds/topics.h)"
        done
      fi
      ;;
  esac
}

ran=0
# The commands come on descriptor 3: a command reading its standard input must not eat the list.
while IFS=$'\t' read -r -u 3 where command; do
  read -r kind arg <<<"$(plan_of "$command")"
  case $kind in
    unknown) fail "$where: '$command' is a documented command this test does not know: add it to plan_of" ;;
    ci)
      script=${command#bash }
      script=${script%% *}
      grep -qF "$script" "$root/$arg" || fail "$where: '$command' is not run by $arg"
      [ "$arg" = .ci/run ] || grep -qF "$arg" "$root/.ci/run" || fail "$arg is not run by .ci/run"
      log "ok (CI runs it through $arg): $command"
      ;;
    by-test)
      key="By hand with podman-compose"  # the containers test runs that README section
      [[ $arg != tests/package/* ]] || key=${command%% *}" "  # the package test runs cpack and apt-get itself
      grep -qF -- "$key" "$root/$arg" || fail "$where: '$command' is not run by $arg"
      log "ok (run as written by $arg): $command"
      ;;
    ctest)
      selection=$(sed -E 's/^(bash deploy\/test.sh|ctest --test-dir build)//; s/ -V//' <<<"$command")
      # shellcheck disable=SC2086  # the selection is words, as in the docs
      listed=$(ctest --test-dir "$build" -N $selection | sed -nE 's/^Total Tests: ([0-9]+)$/\1/p')
      [ "${listed:-0}" -gt 0 ] || fail "$where: '$command' selects no test"
      log "ok ($listed test(s) selected): $command"
      ;;
    run | dry | after)
      [[ $command != *"swa_monitor --combine"* ]] || prepare_out_run
      run=$(shortened "$command")
      expected=${arg:-0}
      [ "$kind" != dry ] || run+=" --dry-run"
      swarm=()
      if [ "$kind" = after ]; then
        expected=0
        # The two processes started by hand find each other in a swarm (DDS partition) of their own.
        swarm=("SWA_SWARM=doc-test-$$")
        # shellcheck disable=SC2086  # the command's words
        (cd "$work" && exec env "${swarm[@]}" $arg >"$work/after.log" 2>&1) &
        background+=($!)
      fi
      status=0
      (cd "$work" && env ${swarm[@]+"${swarm[@]}"} timeout 120 bash -c "$run") </dev/null >"$work/command.log" 2>&1 ||
        status=$?
      if [ "$kind" = after ]; then
        kill "${background[-1]}" 2>/dev/null || true
        wait "${background[-1]}" 2>/dev/null || true
        unset 'background[-1]'
      fi
      [ "$status" -eq "$expected" ] ||
        fail "$where: '$run' exits $status, not $expected:"$'\n'"$(tail -n 20 "$work/command.log")"
      log "ok (exit $status): $run"
      ;;
    daemon)
      started=0
      for port in $((20811 + TEST_DOMAIN)) $((21811 + TEST_DOMAIN)) $((22811 + TEST_DOMAIN)); do
        run=$(sed -E "s/-p [0-9]+/-p $port/" <<<"$command")
        (cd "$work" && exec $run) >"$work/daemon.log" 2>&1 &
        pid=$!
        background+=("$pid")
        sleep 2
        if kill -0 "$pid" 2>/dev/null; then started=1; fi
        kill "$pid" 2>/dev/null || true
        wait "$pid" 2>/dev/null || true
        unset 'background[-1]'
        [ "$started" -eq 0 ] || break
      done
      [ "$started" -eq 1 ] || fail "$where: '$command' did not stay up:"$'\n'"$(tail -n 20 "$work/daemon.log")"
      log "ok (up for 2 s): $run"
      ;;
    script)
      body=$(tr '\037' '\n' <<<"${command#script:}" |
        sed -E "s/duration_s=[0-9]+/duration_s=3/g; s/SWA_DOMAIN=[0-9]+/SWA_DOMAIN=$TEST_DOMAIN/g; s#/tmp/#$work/tmp/#g")
      mkdir -p "$work/tmp"
      status=0
      (cd "$work" && timeout 120 bash -e -c "$body") </dev/null >"$work/command.log" 2>&1 || status=$?
      [ "$status" -eq 0 ] || fail "$where: the block exits $status:"$'\n'"$body"$'\n'"$(tail -n 20 "$work/command.log")"
      log "ok (exit 0): the block of $where"
      ;;
    names)
      check_names "$arg" "$command"
      log "ok (not run; the names it uses checked): $command"
      ;;
  esac
  ran=$((ran + 1))
done 3< <(for doc in README.md deploy/README.md deploy/containers/README.md idl/runtime/dds/README.md; do commands_of "$doc"; done)
[ "$ran" -gt 20 ] || fail "only $ran command(s) found in the docs (the extraction is broken)"
log "PASS: $ran documented commands"
