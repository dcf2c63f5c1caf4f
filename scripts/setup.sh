#!/usr/bin/env bash
# Sets up everything clothcd needs on a fresh Debian machine and builds it: Debian packages, OpenNN from PyPI's source
# distribution, the CMake build (in build/, or $CLOTHCD_BUILD_DIR), and the obstacle models in .cache/models (or
# $CLOTHCD_CACHE when set; the scripts point $CLOTHCD_CACHE there, the program's own default is the user's cache folder).
# Rerunnable: every step skips what is already done.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${CLOTHCD_BUILD_DIR:-$root/build}
cd "$root"

scripts/install-deps.sh
scripts/build-opennn.sh
cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" > /dev/null
cmake --build "$build_dir" --parallel "$(nproc)"
"$build_dir/bin/clothcd" meshes --cache "${CLOTHCD_CACHE:-$root/.cache/models}" > /dev/null
echo "clothcd built in $build_dir (program: $build_dir/bin/clothcd)"
