#!/usr/bin/env bash
# The main job, end to end on a fresh machine: set everything up (scripts/setup.sh), fetch the obstacle models and
# describe the rabbit. Later stages of the pipeline extend this script; results go to out/main/.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
clothcd="$root/build/bin/clothcd"
out="$root/out/main"
mkdir -p "$out"

"$clothcd" meshes --dir "$root/.cache/models" | tee "$out/models.csv"
"$clothcd" info "$root/.cache/models/rabbit.off" | tee "$out/rabbit-info.txt"
echo "main job done: results in $out"
