# shellcheck shell=bash
# Sourced by test_ros2_decode.sh and test_foreign_decode.sh: prepare_decoder WORK_DIR installs Node.js and npm from
# Debian if missing, and the independent decoder (package-lock.json, the .mjs scripts) into WORK_DIR/decoder.
prepare_decoder() {
  local work=$1 from
  from=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    echo "prepare_decoder: installing nodejs and npm (Debian packages)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends nodejs npm
  fi
  rm -rf "$work"
  mkdir -p "$work/decoder"
  cp "$from/package.json" "$from/package-lock.json" "$from"/*.mjs "$work/decoder/"
  (cd "$work/decoder" && npm ci --no-audit --no-fund --loglevel=error)
}
