#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs the whole test suite with CTest.
# With --sanitize, builds in build-asan/ with AddressSanitizer + UndefinedBehaviorSanitizer and runs the suite there.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
if [[ "${1:-}" == "--sanitize" ]]; then
  export CLOTHCD_BUILD_DIR=$root/build-asan
  "$root/scripts/setup.sh" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCLOTHCD_SANITIZE=ON -DCLOTHCD_BUILD_BENCH=OFF
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
else
  export CLOTHCD_BUILD_DIR=$root/build
  "$root/scripts/setup.sh"
fi
ctest --test-dir "$CLOTHCD_BUILD_DIR" --output-on-failure --parallel "$(nproc)"
