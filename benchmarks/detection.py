"""Time per call of contact detection at states of a run of a model.

Run from the repository root::

    .venv/bin/python benchmarks/detection.py campaigns/wearballs --time 1.5 --omega 40

The model runs to ``--time``; at ``--states`` evenly spaced times the world points, boxes and
margins the stepper detected with are kept. Detection (the boxes, then ``detect_contacts``) is
then timed over all kept states, ``--repeat`` times over, the fastest pass counting; the table
gives microseconds per call and the mean number of contacts found. ``--omega`` sets c'omega of a
copy of a wearballs folder.
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

from mbds.kernel.detection import bounding_boxes, detect_contacts  # noqa: E402
from mbds.kernel.jit import jit  # noqa: E402
from mbds.model.load import load_model  # noqa: E402
from mbds.simulation import run as run_module  # noqa: E402
from mbds.simulation.buffers import RunSettings, model_tuple  # noqa: E402


def kept_states(folder: Path, break_time: float, count: int):
    """(model arrays, maximumPenetration (m), world points, boxes, margins, contact workspace) at
    ``count`` times of a run."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(folder)
    made = []
    workspace = run_module.workspace

    def recording(*args):
        made.append(workspace(*args))
        return made[-1]

    times = list(np.linspace(break_time / count, break_time, count))
    states = []

    def progress(t):
        while times and t >= times[0]:
            times.pop(0)
            bodies = made[-1].bodies
            states.append((bodies.world.copy(), bodies.boxes.copy(), bodies.margin.copy()))

    run_module.workspace = recording
    try:
        run_module.simulate(model, RunSettings(break_time=break_time, passes_per_call=1), progress=progress)
    finally:
        run_module.workspace = workspace
    world, boxes, margin = (np.array(column) for column in zip(*states))
    return (model_tuple(run_module.flatten(model)), model.settings.maximum_penetration, world, boxes, margin,
            made[-1].contacts)


@jit
def _detect_all(model, max_pen, world, boxes, margin, contacts, repeat):
    """Detection at every kept state, ``repeat`` times over; returns the number of contacts found
    in one pass."""
    found = 0
    for k in range(repeat * world.shape[0]):
        k %= world.shape[0]
        bounding_boxes(world[k], model.point_start, boxes[k])
        found += detect_contacts(world[k], model.point_start, model.point_reflex, model.concave, boxes[k],
                                 model.pair_bodies, model.pair_resisting, model.skin, margin[k], max_pen,
                                 contacts.pair, contacts.vb, contacts.vertex, contacts.eb, contacts.edge, contacts.xi,
                                 contacts.gap, contacts.normal, contacts.point, contacts.work, contacts.frames)
    return found // repeat


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--time", type=float, default=1.0, help="simulated time of the run (s)")
    parser.add_argument("--states", type=int, default=40, help="states kept from the run")
    parser.add_argument("--repeat", type=int, default=200, help="passes over the kept states per timing")
    parser.add_argument("--omega", type=float, help="c'omega of a copy of a wearballs folder (rad/s)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="mbds-detection-") as temp:
        folder = args.folder.resolve()
        if args.omega is not None:
            folder = Path(shutil.copytree(folder, Path(temp) / "model"))
            for cns in folder.glob("*.cns"):
                cns.write_text("".join(f"c'omega = {args.omega!r}\n" if line.startswith("c'omega") else line
                                       for line in cns.read_text().splitlines(keepends=True)))
        model, max_pen, world, boxes, margin, contacts = kept_states(folder, args.time, args.states)
    found = _detect_all(model, max_pen, world, boxes, margin, contacts, 1)
    best = np.inf
    for _ in range(5):
        start = time.perf_counter()
        _detect_all(model, max_pen, world, boxes, margin, contacts, args.repeat)
        best = min(best, time.perf_counter() - start)
    calls = args.repeat * len(world)
    print(f"| model | states | contacts per state | µs per detection |\n|---|---|---|---|\n"
          f"| {args.folder.name} | {len(world)} | {found / len(world):.1f} | {1e6 * best / calls:.2f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
