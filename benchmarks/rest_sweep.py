"""Random drops onto the floor: does each body come to rest, and what do the contacts cost?

Run from the repository root: ``.venv/bin/python benchmarks/rest_sweep.py [--seed 11] [--runs
100] [--only 27,46]``. Each run drops one body (a rectangle of aspect 1:1 to 1:10 or a regular
polygon of 3 to 12 sides, random tilt, drop height up to 5 cm and spin up to 10 rad/s) onto the
floor with maximumTimestep 1e-5 ... 1e-3 s, maximumPenetration 1e-9 ... 1e-5 m, friction 0 ... 1 and
restitution 0 ... 0.8. Phase 1 runs to landing + 1.5 s, phase 2 one second more. Printed per run:
phase 1 steps over the count at maximumTimestep, impacts, rejected steps and LCP failures; phase 2
kinetic energy at its start and impacts, drift, energy gained (of m g size) and steps. A run
whose body lies still at the start of phase 2 is flagged REST-FAIL when phase 2 has an impact,
a drift above 1e-9 m or an energy gain above 1e-12 m g size; STOP when its steps exceed 30 times
the count at maximumTimestep. The totals end the output (docs/performance.md).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from mbds.kernel import layout as K  # noqa: E402
from mbds.model.load import load_model  # noqa: E402
from mbds.simulation.buffers import RunSettings  # noqa: E402
from mbds.simulation.run import RunStopped, initial_state, simulate  # noqa: E402
from tests.physics.models import BodyOnFloor, energy_residual, rectangle, regular_polygon  # noqa: E402
from tests.physics.test_tunnelling import G, polygon_mass  # noqa: E402

SETTLE, REST = 1.5, 1.0  # s after landing: phase 1, then phase 2


def draw(rng):
    """One random case: (kind, shape, tilt rad, drop m, spin rad/s, dt_max s, maxPen m, mu, e)."""
    if rng.random() < 0.5:
        length = rng.uniform(0.05, 0.4)
        shape, kind = rectangle(length / rng.uniform(1, 10), length), "rect"
    else:
        shape = regular_polygon(int(rng.integers(3, 13)), rng.uniform(0.03, 0.2))
        kind = f"poly{len(shape) - 1}"
    tilt, drop, spin = rng.uniform(0, np.pi), rng.uniform(0, 0.05), rng.uniform(-10, 10)
    dt_max, max_pen = 10 ** rng.uniform(-5, -3), 10 ** rng.uniform(-9, -5)
    return kind, shape, tilt, drop, spin, dt_max, max_pen, rng.uniform(0, 1), rng.uniform(0, 0.8)


def run_case(folder, mass, inertia, shape, fall, dt_max):
    """Both phases of one case; returns the printed figures as a dict."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(folder)
    state = initial_state(model, 0)
    budget = 30.0 * (fall + SETTLE + REST) / dt_max

    def give_up(t):
        if state.clock[K.STEPS] > budget:
            raise RunStopped("collapsed")

    first = simulate(model, RunSettings(break_time=fall + SETTLE), state, progress=give_up)
    impacts, steps = state.clock[K.IMPACTS], state.clock[K.STEPS]
    out = dict(ratio=steps * dt_max / (fall + SETTLE), impacts=impacts, rejected=state.clock[K.REJECTED],
               failures=state.clock[K.LCP_FAILURES])
    second = simulate(model, RunSettings(break_time=fall + SETTLE + REST), state, progress=give_up)
    scale = mass * G * np.ptp(shape, axis=0).max()  # J
    u = second.u[0]
    residual = energy_residual(second)
    out.update(ke=0.5 * (mass * (u[0] ** 2 + u[1] ** 2) + inertia * u[2] ** 2) / scale,
               impacts2=state.clock[K.IMPACTS] - impacts, drift=np.abs(second.q[:, 1:] - second.q[0, 1:]).max(),
               gain=-(residual - residual[0]).min() / scale, steps2=(state.clock[K.STEPS] - steps) * dt_max / REST,
               stopped=bool(first.stopped or second.stopped))
    out["rest_fail"] = out["ke"] < 1e-9 and (out["impacts2"] > 0 or out["drift"] > 1e-9 or out["gain"] > 1e-12)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--only", default="", help="comma-separated run numbers")
    args = parser.parse_args()
    only = {int(x) for x in args.only.split(",") if x}
    rng = np.random.default_rng(args.seed)
    tmp = Path(tempfile.mkdtemp())
    totals = dict(impacts=0.0, rejected=0.0, impacts2=0.0, flagged=0)
    start = time.time()
    for case in range(args.runs):
        kind, shape, tilt, drop, spin, dt_max, max_pen, mu, e = draw(rng)
        if only and case not in only:
            continue
        mass, inertia, shape = polygon_mass(shape)
        lowest = (np.sin(tilt) * shape[:, 0] + np.cos(tilt) * shape[:, 1]).min()
        fall = np.sqrt(2.0 * drop / G)
        folder = BodyOnFloor(shape, mass, inertia, position=(0.0, drop - lowest, tilt), velocity=(0.0, 0.0, spin),
                             friction=mu, restitution=e, dt_min=1e-10, dt_max=dt_max, max_penetration=max_pen,
                             break_time=fall + SETTLE + REST).write(tmp / f"m{case}")
        r = run_case(folder, mass, inertia, shape, fall, dt_max)
        flag = ("STOP " if r["stopped"] else "") + ("REST-FAIL" if r["rest_fail"] else "")
        print(f"{case:3d} {kind:7s} dt {dt_max:.1e} pen {max_pen:.1e} mu {mu:.2f} e {e:.2f} | phase 1 steps "
              f"{r['ratio']:.2f} impacts {r['impacts']:.0f} rejected {r['rejected']:.0f} lcpfail {r['failures']:.0f} | "
              f"phase 2 ke {r['ke']:.1e} impacts {r['impacts2']:.0f} drift {r['drift']:.1e} gain {r['gain']:+.1e} "
              f"steps {r['steps2']:.2f} {flag} ({time.time() - start:.0f} s)", flush=True)
        for key in ("impacts", "rejected", "impacts2"):
            totals[key] += r[key]
        totals["flagged"] += bool(flag)
    print(f"totals: phase 1 impacts {totals['impacts']:.0f}, rejected steps {totals['rejected']:.0f}; "
          f"phase 2 impacts {totals['impacts2']:.0f}; flagged runs {totals['flagged']}")


if __name__ == "__main__":
    main()
