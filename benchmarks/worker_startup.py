"""A campaign worker's start-up, split as a worker rank makes it (docs/performance.md, "Workers
without sympy").

For each of ``--repeat`` fresh copies of the campaign folder of JOB (default: the README's
``campaigns/wearballs/wearballs_campaign.job``), a new process imports what a worker rank imports
before it serves (mpi4py and ``mbds.campaign.executors``), then what the plan's task kinds need
(``import_for``), loads the first variant's compiled model as a worker does (``load_first``,
which then freezes what the process holds out of the garbage collector's sweeps) and runs the
first chain's prepare task and first run; it prints the seconds of each part, the heavy packages it
imported, and the process's wall time. The plan is expanded in another process first (rank 0's
work). Use a cache warmed by one run of the campaign (``MBDS_CACHE_DIR``) to see the steady state.

Run from the repository root: ``.venv/bin/python benchmarks/worker_startup.py [JOB] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bytecode import write_bytecode

ROOT = Path(__file__).resolve().parents[1]
PYTHON = sys.executable
EXPAND = ("import pickle, sys; from mbds.campaign.plan import expand; "
          "open(sys.argv[2], 'wb').write(pickle.dumps(expand(sys.argv[1])))")
WORKER = """
import sys, time
begun = time.perf_counter()
import mpi4py, mbds.campaign.executors
from mbds.campaign.executors import _load_first as load_first
from mbds.campaign.tasks import import_for, run_task
path = time.perf_counter()
import pickle
plan = pickle.loads(open(sys.argv[1], "rb").read())
unpickled = time.perf_counter()
import_for({task.kind for task in plan.tasks})
imported = time.perf_counter()
load_first(plan.job.world_path(), plan.variants[0] if plan.variants else None)
loaded = time.perf_counter()
chain = plan.tasks[0].chain
first = [task for task in plan.tasks if task.chain == chain][:2]
walls = ", ".join(f"{task.kind} {run_task(task)['wall']:.2f}" for task in first)
heavy = " ".join(m for m in ("sympy", "xarray", "pandas", "numba", "scipy", "typer") if m in sys.modules)
print(f"worker path {path - begun:.2f}  import_for {imported - unpickled:.2f}  model load {loaded - imported:.2f}  "
      f"start-up {path - begun + loaded - unpickled:.2f}  first tasks: {walls}  imported: {heavy}")
"""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("job", nargs="?", default=str(ROOT / "campaigns" / "wearballs" / "wearballs_campaign.job"))
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    write_bytecode()
    source = Path(args.job).resolve()
    for round_ in range(args.repeat):
        with tempfile.TemporaryDirectory(prefix="mbds-worker-startup-") as temp:
            folder = Path(temp) / source.parent.name
            shutil.copytree(source.parent, folder, ignore=shutil.ignore_patterns("campaign", ".cache"))
            plan = Path(temp) / "plan.pickle"
            subprocess.run([PYTHON, "-c", EXPAND, str(folder / source.name), str(plan)], check=True)
            begun = time.perf_counter()
            subprocess.run([PYTHON, "-c", "pass"], check=True)
            interpreter = time.perf_counter() - begun
            begun = time.perf_counter()
            done = subprocess.run([PYTHON, "-c", WORKER, str(plan)], capture_output=True, text=True, check=True)
            wall = time.perf_counter() - begun
            print(f"{round_ + 1}: interpreter {interpreter:.2f}  {done.stdout.strip()}  process wall {wall:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
