#!/usr/bin/env bash
# Mutation check of the safety-critical code: applies each mutation of scripts/mutants.txt in turn to a scratch copy
# of the source tree (build-mutants/tree, never the working tree), rebuilds incrementally, runs the tests and prints
# whether each mutation was killed (a test failed) or survived. Exits non-zero when a mutation survives, when a
# snippet is not found, or when a mutant does not compile (a broken list entry).
#
# Usage: scripts/mutants.sh [--dry-run] [name-pattern]   (only the mutations whose name matches the extended regex)
# Needs the set-up of scripts/setup.sh (dependencies and OpenNN). Takes minutes per mutation on two cores.
# --dry-run only checks the list against the working tree, in seconds, copying and building nothing: every entry has a
# unique name, known keys and the fields it needs, its file exists and its snippet occurs as listed (exactly once, or
# at least `occurrence` times), so that the list cannot fall behind the code unnoticed (CTest runs it).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
list="$root/scripts/mutants.txt"
dry_run=0
if [[ "${1:-}" == "--dry-run" ]]; then
  dry_run=1
  shift
fi
only="${1:-}"
work="$root/build-mutants"
src="$work/tree"
build="$src/build"  # inside the copy, as build/ is in the tree: the same relative paths, so ccache can reuse objects
jobs="${CLOTHCD_JOBS:-2}"
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"

build_tests() { cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1; }  # every target: the suite installs them
# Runs the tests matching $1 (all when empty), stopping at the first failure; prints the first failed test's name.
run_tests() {
  # The list's dry run (mutation_list) checks the snippets against the unmutated tree, so a mutant always fails it.
  local args=(--test-dir "$build" --stop-on-failure --timeout 600 -j "$jobs" -E '^mutation_list$')
  [[ -n "$1" ]] && args+=(-R "$1")
  if ctest "${args[@]}" >"$work/ctest.log" 2>&1; then return 0; fi
  grep -m1 -E '\*\*\*Failed|\(Failed\)|Exception|Timeout' "$work/ctest.log" | sed -E 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: //; s/ \.+.*//'
  return 1
}

# Copies the working tree, configures the copy and checks that it builds and passes unmutated.
prepare_copy() {
  # The scratch copy: the working tree's files (committed or not, minus ignored ones), times kept so that ninja
  # rebuilds only what changed since the last run. third_party (OpenNN) and .cache are linked, not copied.
  mkdir -p "$src"
  (cd "$root" && git ls-files --cached --others --exclude-standard) | grep -vE '^(third_party|\.cache)(/|$)' |
    sort -u >"$work/files"
  (cd "$root" && tr '\n' '\0' <"$work/files" | xargs -0 cp -p --parents -t "$src")
  # Files removed from the tree since the last run go from the copy too (CMake globs the test sources).
  (cd "$src" && find . \( -path ./build -o -path ./third_party -o -path ./.cache \) -prune -o -type f -print |
    sed 's|^\./||' | sort | comm -23 - "$work/files" | tr '\n' '\0' | xargs -0 -r rm -f)
  for linked in third_party .cache; do
    if [[ -e "$root/$linked" && ! -e "$src/$linked" ]]; then ln -s "$(readlink -f "$root/$linked")" "$src/$linked"; fi
  done

  launcher=()
  if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
  if [[ ! -f "$build/build.ninja" ]]; then
    cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >"$work/configure.log"
  fi

  echo "baseline: building and running the whole suite unmutated"
  build_tests || { echo "the unmutated copy does not build (see $work/build.log)" >&2; exit 1; }
  if ! failed="$(run_tests "")"; then
    echo "the unmutated suite fails ($failed; see $work/ctest.log): fix that first" >&2
    exit 1
  fi
}

# mutate FILE FIND REPLACE OCCURRENCE [check]: replaces the occurrence (1-based; 0: the only one) of FIND in FILE;
# with "check", only checks that it is there.
mutate() {
  python3 - "$@" <<'EOF'
import os, sys
path, find, replace, occurrence = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
check_only = len(sys.argv) > 5 and sys.argv[5] == "check"
if not os.path.isfile(path):
    sys.exit(f"{path}: no such file")
text = open(path).read()
count = text.count(find)
if count == 0 or (occurrence == 0 and count > 1) or occurrence > count:
    sys.exit(f"{path}: snippet found {count} times (occurrence {occurrence or 'unique'} asked): {find}")
if check_only:
    sys.exit(0)
at = -1
for _ in range(max(occurrence, 1)):
    at = text.index(find, at + 1)
open(path, "w").write(text[:at] + replace + text[at + len(find):])
EOF
}

results=()
failures=0
declare -A seen=()
# Parse the list: one mutation per block of "key: value" lines.
run_block() {
  [[ -z "${fields[name]:-}" ]] && return 0
  local name="${fields[name]}" file="${fields[file]:-}"
  if [[ -n "${seen[$name]:-}" ]]; then echo "mutants.txt: the name $name is used twice" >&2; exit 1; fi
  seen[$name]=1
  for key in "${!fields[@]}"; do
    case "$key" in
      name | file | find | occurrence | replace | tests | why | equivalent) ;;
      *) echo "mutants.txt: $name has an unknown key '$key'" >&2; exit 1 ;;
    esac
  done
  if [[ -n "$only" && ! "$name" =~ $only ]]; then return 0; fi
  for key in file find replace; do
    if [[ -z "${fields[$key]:-}" ]]; then echo "mutants.txt: $name has no $key" >&2; exit 1; fi
  done
  if ((dry_run)); then
    if mutate "$root/$file" "${fields[find]}" "${fields[replace]}" "${fields[occurrence]:-0}" check; then
      results+=("$(printf '%-28s %-36s found' "$name" "$file")")
    else
      results+=("$(printf '%-28s %-36s SNIPPET NOT FOUND' "$name" "$file")")
      failures=$((failures + 1))
    fi
    return 0
  fi
  if [[ -n "${fields[equivalent]:-}" ]]; then
    results+=("$(printf '%-28s %-36s equivalent (not run)' "$name" "$file")")
    return 0
  fi
  local target="$src/$file" saved="$work/original"
  cp -p "$target" "$saved"
  if ! mutate "$target" "${fields[find]}" "${fields[replace]}" "${fields[occurrence]:-0}"; then
    results+=("$(printf '%-28s %-36s SNIPPET NOT FOUND' "$name" "$file")")
    failures=$((failures + 1))
    return 0
  fi
  echo "mutant $name: building"
  local outcome
  if ! build_tests; then
    outcome="BROKEN (does not compile; see the list entry)"
    cp "$work/build.log" "$work/broken-$name.log"
    failures=$((failures + 1))
  else
    local failed=""
    echo "mutant $name: testing"
    if failed="$(run_tests "${fields[tests]:-}")" && failed="$(run_tests "")"; then
      outcome="SURVIVED"
      failures=$((failures + 1))
    else
      outcome="killed by: $failed"
    fi
  fi
  # Restore the original, its time bumped so that ninja rebuilds it.
  cp "$saved" "$target"
  touch "$target"
  results+=("$(printf '%-28s %-36s %s' "$name" "$file" "$outcome")")
}

((dry_run)) || prepare_copy
declare -A fields=()
while IFS= read -r line || [[ -n "$line" ]]; do
  if [[ "$line" =~ ^# ]]; then continue; fi
  if [[ -z "$line" ]]; then
    run_block
    fields=()
    continue
  fi
  key="${line%%:*}"
  fields[$key]="${line#*: }"
done <"$list"
run_block

# Leave the copy unmutated and built for the next run.
((dry_run)) || build_tests || true

echo
printf '%-28s %-36s %s\n' mutation file result
for r in "${results[@]}"; do echo "$r"; done
if ((failures > 0)); then
  echo "$failures mutation(s) survived, were not found or did not compile" >&2
  exit 1
fi
if ((dry_run)); then echo "every snippet was found as listed"; else echo "every mutation was killed"; fi
