#!/usr/bin/env bash
# Builds oneTBB with ThreadSanitizer for `scripts/test.sh --sanitize thread`, so that TSan sees
# TBB's synchronisation instead of reporting every parallel loop: the source of the version that
# Debian's libtbb-dev has (its headers compile our code), from Debian's archive, checked against
# the checksum Debian's source package lists. Installs into DIR/onetbb and prints that path.
#   bash scripts/build_instrumented_tbb.sh DIR
set -euo pipefail
dir=$(realpath -m "${1:?usage: build_instrumented_tbb.sh DIR}")
version=2021.8.0
sha256=7e9111b8bb59c8800bf6d0b06afe7b0891937443d2dae1ee1101c8e2ede6a7ef
installed=$(dpkg-query -W -f='${Version}' libtbb-dev)
[[ $installed == "$version"-* ]] || {
  echo "build_instrumented_tbb: libtbb-dev is $installed; this script builds $version (update it)" >&2
  exit 1
}
prefix=$dir/onetbb
if [ ! -f "$prefix/lib/libtbb.so.12" ]; then
  work=$dir/onetbb-source
  mkdir -p "$work"
  tarball=$work/onetbb_$version.orig.tar.xz
  if [ ! -f "$tarball" ]; then
    echo "build_instrumented_tbb: downloading oneTBB $version from Debian's archive" >&2
    curl -fsSL -o "$tarball.part" "http://deb.debian.org/debian/pool/main/o/onetbb/onetbb_$version.orig.tar.xz"
    mv "$tarball.part" "$tarball"
  fi
  echo "$sha256  $tarball" | sha256sum -c --quiet - >&2
  tar -xf "$tarball" -C "$work"
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  cmake -S "$work/oneTBB-$version" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
    -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_INSTALL_LIBDIR=lib >&2
  cmake --build "$work/build" --parallel "$(nproc)" >&2
  cmake --install "$work/build" >&2
fi
echo "$prefix"
