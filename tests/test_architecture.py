"""The import contracts of pyproject.toml, checked by import-linter: the kernel stays pure
(nothing under mbds/kernel imports xarray, sympy, mpi4py, typer, scipy or the model layers),
nothing below the front-ends imports the model-file records, and the layers cli > campaign > workflow > (plot | wear | data) > analysis > model > expr > io
> kernel import only downwards (docs/architecture.md)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_import_contracts_are_kept():
    exe = Path(sys.executable).with_name("lint-imports")
    result = subprocess.run([str(exe)], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "3 kept, 0 broken" in result.stdout
