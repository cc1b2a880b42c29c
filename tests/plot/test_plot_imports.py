"""Figures start light (issue 14, "Speed"): drawing reads outputs and needs neither the model
loader (sympy) nor the kernel (numba) nor scipy, so ``mbds-campaign plot`` imports none of them."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def modules_loaded_by(statement: str) -> set[str]:
    """The modules a fresh interpreter holds after ``statement``."""
    code = f"{statement}\nimport json, sys\nprint(json.dumps(sorted(sys.modules)))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    return set(json.loads(done.stdout))


def test_the_campaign_plot_command_imports_neither_sympy_numba_nor_scipy():
    loaded = modules_loaded_by("import mbds.plot, mbds.plot.batch, mbds.cli.campaign, mbds.cli.plot, "
                               "mbds.campaign.collect, mbds.campaign.plan")
    assert "matplotlib.figure" in loaded and "xarray" in loaded
    assert not loaded & {"sympy", "numba", "scipy"}
