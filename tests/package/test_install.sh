#!/usr/bin/env bash
# ctest package_install_is_usable (issue #47): SWA installed into a prefix, the prefix moved elsewhere (the package is
# relocatable), then used as an outside project uses it:
#   - agent/examples/embed_agent, its own CMake project, finds it with find_package(swa) and links swa::agent_core; fed
#     samples recorded from an in-process run, it prints exactly the commands SWA's own agent core gives for them
#     (write_agent_samples), and it runs on the samples shipped beside it;
#   - the same main.cpp built with pkg-config's flags alone (swa-agent-core.pc) prints the same;
#   - tests/package/dds_consumer links swa::dds and makes a participant with the installed profiles;
#   - the installed programs find the installed profiles themselves, and swa_launch --help runs.
#   test_install.sh BUILD_DIR WRITE_AGENT_SAMPLES
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
build=$1
writer=$2
work=$(mktemp -d /tmp/swa_install.XXXXXX)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/staged" > "$work/install.log" || { cat "$work/install.log" >&2; fail "install"; }
mv "$work/staged" "$work/prefix"
prefix=$work/prefix
for f in bin/swa_launch bin/swa_agent share/swa/profiles.xml share/swa/scenarios/dropout_4.yaml \
  share/swa/security/make-credentials.sh include/swa/agent/agent.h include/swa/dds/participant.h \
  include/swa/msg/Imu.h; do
  [ -e "$prefix/$f" ] || fail "$f not installed"
done
config=$(find "$prefix" -name swa-config.cmake)
[ -n "$config" ] && [ -f "$(dirname "$config")/swa-config-version.cmake" ] || fail "no CMake package with its version"
grep -rq "$work/staged" "$prefix" && fail "the install names its first place: $(grep -rl "$work/staged" "$prefix")"

# The outside projects, configured against the moved prefix.
configure_and_build() {  # SOURCE BINARY
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" > "$2.log" 2>&1 &&
    cmake --build "$2" >> "$2.log" 2>&1 || { cat "$2.log" >&2; fail "$1 did not build against the install"; }
}
example=$root/agent/examples/embed_agent
configure_and_build "$example" "$work/example"
configure_and_build "$here/dds_consumer" "$work/consumer"

"$writer" "$root/deploy/scenarios/dropout_4.yaml" 6 1 "$work/samples.txt" "$work/expected.txt"
"$work/example/embed_agent" "$work/samples.txt" > "$work/printed.txt" 2> "$work/example.err" ||
  fail "embed_agent failed: $(cat "$work/example.err")"
lines=$(wc -l < "$work/expected.txt")
[ "$lines" -ge 500 ] || fail "only $lines commands recorded for 6 s at 100 Hz"
cmp -s "$work/printed.txt" "$work/expected.txt" ||
  fail "embed_agent's commands differ from SWA's own: $(diff "$work/printed.txt" "$work/expected.txt" | head -4)"
grep -q " 0 input(s) rejected" "$work/example.err" || fail "embed_agent rejected inputs: $(cat "$work/example.err")"
shipped=$("$work/example/embed_agent" "$example/samples.txt" | wc -l)
[ "$shipped" -eq "$(grep -c '^imu ' "$example/samples.txt")" ] || fail "$shipped commands for the shipped samples"

pc_dir=$(dirname "$(find "$prefix" -name swa-agent-core.pc)")
pc_flags=$(PKG_CONFIG_PATH=$pc_dir pkg-config --cflags --libs swa-agent-core) || fail "pkg-config: no swa-agent-core"
g++ -std=c++17 -O2 "$example/main.cpp" $pc_flags -o "$work/embed_pc" || fail "main.cpp with pkg-config's flags"
"$work/embed_pc" "$work/samples.txt" 2> /dev/null | cmp -s - "$work/expected.txt" ||
  fail "built with pkg-config, embed_agent prints other commands"

reserve_test_domain 150
out=$("$work/consumer/dds_consumer" --domain "$TEST_DOMAIN") || fail "dds_consumer: $out"
grep -q "^profiles $prefix/share/swa/profiles.xml$" <<< "$out" || fail "SWA_PROFILES_FILE is not the moved prefix's: $out"
grep -q "^participant up" <<< "$out" || fail "no participant: $out"

# Installed programs find the installed profiles (not the source tree's), wherever the prefix lies.
timeout -s TERM 5 "$prefix/bin/swa_agent" --id 0 --domain "$TEST_DOMAIN" 2> "$work/agent.err" || true
grep -q "profiles $prefix/share/swa/profiles.xml" "$work/agent.err" ||
  fail "the installed swa_agent did not take the installed profiles: $(head -3 "$work/agent.err")"
help=$("$prefix/bin/swa_launch" --help) || fail "swa_launch --help"
grep -q "swa_launch" <<< "$help" || fail "swa_launch --help says nothing of itself"
log "installed, moved, used: embed_agent (CMake and pkg-config) gives SWA's own $lines commands bit for bit, dds_consumer makes a participant, swa_launch --help runs"
