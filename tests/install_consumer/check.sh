#!/usr/bin/env bash
# The installed package on its own: installs the build into a temporary prefix, MOVES the prefix elsewhere, checks that
# nothing installed points into the source or build tree (package config, run paths), then builds and runs the
# consumer project and the C++ example (examples/cpp) against the moved prefix.
# Usage: check.sh BUILD_DIR CONSUMER_DIR EXAMPLE_DIR SOURCE_DIR [SANITIZER_FLAGS]
set -euo pipefail
build_dir=$(cd "$1" && pwd) consumer_dir=$2 example_dir=$3 source_dir=$(cd "$4" && pwd) sanitizer_flags=${5:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" > /dev/null
mv "$work/prefix" "$work/moved"
prefix=$work/moved
fail() { echo "install check: $*" >&2; exit 1; }

if grep -rlF -e "$source_dir" -e "$build_dir" "$prefix/lib/cmake" > /dev/null; then
  fail "the package config names the source or build tree: $(grep -rlF -e "$source_dir" -e "$build_dir" "$prefix/lib/cmake")"
fi
for file in "$prefix"/lib/libclothcd*.so.* "$prefix"/bin/*; do
  [[ -f "$file" && ! -L "$file" ]] || continue
  runpath=$(readelf -d "$file" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p')
  for entry in ${runpath//:/ }; do
    [[ "$entry" == '$ORIGIN'* ]] || fail "$file has the run path entry $entry outside the prefix"
  done
done
if readelf -d "$prefix"/lib/libclothcd_core.so | grep -q opennn; then fail "libclothcd_core needs OpenNN"; fi
if [[ -e "$prefix/lib/libclothcd_learning.so" && ! -e "$prefix/lib/libopennn.so" ]]; then
  fail "clothcd::learning is installed without OpenNN's library"
fi

for project in "$consumer_dir" "$example_dir"; do
  name=$(basename "$project")
  cmake -S "$project" -B "$work/build-$name" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_CXX_FLAGS="$sanitizer_flags" -DCMAKE_EXE_LINKER_FLAGS="$sanitizer_flags" > /dev/null
  cmake --build "$work/build-$name" > /dev/null
done
output=$(env -u LD_LIBRARY_PATH "$work/build-install_consumer/consumer")
echo "$output"
[[ "$(sed -n 2p <<<"$output")" == 4802 ]] || fail "consumer printed the wrong face count"
env -u LD_LIBRARY_PATH "$work/build-cpp/drop_on_sphere"
if [[ -x "$prefix/bin/clothcd" ]]; then
  env -u LD_LIBRARY_PATH "$prefix/bin/clothcd" --version
fi
echo "find_package(clothcd) from a moved install prefix: ok (consumer and examples/cpp built and run)"
