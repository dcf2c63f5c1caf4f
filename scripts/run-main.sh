#!/usr/bin/env bash
# The main job, end to end on a fresh machine: set everything up (scripts/setup.sh), fetch the obstacle models,
# simplify the rabbit and bound it, train and evaluate a small pair-culling network, and drop a cloth on a box.
# Everything it makes goes to out/main/: open out/main/box/contact_sheet.png first.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
clothcd="$root/build/bin/clothcd"
models="$root/.cache/models"
out="$root/out/main"
rm -rf "$out"
mkdir -p "$out"

step() { printf '\n== %s\n' "$*"; }

step "obstacle models (Debian packages -> $models)"
"$clothcd" meshes --dir "$models" | tee "$out/models.csv"
"$clothcd" info "$models/rabbit.off" | tee "$out/rabbit-info.txt"

step "QEM: the rabbit to 10% of its faces, and its oriented boxes"
"$clothcd" simplify "$models/rabbit.off" "$out/rabbit-10.obj" --ratio 0.1 --hausdorff | tee "$out/simplify.txt"
for method in covariance adaptive adaptive-simplified; do
  "$clothcd" obb "$models/rabbit.off" --method "$method" | tee "$out/obb-$method.txt"
done

step "pair-culling network: labelled pairs, training with neuron selection, evaluation"
"$clothcd" train "$out/pairs.csv" --random-pairs 3000 --seed 1 --max-neurons 4 --trials 1 --max-epochs 300 \
  --out "$out/model" | tee "$out/train.txt"
"$clothcd" evaluate "$out/model" "$out/pairs.csv" --roc "$out/model/roc" | tee "$out/evaluate.txt"
"$clothcd" evaluate "$root/models/default" "$out/pairs.csv" --roc "$out/default-model-roc" | tee "$out/evaluate-default.txt"

step "cloth A falls on a box (frames, stats.csv, pictures)"
"$clothcd" simulate --scene box --cloth A --steps 300 --frames-every 30 --out "$out/box" | tee "$out/simulate.txt"

printf '\nmain job done: results in %s (pictures: box/contact_sheet.png, box/renders/)\n' "$out"
