#!/usr/bin/env bash
# The Python package's test: installs it with pip into a virtual environment (pip install ., as a user would) and runs
# its pytest suite, which compares it with the clothcd program.
# Usage: python/run-tests.sh CLOTHCD_PROGRAM [VENV_DIR]   (default VENV_DIR: build/python-venv)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cli=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
venv=${2:-$root/build/python-venv}
[[ -x "$venv/bin/python" ]] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "$root[test]"
cd "$root"
CLOTHCD_CLI=$cli "$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests
