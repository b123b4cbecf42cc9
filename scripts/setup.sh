#!/usr/bin/env bash
# Installs the Debian 12 packages steadylight needs to build, test and benchmark.
# Idempotent and non-interactive: it installs only what is missing, so a second run is quick.
# Extra packages a script needs only for itself can be named as arguments (fuzz.sh: clang).
#   bash scripts/setup.sh [PACKAGE...]
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libnanoflann-dev libtinygltf-dev libtinyobjloader-dev
  libopenexr-dev zlib1g-dev libisal-dev libstb-dev libjpeg-dev nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev
  libgtest-dev libbenchmark-dev
  ffmpeg   # optional at run time: only `render --video` and its test (skipped without it) use it
  slurm-wlm munge   # the farm test's one-node Slurm cluster (tests/farm/); `submit` needs sbatch only
  blender-data   # Blender's world images (DWAB-compressed EXRs), which the world image tests read
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
