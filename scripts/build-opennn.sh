#!/usr/bin/env bash
# Downloads OpenNN 0.56.2 from PyPI, verifies it, applies clothcd's patches and installs it as a shared library under
# third_party/opennn/install. A second run with the same source and patch reuses the installed library.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
version=0.56.2
sha256=b7cf31e79f814823fdd5f49957074ed29debd103647a2331d1f664827acec470
work="$root/third_party/opennn"
prefix="$work/install"
patch_file="$root/scripts/opennn/clothcd-opennn.patch"
# The contents only, not the paths: checkouts in other folders sharing third_party/ must agree on the stamp.
stamp_value="$version $sha256 $(cat "$patch_file" "$root/scripts/opennn/CMakeLists.txt" | sha256sum | cut -c1-64)"

if [[ -f "$prefix/.stamp" && "$(cat "$prefix/.stamp")" == "$stamp_value" ]]; then
  echo "OpenNN $version already built in $prefix"
  exit 0
fi

mkdir -p "$work"
archive="$work/OpenNN-$version.tar.gz"
if [[ ! -f "$archive" ]] || ! echo "$sha256  $archive" | sha256sum --check --status; then
  echo "Downloading OpenNN $version source distribution from PyPI"
  rm -f "$archive"
  python3 -m pip download --quiet --no-deps --no-binary :all: "opennn==$version" -d "$work"
fi
echo "$sha256  $archive" | sha256sum --check --status || { echo "error: $archive fails its sha256 check" >&2; exit 1; }

source_dir="$work/src"
rm -rf "$source_dir" "$work/build" "$prefix"
mkdir -p "$source_dir"
tar xzf "$archive" -C "$source_dir" --strip-components=1
patch --quiet -p1 -d "$source_dir" < "$patch_file"

echo "Building OpenNN $version (about two minutes on two cores)"
cmake -S "$root/scripts/opennn" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DOPENNN_SOURCE_DIR="$source_dir" -DCMAKE_INSTALL_PREFIX="$prefix" > "$work/configure.log"
cmake --build "$work/build" --parallel "$(nproc)" > "$work/build.log" || { tail -30 "$work/build.log" >&2; exit 1; }
cmake --install "$work/build" > /dev/null
echo "$stamp_value" > "$prefix/.stamp"
echo "OpenNN $version installed in $prefix"
