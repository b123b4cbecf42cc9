# Sourced by the tests that need a tool beside steadylight (Chromium, ffmpeg, Slurm, a tmpfs
# mount): `skip_without_tool REASON` skips the test (exit 77, CTest's SKIPPED) outside CI, and
# fails it under CI=true, where every test must run (docs/testing.md).
skip_without_tool() {
  if [ "${CI:-}" = true ]; then
    echo "FAIL: $1; under CI=true a test that needs a tool runs or fails (bash scripts/setup.sh installs them)"
    exit 1
  fi
  echo "SKIP: $1"
  exit 77
}
