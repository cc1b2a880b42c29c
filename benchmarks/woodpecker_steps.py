"""The woodpecker's limit cycle against the step size, in mbds and in Siconos, in one run.

Run from the repository root: ``.venv/bin/python benchmarks/woodpecker_steps.py [--steps
5e-6,1e-5,2e-5,5e-5,1e-4]``. For each step h, mbds runs campaigns/woodpecker with maximumTimestep = h
(history at every maximum step; its steps are h between impacts) and Siconos runs its Moreau-Jean
woodpecker (benchmarks/kernel.py) with the fixed step h, each for 2 s; both are measured over the
second second as in benchmarks/kernel.py. Printed per tool and step: period and its error
against Leine, Glocker and van Campen (2003, 145.2 ms) and against Siconos' Woodpecker.ref
(146.1 ms), the change of the period from the tool's own finest step, the descent, the angles and
the wall time per simulated second (each the fastest of 3 runs, Siconos on one thread); then the speed ratios at equal steps and at the step where
each tool's period is within 0.05 % of its own finest-step period.
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np


ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from kernel import RUNS, SICONOS_WOODPECKER, WOODPECKER_TIME, siconos_best  # noqa: E402

from mbds.model.load import load_model  # noqa: E402
from mbds.simulation.buffers import RunSettings  # noqa: E402
from mbds.simulation.run import simulate  # noqa: E402
from tests.physics.limit_cycle import cycle_figures, velocity_jumps  # noqa: E402

LGV_PERIOD, SICONOS_REF_PERIOD = 0.1452, 0.1461  # s
CONVERGED = 5e-4  # relative change of the period from the finest step that counts as converged


def mbds_figures(step: float, folder: Path) -> dict:
    """campaigns/woodpecker with maximumTimestep = ``step``: the limit-cycle figures and the wall
    time of a warm 2 s run."""
    copy = folder / f"woodpecker_{step:g}"
    shutil.copytree(ROOT / "campaigns" / "woodpecker", copy)
    world = copy / "woodpecker.wld"
    world.write_text(world.read_text().replace("maximumTimestep = 1e-5", f"maximumTimestep = {step!r}"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(copy)
    simulate(model, RunSettings(break_time=0.001))  # compiles the stepper (or loads it)
    wall = np.inf
    for _ in range(RUNS):  # the fastest counts, as for Siconos
        begun = time.perf_counter()
        result = simulate(model, RunSettings(break_time=WOODPECKER_TIME))
        wall = min(wall, time.perf_counter() - begun)
    impacts = velocity_jumps(result.time, result.u, result.a, (1.0, 0.01, 0.015), 1e-3)
    cycle = cycle_figures(result.time, result.q, impacts, 1.0)
    return {"period": cycle.period, "descent": cycle.descent_speed, "ring": list(cycle.ring_limits),
            "bird": list(cycle.bird_limits), "wall": wall}


def siconos_figures(step: float) -> dict | None:
    """Siconos' Moreau-Jean woodpecker with the fixed step ``step`` (the fastest of RUNS runs, on
    one thread); None without Siconos."""
    return siconos_best(SICONOS_WOODPECKER, repr(step), WOODPECKER_TIME)


def converged_step(rows: dict[float, dict]) -> float:
    """The largest step whose period is within CONVERGED of the period at the finest step."""
    finest = rows[min(rows)]["period"]
    return max(h for h, row in rows.items() if abs(row["period"] / finest - 1.0) <= CONVERGED)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", default="5e-6,1e-5,2e-5,5e-5,1e-4", help="step sizes (s), comma-separated")
    steps = sorted(float(h) for h in parser.parse_args().steps.split(","))
    results: dict[str, dict[float, dict]] = {"mbds": {}, "Siconos": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for h in steps:
            results["mbds"][h] = mbds_figures(h, Path(tmp))
            theirs = siconos_figures(h)
            if theirs is not None:
                results["Siconos"][h] = theirs
    print("| tool | step s | period ms | vs LGV 145.2 ms | vs Woodpecker.ref 146.1 ms | vs own finest step | "
          "descent mm/s | sleeve rad | bird rad | wall s per simulated s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for tool, rows in results.items():
        if not rows:
            print(f"| {tool} | MISSING: install it with `apt-get install -y python3-siconos` |")
            continue
        finest = rows[min(rows)]["period"]
        for h, row in rows.items():
            print(f"| {tool} | {h:g} | {1e3 * row['period']:.2f} | {row['period'] / LGV_PERIOD - 1:+.2%} | "
                  f"{row['period'] / SICONOS_REF_PERIOD - 1:+.2%} | {row['period'] / finest - 1:+.3%} | "
                  f"{1e3 * row['descent']:.1f} | {row['ring'][0]:.4f} .. {row['ring'][1]:.4f} | "
                  f"{row['bird'][0]:.4f} .. {row['bird'][1]:.4f} | {row['wall'] / WOODPECKER_TIME:.3f} |")
    ours, theirs = results["mbds"], results["Siconos"]
    if theirs:
        for h in steps:
            print(f"\nequal step {h:g} s: mbds {ours[h]['wall'] / theirs[h]['wall']:.3f} x Siconos' wall time "
                  f"({theirs[h]['wall'] / ours[h]['wall']:.1f} x faster)", end="")
        a, b = converged_step(ours), converged_step(theirs)
        print(f"\n\nconverged to {CONVERGED:.2%} of the own finest-step period: mbds at {a:g} s, Siconos at {b:g} s; "
              f"Siconos' wall / mbds' wall = {theirs[b]['wall'] / ours[a]['wall']:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
