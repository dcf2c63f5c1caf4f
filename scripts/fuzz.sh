#!/usr/bin/env bash
# Fuzzes clothcd's file readers: builds the libFuzzer targets of fuzz/ with Debian's clang under AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz/ (installing clang and its fuzzer runtime first), then runs each target for
# SECONDS (default 60) on its committed seeds (fuzz/corpus/<target>) and the corpus it grew before
# (build-fuzz/corpus/<target>). Inputs are capped at 4 KB (the model files, two in one input, at 16 KB), a single
# allocation at 64 MB and an input's run at 10 s. Findings are written to build-fuzz/findings/<target>/; the script
# fails when a target finds anything. Usage: scripts/fuzz.sh [SECONDS]
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
build=$root/build-fuzz
cd "$root"

scripts/install-deps.sh --fuzz
cmake -S fuzz -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build "$build" --parallel "$(nproc)"

export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
targets=(ply_reader obj_reader off_reader stl_reader mesh_frames query_file model_loader tar_gz_member)
summary=()
failed=0
for target in "${targets[@]}"; do
  max_len=4096
  [[ $target == model_loader ]] && max_len=16384
  corpus=$build/corpus/$target findings=$build/findings/$target
  mkdir -p "$corpus" "$findings"
  log=$build/$target.log
  echo "fuzzing $target for $seconds s"
  status=0
  "$build/fuzz_$target" "$corpus" "fuzz/corpus/$target" -max_total_time="$seconds" -timeout=10 -malloc_limit_mb=64 \
    -rss_limit_mb=2048 -max_len="$max_len" -artifact_prefix="$findings/" -print_final_stats=1 > "$log" 2>&1 ||
    status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  if ((status != 0)); then
    failed=1
    summary+=("$target: FINDING after ${runs:-?} runs (exit $status; see $log and $findings/)")
    grep -m 5 -E "ERROR|SUMMARY|runtime error|deadly signal" "$log" || true
  else
    summary+=("$target: ${runs:-?} runs, no finding")
  fi
done
printf '%s\n' "${summary[@]}"
exit "$failed"
