#!/usr/bin/env bash
# The main job, end to end on a fresh machine: set everything up (scripts/setup.sh), fetch the obstacle models,
# simplify the rabbit and bound it, generate labelled pairs from simulations, train and evaluate a small pair-culling
# network on them, and drop a cloth on a box with that network culling the CCD candidates.
# Everything it makes goes to out/main/: open out/main/box/contact_sheet.png first.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
clothcd="${CLOTHCD_BUILD_DIR:-$root/build}/bin/clothcd"
models="${CLOTHCD_CACHE:-$root/.cache/models}"
export CLOTHCD_CACHE=$models  # every command finds the models set-up fetched
out="$root/out/main"
rm -rf "$out"
mkdir -p "$out"

step() { printf '\n== %s\n' "$*"; }

step "obstacle models (Debian packages -> $models)"
"$clothcd" meshes --cache "$models" | tee "$out/models.csv"
"$clothcd" info "$models/rabbit.off" | tee "$out/rabbit-info.txt"

step "QEM: the rabbit to 10% of its faces, and its oriented boxes"
"$clothcd" simplify "$models/rabbit.off" "$out/rabbit-10.obj" --ratio 0.1 --hausdorff | tee "$out/simplify.txt"
for method in covariance adaptive adaptive-simplified; do
  "$clothcd" obb "$models/rabbit.off" --method "$method" | tee "$out/obb-$method.txt"
done

step "pair-culling network: pairs from simulated steps, training with neuron selection, evaluation"
"$clothcd" gen-dataset --out "$out/pairs.csv" --scenes box,sphere --cloths A --steps 100 --seeds 1,2 \
  --max-rows 4000 --keep-collisions --seed 1 | tee "$out/gen-dataset.txt"
"$clothcd" train "$out/pairs.csv" --seed 1 --max-neurons 6 --trials 2 --max-epochs 300 \
  --out "$out/model" | tee "$out/train.txt"
"$clothcd" evaluate "$out/model" "$out/pairs.csv" --roc "$out/model/roc" | tee "$out/evaluate.txt"
"$clothcd" evaluate "$root/models/default" "$out/pairs.csv" --roc "$out/default-model-roc" | tee "$out/evaluate-default.txt"

step "cloth A falls on a box, the trained network culling the CCD candidates (frames, stats.csv, pictures)"
"$clothcd" simulate --scene box --cloth A --steps 300 --frames-every 30 --filter network --network "$out/model" \
  --out "$out/box" | tee "$out/simulate.txt"

printf '\nmain job done: results in %s (pictures: box/contact_sheet.png, box/renders/;' "$out"
printf ' network: model/neurons.svg, model/roc.svg)\n'
