#!/usr/bin/env bash
# The C and C++ sources are laid out as .clang-format says (issue 42): every .cpp, .hpp, .c and
# .h under apps/ bench/ examples/ fuzz/ include/ python/ src/ tests/, checked with Debian 12's
# clang-format-14 (another version lays some lines out differently). Prints the files that differ
# and the command that fixes them.
#   scripts/tests/check_format.sh [CLANG_FORMAT]
#   scripts/tests/check_format.sh --self-test [CLANG_FORMAT]  # the check fails on a misformatted file
set -euo pipefail
cd "$(dirname "$0")/../.."
self_test=""
if [[ ${1:-} == --self-test ]]; then self_test=1; shift; fi
clang_format=${1:-clang-format-14}
command -v "$clang_format" >/dev/null ||
  { echo "check_format: $clang_format not found (Debian package clang-format-14)" >&2; exit 1; }

if [[ -n $self_test ]]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  cp .clang-format "$work/"
  printf 'int   main( ) {return 0;}\n' >"$work/bad.cpp"
  printf 'int main() { return 0; }\n' >"$work/good.cpp"
  "$clang_format" --dry-run --Werror "$work/good.cpp" ||
    { echo "self-test: a well-formatted file was flagged" >&2; exit 1; }
  if "$clang_format" --dry-run --Werror "$work/bad.cpp" 2>/dev/null; then
    echo "self-test: a misformatted file passed" >&2; exit 1
  fi
  echo "self-test: ok"
  exit 0
fi

mapfile -d '' files < <(find apps bench examples fuzz include python src tests \
  -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.c' -o -name '*.h' \) -print0 | sort -z)
# In batches across the CPUs; clang-format names each file that differs in its warnings.
mapfile -t bad < <(printf '%s\0' "${files[@]}" |
  xargs -0 -n 64 -P "$(nproc)" "$clang_format" --dry-run --Werror 2>&1 |
  sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if ((${#bad[@]})); then
  printf '%s\n' "${bad[@]}"
  echo "${#bad[@]} of ${#files[@]} files differ from .clang-format; fix with:" >&2
  echo "  $clang_format -i ${bad[*]}" >&2
  exit 1
fi
echo "${#files[@]} files laid out as .clang-format says"
