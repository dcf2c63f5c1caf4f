#!/usr/bin/env bash
# Installs clothcd's Debian dependencies (skips apt when every package is already installed). With --fuzz, also clang and
# its libFuzzer and sanitizer runtime, which scripts/fuzz.sh needs (nothing else does).
set -euo pipefail

packages=(
  build-essential cmake ninja-build python3-pip  # toolchain; pip downloads OpenNN's source distribution
  libeigen3-dev        # linear algebra in every public type
  libassimp-dev        # reading 3DS, BLEND, DAE, glTF, ... (OBJ, PLY, OFF, STL have readers of their own)
  catch2               # the test framework
  libcli11-dev         # the clothcd program's subcommands and options
  nlohmann-json3-dev   # JSON: model cards, the --json reports of the clothcd program
  libgmp-dev           # exact rational arithmetic: the CCD reference and its uncertain-case fallback
  libtbb-dev           # parallel broad phase and batched culling on both cores
  zlib1g-dev           # reading libcgal-demo's data archive (a .tar.gz) for the obstacle models
  libstb-dev           # PNG pictures and charts
  libcgal-demo         # obstacle models: rabbit, dinosaur, human, cow, sphere, cube
  assimp-testmodels    # obstacle models: HUMAN.blend, duck.dae (the bird)
  glmark2-data         # obstacle model: cat
  libmeshoptimizer-dev # benchmark peer: QEM simplification (linked into bench/ only)
  libcgal-dev          # benchmark peer: Garland-Heckbert simplification, optimal OBB (bench/ only)
  libfcl-dev           # benchmark peer: AABB/OBB BVH broad phase (bench/ only)
  libqhull-dev         # convex hulls for the tight reference OBB and the simplified-model OBB (library)
  libpugixml-dev       # reading a trained network's XML at run time (the library; OpenNN is needed only to train)
  python3-dev          # the Python package (pip install .)
  python3-venv         # the Python package's tests; the scale bench section's Python environment for the IPC Toolkit
)
if [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]} == 0)); then
  echo "Debian packages: all ${#packages[@]} installed"
  exit 0
fi
echo "Installing Debian packages: ${missing[*]}"
sudo_cmd=()
[[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
