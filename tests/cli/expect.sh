#!/usr/bin/env bash
# Runs a steadylight command and checks its exit status and output.
#   expect.sh ok|fail REGEX -- COMMAND...
# `ok` wants exit status 0, `fail` a non-zero status without a crash (no signal, no abort);
# the combined stdout and stderr must match REGEX (extended grep).
set -u
want=$1 regex=$2
shift 3
output=$("$@" 2>&1)
status=$?
echo "$output"
echo "exit status: $status"
if [ "$want" = ok ] && [ $status -ne 0 ]; then echo "FAIL: expected success"; exit 1; fi
if [ "$want" = fail ] && { [ $status -eq 0 ] || [ $status -gt 128 ]; }; then
  echo "FAIL: expected a clean failure (exit 1), got $status"; exit 1
fi
if ! grep -Eq -- "$regex" <<<"$output"; then echo "FAIL: output does not match /$regex/"; exit 1; fi
exit 0
