# shellcheck shell=bash
# Sourced by test_ros2_decode.sh and test_foreign_decode.sh: prepare_decoder WORK_DIR installs Node.js and npm from
# Debian if missing, and the independent decoder (package-lock.json, the .mjs scripts) into WORK_DIR/decoder.
_decoder_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source-path=SCRIPTDIR source=../../node_tools.sh
source "$_decoder_dir/../../node_tools.sh"
prepare_decoder() {
  local work=$1 scripts=() f
  ensure_packages nodejs npm
  rm -rf "$work"
  for f in "$_decoder_dir"/*.mjs; do scripts+=("$(basename "$f")"); done
  install_npm_folder "$_decoder_dir" "$work/decoder" "${scripts[@]}"
}
