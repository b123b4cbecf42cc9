#!/usr/bin/env bash
# Checks that every C++ file is laid out as .clang-format says (clang-format 14, Debian 12's; other
# versions lay some lines out differently). CTest runs it as `repo.format`.
#   bash scripts/check_format.sh          list the files that differ, exit 1 if any
#   bash scripts/check_format.sh --fix    format them in place
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check_format: clang-format is not installed (bash scripts/setup.sh clang-format)" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.h' '*.cpp')
if [ "${1:-}" == --fix ]; then
  clang-format -i "${files[@]}"
  exit
fi
# One clang-format for every file (a process per file took 30 s): it names each line it would
# change as "FILE:LINE:COLUMN: error: code should be clang-formatted".
report=$(clang-format --dry-run -Werror "${files[@]}" 2>&1) && status=0 || status=$?
mapfile -t bad < <(grep -oE '^[^:]+(:[0-9]+){2}: error: code should be clang-formatted' <<< "$report" | cut -d: -f1 | sort -u)
if [ "$status" -ne 0 ] && [ ${#bad[@]} -eq 0 ]; then
  printf 'check_format: clang-format failed:\n%s\n' "$report" >&2
  exit 1
fi
if [ ${#bad[@]} -gt 0 ]; then
  printf 'check_format: not formatted: %s\n' "${bad[@]}"
  echo "check_format: run bash scripts/check_format.sh --fix"
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
