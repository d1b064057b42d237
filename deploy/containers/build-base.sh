#!/usr/bin/env bash
# Builds the local Debian 12 base image that every SWA image starts FROM, once: no container registry is reachable,
# so the image is made from Debian packages with debootstrap and imported. An existing image is reused.
#
#   build-base.sh [--engine podman] [--image NAME] [--mirror URL] [--rebuild]
#
# Needs root, debootstrap and the engine (deploy/containers.sh installs them).
set -euo pipefail

engine=podman
image=localhost/swa-debian-base:bookworm
# The same archive the host's apt uses; SWA_DEBIAN_MIRROR points at another one (a local mirror, a proxy).
mirror=${SWA_DEBIAN_MIRROR:-http://deb.debian.org/debian}
rebuild=0

usage() {
  sed -n '2,7p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
}

while [ $# -gt 0 ]; do
  case $1 in
    --engine) engine=$2; shift 2 ;;
    --image) image=$2; shift 2 ;;
    --mirror) mirror=$2; shift 2 ;;
    --rebuild) rebuild=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "build-base: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

if [ "$rebuild" -eq 0 ] && "$engine" image exists "$image" 2>/dev/null; then
  echo "build-base: $image present, reused"
  exit 0
fi

rootfs=$(mktemp -d /var/tmp/swa-base-rootfs.XXXXXX)
log=$(mktemp /var/tmp/swa-base-debootstrap.XXXXXX)
cleanup() { rm -rf --one-file-system "$rootfs" "$log"; }
trap cleanup EXIT

echo "build-base: debootstrap --variant=minbase bookworm from $mirror"
start=$SECONDS
# minbase: essential packages and apt only; the images add just the runtime libraries the binaries link.
debootstrap --variant=minbase bookworm "$rootfs" "$mirror" > "$log" 2>&1 || {
  tail -n 30 "$log" >&2
  echo "build-base: debootstrap failed" >&2
  exit 1
}

# Point-release and security updates too, so the images get the same library versions as a host that is up to
# date (the binaries copied in were linked on such a host).
rm -f "$rootfs/etc/apt/sources.list"
security_mirror=${SWA_DEBIAN_SECURITY_MIRROR:-${mirror%/debian}/debian-security}
cat > "$rootfs/etc/apt/sources.list.d/debian.sources" <<EOF
Types: deb
URIs: $mirror
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb
URIs: $security_mirror
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
# Images install with --no-install-recommends anyway; this keeps ad-hoc installs in a running container small too.
printf 'APT::Install-Recommends "false";\nAPT::Install-Suggests "false";\n' \
  > "$rootfs/etc/apt/apt.conf.d/90swa-no-recommends"
rm -rf "$rootfs"/var/cache/apt/archives/*.deb "$rootfs"/var/lib/apt/lists/*

tar -C "$rootfs" --numeric-owner -c . |
  "$engine" import --quiet --change 'CMD ["/bin/bash"]' \
    --change 'LABEL org.opencontainers.image.description="Debian 12 minbase for SWA (build-base.sh)"' \
    - "$image" > /dev/null
echo "build-base: $image built in $((SECONDS - start)) s"
