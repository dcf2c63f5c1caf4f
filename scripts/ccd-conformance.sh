#!/usr/bin/env bash
# CCD conformance: runs `clothcd ccd` on DIR's vertex-face and edge-edge queries (public benchmark CSV format, ground
# truth in column 7) with every filter mode (and the combined one with --approximate), prints the summaries, and exits
# non-zero on any false negative.
# Usage: scripts/ccd-conformance.sh DIR   (the clothcd program: $CLOTHCD, else $CLOTHCD_BUILD_DIR/bin, else build/bin)
set -euo pipefail

if [[ $# -ne 1 || ! -d "$1" ]]; then
  echo "usage: $0 DIR (a folder of vertex-face/ and edge-edge/ query folders)" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
clothcd=${CLOTHCD:-${CLOTHCD_BUILD_DIR:-$root/build}/bin/clothcd}
if [[ ! -x "$clothcd" ]]; then
  echo "ccd-conformance: no clothcd program at $clothcd (build first or set CLOTHCD)" >&2
  exit 2
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for kind in vertex-face edge-edge; do
  # Gather every <scene>/<kind> folder under one <kind> folder (links), so each kind is summarised on its own.
  mkdir -p "$work/$kind"
  count=0
  while IFS= read -r -d '' folder; do
    count=$((count + 1))
    ln -s "$folder" "$work/$kind/$count"
  done < <(find "$(cd "$1" && pwd)" -type d -name "$kind" -print0 | sort -z)
  if [[ $count -eq 0 ]]; then
    echo "ccd-conformance: no $kind folders under $1" >&2
    status=1
    continue
  fi
  # Every filter with every query decided exactly (the default), and the combined one in the approximate mode
  # (--approximate: undecided queries reported as conservative hits).
  for run in none nonpenetration projection combined "combined --approximate"; do
    read -r filter exact <<<"$run"
    summary=$("$clothcd" ccd "$work/$kind" --filter "$filter" ${exact:+"$exact"} --json)
    echo "$kind $run: $summary"
    misses=$(sed -n 's/.*"false_negatives": \([0-9]*\).*/\1/p' <<<"$summary")
    if [[ "$misses" != "0" ]]; then
      echo "ccd-conformance: FAILED: $kind with filter $run has ${misses:-unknown} false negatives" >&2
      status=1
    fi
  done
done
[[ $status -eq 0 ]] && echo "ccd-conformance: OK (no false negatives)"
exit $status
