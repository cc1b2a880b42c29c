"""Figures start light (issue 14, "Speed"): drawing reads outputs and needs neither the model
loader (sympy) nor the kernel (numba) nor scipy; ``mbds-campaign plot`` imports only what it draws
with."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("sympy", "numba", "scipy")
PLOT_PATH = ("mbds.plot", "mbds.cli.campaign", "mbds.cli.plot", "mbds.campaign.collect", "mbds.campaign.plan")


def test_the_plot_path_imports_no_heavy_package():
    code = (f"import sys\nimport {', '.join(PLOT_PATH)}\n"
            f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert result.stdout.split() == [], f"drawing imports {result.stdout.strip()}"
