#!/usr/bin/env bash
# Installs the built clothcd into a temporary prefix, builds the consumer project against it and runs it.
set -euo pipefail
build_dir=$1 source_dir=$2 sanitizer_flags=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" > /dev/null
cmake -S "$source_dir" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_FLAGS="$sanitizer_flags" -DCMAKE_EXE_LINKER_FLAGS="$sanitizer_flags" > /dev/null
cmake --build "$work/build" > /dev/null
test "$("$work/build/consumer")" = 4802
echo "find_package(clothcd) from an install prefix: ok"
