"""The Python examples' command lines: --help prints the usage and exits without running the example."""

import pathlib
import subprocess
import sys

import pytest

EXAMPLES = sorted((pathlib.Path(__file__).resolve().parents[2] / "examples" / "python").glob("*.py"))


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda path: path.name)
def test_help_prints_the_usage_and_writes_nothing(example, tmp_path):
    run = subprocess.run([sys.executable, str(example), "--help"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=60)
    assert run.returncode == 0, run.stderr
    assert "usage" in run.stdout
    assert list(tmp_path.iterdir()) == []
