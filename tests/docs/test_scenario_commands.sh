#!/usr/bin/env bash
# The commands the shipped scenario files give in their header comments still run (issue #30, "docs that run"):
#   test_scenario_commands.sh BIN_DIR
# A header line "#   build/bin/<program> ..." or "#   deploy/<script> ..." is a command for the reader to copy. Each is
# run from the source tree as written, with build/bin standing for BIN_DIR (also first on PATH, for scripts that call
# the programs) and --dry-run appended, so nothing is flown, written or submitted; it must exit 0. A scenario file
# whose header gives no command is fine; a header command that no longer runs fails the test with its output.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=$(cd "$1" && pwd)
export PATH=$bin:$PATH
cd "$root"
ran=0
for file in deploy/scenarios/*.yaml; do
  # Header comments only: the lines before the first line that is not a comment.
  while IFS= read -r line; do
    [[ $line == \#* ]] || break
    command=${line#\#}
    command=${command#"${command%%[![:space:]]*}"}  # leading blanks
    [[ $command == build/bin/* || $command == deploy/* ]] || continue
    read -r -a words <<<"${command/#build\/bin\//$bin/}"
    ran=$((ran + 1))
    if ! output=$("${words[@]}" --dry-run 2>&1); then
      fail "$file: '$command --dry-run' exits non-zero:"$'\n'"$output"
    fi
    log "ok: $file: $command"
  done <"$file"
done
[[ $ran -gt 0 ]] || fail "no command found in the scenario headers (the extraction is broken)"
log "PASS: $ran command(s)"
