# shellcheck shell=bash
# Sourced by the scripted tests that check SWA with a Node.js program (tests/record, tests/live, tests/ros2) and by
# tests/bench/bench_record_live.sh: one failure format, one way to get Debian's packages, one way to install a
# pinned npm folder. NODE_TOOLS_TAG names the script in every line (default: its file name).
#   fail MESSAGE...                 "<tag>: FAIL: MESSAGE" on stderr, exit 1
#   ensure_packages PKG...          apt-get install the Debian packages whose program is missing (root); the package
#                                   index is refreshed only if the first attempt fails
#   install_npm_folder SRC DEST F... DEST gets SRC's package.json, package-lock.json and the files F, then `npm ci`:
#                                   exactly the versions of the lock file (npm's registry is reachable, nothing else)

: "${NODE_TOOLS_TAG:=$(basename "${BASH_SOURCE[${#BASH_SOURCE[@]}-1]}" .sh)}"

fail() {
  echo "$NODE_TOOLS_TAG: FAIL: $*" >&2
  exit 1
}

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
  echo "$NODE_TOOLS_TAG: installing ${need[*]} (Debian packages)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null 2>&1 || {
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${need[@]}"
  }
}

install_npm_folder() {
  local src=$1 dest=$2
  shift 2
  mkdir -p "$dest"
  cp "$src/package.json" "$src/package-lock.json" "$dest/"
  local f
  for f in "$@"; do cp "$src/$f" "$dest/"; done
  (cd "$dest" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
}
