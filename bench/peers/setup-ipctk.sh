#!/usr/bin/env bash
# Creates the scale benchmark's Python environment with its peer, the IPC Toolkit's wheel from PyPI:
# setup-ipctk.sh VENV_DIR. Needs python3-venv and network access; `clothcd bench scale` runs it when VENV_DIR has no
# working ipctk, and reports "peer not installed" when it fails.
set -euo pipefail
venv=${1:?usage: setup-ipctk.sh VENV_DIR}
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --disable-pip-version-check ipctk==1.6.1 numpy
"$venv/bin/python" -c "import ipctk"
