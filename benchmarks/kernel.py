"""Time the stepping kernel on the example models, and mbds against Siconos on a bouncing ball.

Run from the repository root: ``.venv/bin/python benchmarks/kernel.py``.

Per example (campaigns/2mass 0.5 s, wearballs 1.5 s, woodpecker 1 s of simulated time):

- ``compile cold``: a fresh Python process with an empty ``MBDS_CACHE_DIR`` loads the model
  and takes one step; the figure is that process's time from its start to the end of the first
  step (import, model load, code generation and numba compilation of the model functions and
  of the stepper);
- ``start-up warm``: the same process again with that cache filled: import + load + loading
  the compiled code from the cache, up to the end of the first step. A process's start is
  the parent's time stamp just before it launches the process, so interpreter start is in;
- ``mbds run``: wall time of the whole ``mbds run`` command (warm cache) on a copy of the
  model folder (it writes a version folder), when that command exists;
- ``steps/s`` and ``sim s/wall s``: a full run inside this process after a warm-up run, from
  the ``STEPS`` counter and the wall time of ``simulate``.

Bouncing ball against Siconos: Debian's ``python3-siconos`` (Moreau–Jean time stepping,
theta = 0.5, a frictionless ``LagrangianLinearTIDS`` disk of 1 kg and radius 0.05 m dropped
from 0.2 m onto y = 0, ``NewtonImpactNSL`` with e = 0.8, ``LCP`` one-step problem) runs
BALL_STEPS fixed steps of BALL_STEP in a subprocess of ``/usr/bin/python3`` that times its own
loop. mbds runs the same ball as a 64-sided polygon on a fixed floor with minimumTimestep =
maximumTimestep = BALL_STEP (Poisson impacts, e = 0.8, friction 0), i.e. the same number of
steps; its time covers the ``simulate`` call, warm. Install Siconos with
``apt-get install -y python3-siconos``; without it the comparison says so and is skipped.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from mbds.kernel import layout as K  # noqa: E402
from mbds.model.load import load_model  # noqa: E402
from mbds.simulation.buffers import RunSettings  # noqa: E402
from mbds.simulation.run import simulate  # noqa: E402
from tests.physics.models import BodyOnFloor, regular_polygon  # noqa: E402

EXAMPLES = {"2mass": 0.5, "wearballs": 1.5, "woodpecker": 1.0}
BALL_STEP, BALL_STEPS = 1e-4, 20000  # s, count: 2 s of bouncing
SICONOS_PYTHON = "/usr/bin/python3"

FIRST_STEP = textwrap.dedent("""
    import json, sys, time, warnings
    from mbds.model.load import load_model
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate
    warnings.simplefilter("ignore")
    model = load_model(sys.argv[2])
    dt = model.files.world.settings.maximum_timestep
    simulate(model, RunSettings(break_time=dt))
    print(json.dumps({"first_step": time.time() - float(sys.argv[1])}))
""")

SICONOS = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    import siconos.kernel as sk
    e, radius, mass, drop, h, steps = (float(a) for a in sys.argv[1:7])
    steps = int(steps)
    q0 = [0.0, radius + drop, 0.0]
    ds = sk.LagrangianLinearTIDS(q0, [0.0, 0.0, 0.0], np.diag([mass, mass, 0.5 * mass * radius**2]))
    ds.setFExtPtr(np.array([0.0, -9.81 * mass, 0.0]))
    relation = sk.LagrangianLinearTIR(np.array([[0.0, 1.0, 0.0]]), np.array([-radius]))
    interaction = sk.Interaction(sk.NewtonImpactNSL(e), relation)
    world = sk.NonSmoothDynamicalSystem(0.0, h * steps)
    world.insertDynamicalSystem(ds)
    world.link(interaction, ds)
    stepping = sk.TimeStepping(world, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(0.5), sk.LCP())
    start = time.perf_counter()
    done = 0
    while stepping.hasNextEvent():
        stepping.computeOneStep()
        stepping.nextStep()
        done += 1
    wall = time.perf_counter() - start
    print(json.dumps({"steps": done, "wall": wall, "y": float(ds.q()[1])}))
""")


def first_step_time(folder: Path, cache: Path) -> float:
    """Seconds from launching a fresh process to the end of its first step of ``folder``."""
    env = dict(os.environ, MBDS_CACHE_DIR=str(cache))
    start = time.time()
    out = subprocess.run([sys.executable, "-c", FIRST_STEP, repr(start), str(folder)], env=env, cwd=ROOT,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])["first_step"]


def command_time(folder: Path, cache: Path, break_time: float) -> float | None:
    """Wall time (s) of ``mbds run`` on a copy of ``folder``; None when the command is missing."""
    exe = Path(sys.executable).with_name("mbds")
    if not exe.exists():
        return None
    help_text = subprocess.run([str(exe), "--help"], capture_output=True, text=True).stdout
    if " run " not in help_text:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / folder.name
        shutil.copytree(folder, copy, ignore=shutil.ignore_patterns("0[0-9][0-9]"))
        start = time.perf_counter()
        done = subprocess.run([str(exe), "run", str(copy)], env=dict(os.environ, MBDS_CACHE_DIR=str(cache)),
                              capture_output=True, text=True)
        wall = time.perf_counter() - start
    return wall if done.returncode == 0 else None


def timed_run(folder: Path, break_time: float) -> tuple[float, float]:
    """(steps, wall seconds) of a warm in-process run of ``folder`` to ``break_time``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(folder)
    simulate(model, RunSettings(break_time=min(break_time, 0.01)))  # warm-up: compiles the stepper
    start = time.perf_counter()
    result = simulate(model, RunSettings(break_time=break_time))
    return result.state.clock[K.STEPS], time.perf_counter() - start


def examples(cache_root: Path) -> None:
    print("## examples\n")
    print("| model | simulated s | steps | steps/s | sim s / wall s | compile cold s | start-up warm s | mbds run s |")
    print("|---|---|---|---|---|---|---|---|")
    for name, break_time in EXAMPLES.items():
        folder = ROOT / "campaigns" / name
        cache = cache_root / name
        cold = first_step_time(folder, cache)
        warm = min(first_step_time(folder, cache) for _ in range(3))
        command = command_time(folder, cache, break_time)
        os.environ["MBDS_CACHE_DIR"] = str(cache)
        steps, wall = timed_run(folder, break_time)
        shown = "missing" if command is None else f"{command:.2f}"
        print(f"| {name} | {break_time} | {steps:.0f} | {steps / wall:,.0f} | {break_time / wall:.2f} | {cold:.1f} | "
              f"{warm:.2f} | {shown} |")


def bouncing_ball(cache_root: Path) -> None:
    print("\n## bouncing ball, mbds against Siconos (Moreau-Jean)\n")
    e, radius, mass, drop = 0.8, 0.05, 1.0, 0.2
    os.environ["MBDS_CACHE_DIR"] = str(cache_root / "ball")
    with tempfile.TemporaryDirectory() as tmp:
        folder = BodyOnFloor(regular_polygon(64, radius), mass, 0.5 * mass * radius**2, position=(0.0, radius + drop, 0.0),
                             restitution=e, dt_min=BALL_STEP, dt_max=BALL_STEP, max_penetration=1e-3,
                             history_every=100, break_time=BALL_STEP * BALL_STEPS).write(Path(tmp) / "ball")
        steps, wall = timed_run(folder, BALL_STEP * BALL_STEPS)
    ours = steps / wall
    print(f"mbds: {steps:.0f} steps in {wall:.3f} s: {ours:,.0f} steps/s")
    try:
        out = subprocess.run([SICONOS_PYTHON, "-c", SICONOS, *map(str, (e, radius, mass, drop, BALL_STEP, BALL_STEPS))],
                             capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as error:
        detail = getattr(error, "stderr", "") or str(error)
        print(f"Siconos: MISSING or failing ({detail.strip().splitlines()[-1] if detail.strip() else error}); "
              "install it with `apt-get install -y python3-siconos`")
        return
    theirs = json.loads(out.stdout.strip().splitlines()[-1])
    rate = theirs["steps"] / theirs["wall"]
    print(f"Siconos: {theirs['steps']} steps in {theirs['wall']:.3f} s: {rate:,.0f} steps/s")
    print(f"ratio mbds/Siconos steps per second: {ours / rate:.2f}")


OMEGAS = (40.0, 50.0, 62.83185307, 80.0, 100.0)
"""c'omega (rad/s) of the wearballs drive swept by :func:`stick_slip`."""

SWEEP_TIME = 0.3
"""Simulated time (s) of each run of the sweep."""


def stick_slip(cache_root: Path) -> None:
    """Wall time per simulated second of campaigns/wearballs across its drive frequency c'omega:
    resting and stick-slip regimes must not collapse the step (goal: all within 3x of the
    fastest). The variants differ in a constant only, so they share one compiled model."""
    print("\n## stick-slip: wearballs across c'omega\n")
    print("| c'omega rad/s | steps | mean step s | wall s per simulated s |")
    print("|---|---|---|---|")
    os.environ["MBDS_CACHE_DIR"] = str(cache_root / "wearballs")
    costs = []
    with tempfile.TemporaryDirectory() as tmp:
        for omega in OMEGAS:
            folder = Path(tmp) / f"omega{omega:g}"
            shutil.copytree(ROOT / "campaigns" / "wearballs", folder)
            cns = folder / "wearballs.cns"
            cns.write_text("".join(f"c'omega = {omega!r}\n" if line.startswith("c'omega") else line
                                   for line in cns.read_text().splitlines(keepends=True)))
            steps, wall = timed_run(folder, SWEEP_TIME)
            costs.append(wall / SWEEP_TIME)
            print(f"| {omega:g} | {steps:.0f} | {SWEEP_TIME / steps:.2e} | {costs[-1]:.2f} |")
    print(f"\nslowest / fastest: {max(costs) / min(costs):.2f} (goal: at most 3)")


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        examples(Path(tmp))
        stick_slip(Path(tmp))
        bouncing_ball(Path(tmp))
    print("\ngoals: start-up warm < 2 s; woodpecker sim s / wall s > 1 (1 s simulated in under 1 s)")


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
