#!/usr/bin/env bash
# ctest sources_are_clang_formatted: every C++ file under agent/, sim/, monitor/, idl/, deploy/ and tests/ is as
# clang-format leaves it with the tree's .clang-format (Debian 12's clang-format 14: another version may disagree on a
# few constructs, and says so); and the check can fail: a file formatted otherwise is refused.
#   test_format.sh SOURCE_DIR
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
src=$1
command -v clang-format >/dev/null || fail "clang-format is missing (bash deploy/install-deps.sh installs it)"
version=$(clang-format --version)
[[ $version =~ version\ 14\. ]] || log "$version: the tree is formatted with clang-format 14, this one may disagree"

work=$(mktemp -d /tmp/swa_format.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$src"
mapfile -t files < <(find agent sim monitor idl deploy tests \( -name '*.cpp' -o -name '*.h' \) -type f | sort)
[ ${#files[@]} -gt 100 ] || fail "only ${#files[@]} C++ files under $src"
# Two clang-formats at a time, 40 files each; every complaint names its file and line.
if ! printf '%s\0' "${files[@]}" | xargs -0 -n 40 -P "$(nproc)" clang-format --dry-run -Werror 2> "$work/out"; then
  grep -E '^[^ ].*: error:' "$work/out" | sed 's/ \[-Wclang-format-violations\]//' | head -40 >&2
  fail "$(grep -c ': error:' "$work/out") place(s) not as clang-format writes them; clang-format -i FILE... fixes them"
fi

cp .clang-format "$work/"
printf 'int  f( int a ){return a;}\n' > "$work/bad.cpp"
(cd "$work" && clang-format --dry-run -Werror bad.cpp 2> /dev/null) && fail "a misformatted file was accepted"
log "${#files[@]} C++ files as clang-format writes them; a misformatted file is refused"
