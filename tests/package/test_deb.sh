#!/usr/bin/env bash
# ctest package_debs_install_on_debian12 (issue #47): `cpack -G DEB` makes swa (the programs, profiles, scenarios) and
# swa-dev (headers, static libraries, the CMake package, pkg-config) from the build; both install with apt on a clean
# Debian 12 (the containers' debootstrap base image, which has no SWA and no Fast DDS), which fetches what their
# computed dependencies name from Debian's archive; then the installed programs run there.
#   test_deb.sh BUILD_DIR
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
build=$1
work=$(mktemp -d /tmp/swa_deb.XXXXXX)
name=swa-deb-test-$$
# shellcheck disable=SC2317  # run by the EXIT trap
cleanup() {
  podman rm -f "$name" > /dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

bash "$root/deploy/containers.sh" install > "$work/tools.log" 2>&1 || { cat "$work/tools.log" >&2; fail "podman"; }
export CONTAINERS_CONF=$root/deploy/containers/containers.conf
timeout 600 bash "$root/deploy/containers/build-base.sh" > "$work/base.log" 2>&1 ||
  { cat "$work/base.log" >&2; fail "the Debian 12 base image"; }

cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work" > "$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log" >&2; fail "cpack -G DEB"; }
runtime=$(find "$work" -maxdepth 1 -name 'swa_*.deb')
dev=$(find "$work" -maxdepth 1 -name 'swa-dev_*.deb')
[ -f "$runtime" ] && [ -f "$dev" ] || fail "cpack made $(ls "$work"/*.deb 2> /dev/null | xargs -n1 basename | tr '\n' ' ')"
depends=$(dpkg-deb -f "$runtime" Depends)
[[ $depends == *libfastrtps2.9* && $depends == *libyaml-cpp* ]] || fail "swa's Depends miss libraries: $depends"
dpkg-deb -c "$dev" > "$work/dev.list"
grep -q 'swa-config.cmake$' "$work/dev.list" || fail "swa-dev has no CMake package"

# --network host: apt reaches the archive as the host does (the build of the images does the same).
timeout 500 podman run --name "$name" --network host -v "$work:/debs:ro" localhost/swa-debian-base:bookworm sh -ec '
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends /debs/swa_*.deb /debs/swa-dev_*.deb \
    > /tmp/apt.log 2>&1 || { tail -20 /tmp/apt.log; exit 1; }
  swa_launch --help | head -1
  swa_sim --help > /dev/null
  swa_agent --help > /dev/null
  test -f /usr/share/swa/profiles.xml
  find /usr -name swa-config.cmake | grep -q .
' > "$work/container.log" 2>&1 || { cat "$work/container.log" >&2; fail "the packages on a clean Debian 12"; }
grep -q "swa_launch" "$work/container.log" || fail "swa_launch --help printed nothing: $(cat "$work/container.log")"
log "$(basename "$runtime") and $(basename "$dev") installed with apt on a clean Debian 12; swa_launch --help runs there"
