#!/usr/bin/env bash
# Installs, from Debian 12 packages only, exactly what SWA needs to build and test. Idempotent: packages that are
# already present are not touched, and apt is not contacted at all when nothing is missing.
set -euo pipefail

# libgmock-dev: Debian's GTestConfig.cmake declares the gmock targets too and fails to import without it.
# libnetfilter-queue-dev: the packet-loss emulator of the `loss` tests (tests/loss/swa_netem.cpp).
# libwebsocketpp-dev, libasio-dev: the monitor's live view (swa_monitor --live: a WebSocket server, standalone asio).
# clang-format: the ctest sources_are_clang_formatted (tests/layers/test_format.sh).
# ninja-build, ccache, mold: build speed only (deploy/build.sh, CMakeLists.txt); the build works without them.
packages=(
  build-essential cmake ninja-build ccache mold clang-format
  libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools openssl libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pkg-config libnetfilter-queue-dev
  libwebsocketpp-dev libasio-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run as root (or with sudo) to install them" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
