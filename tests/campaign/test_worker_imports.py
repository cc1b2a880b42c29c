"""A campaign worker starts light (issue 12): importing what a worker runs (the executors, the
scheduling loop and the task runner) loads neither sympy, xarray, typer nor scipy; a task
imports the simulation layers when it runs."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("sympy", "xarray", "typer", "scipy")
WORKER_PATH = ("mbds.campaign.executors", "mbds.campaign.run", "mbds.campaign.tasks")


def test_worker_path_imports_no_heavy_package():
    code = (f"import sys\nimport {', '.join(WORKER_PATH)}\n"
            f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert result.stdout.split() == [], f"a worker imports {result.stdout.strip()} before any task runs"

