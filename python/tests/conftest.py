"""Shared fixtures: the clothcd program (CLOTHCD_CLI, else build/bin/clothcd) and the repository root."""

import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> str:
    """The clothcd program to compare against; the comparison tests need it."""
    path = os.environ.get("CLOTHCD_CLI") or str(ROOT / "build" / "bin" / "clothcd")
    if not os.access(path, os.X_OK):
        path = shutil.which("clothcd") or path
    assert os.access(path, os.X_OK), f"no clothcd program at {path}: build it or set CLOTHCD_CLI"
    return path


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT
