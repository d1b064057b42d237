#!/usr/bin/env bash
# Every program's --help reads in an 80-column terminal with its options first (issue #30):
#   test_help_width.sh PROGRAM...
# For each program: exit 0, no line wider than 80 columns, and (for the programs with an option list) "Options:"
# before any other paragraph after the usage, so a reader finds the options without scrolling past the details.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
[ $# -gt 0 ] || fail "usage: test_help_width.sh PROGRAM..."
width=80
checked=0
for path in "$@"; do
  program=$(basename "$path")
  [[ -x $path ]] || fail "$path is not built"
  # study_formation prints its usage on stderr and exits 2 for --help (a benchmark, not a user program).
  status=0
  text=$("$path" --help 2>&1) || status=$?
  [[ $status -eq 0 || $program == study_formation ]] || fail "$program --help exits $status"
  widest=$(awk '{ if (length($0) > m) { m = length($0); l = $0 } } END { print m }' <<<"$text")
  if ((widest > width)); then
    fail "$program --help has a line of $widest columns (at most $width):"$'\n'"$(awk -v w=$width 'length($0) > w' <<<"$text")"
  fi
  if grep -q '^Options:' <<<"$text"; then
    # The first paragraph after the usage lines is the option list.
    first=$(awk '/^Usage:/ { u = 1; next } u && /^$/ { b = 1; next } b && NF { print; exit }' <<<"$text")
    [[ $first == "Options:" ]] || fail "$program --help: after the usage comes '$first', not the options"
  fi
  checked=$((checked + 1))
  log "ok: $program --help: widest line $widest"
done
log "PASS: $checked programs"
