"""Time the stepping kernel on the example models, and mbds against Siconos on a bouncing ball.

Run from the repository root: ``.venv/bin/python benchmarks/kernel.py``; ``--only
ball,woodpecker`` runs only the named parts (examples, stick-slip, woodpecker, precision, ball);
``--sweep-time`` (default 1.5 s, the whole run) and ``--amplitudes`` set the stick-slip sweep
of campaigns/wearballs over c'omega (and c'amplitude).

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
steps; its time covers the ``simulate`` call, warm. Its maximumPenetration is BALL_PENETRATION
(the figures of docs/performance.md from before the detection kept only a vertex's nearest faces
used 1e-3, whose default skin of 0.1 m made the first impact plastic). Install Siconos with
``apt-get install -y python3-siconos``; without it the comparison says so and is skipped.

The woodpecker against Siconos (Moreau–Jean on the published small-angle model): at the same
step of WOODPECKER_STEP (``woodpecker``), and at several steps, each code measured against its
own run at a small step (``precision``: work against precision, where the two models'
differences drop out).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time
import warnings
from pathlib import Path

from bytecode import write_bytecode

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from mbds.data.run_result import RunResult  # noqa: E402
from mbds.kernel import layout as K  # noqa: E402
from mbds.model.load import load_model  # noqa: E402
from mbds.simulation.buffers import RunSettings  # noqa: E402
from mbds.simulation.run import simulate  # noqa: E402
from tests.physics.limit_cycle import cycle_figures, velocity_jumps  # noqa: E402
from tests.physics.models import BodyOnFloor, regular_polygon  # noqa: E402

EXAMPLES = {"2mass": 0.5, "wearballs": 1.5, "woodpecker": 1.0}
BALL_STEP, BALL_STEPS = 1e-4, 20000  # s, count: 2 s of bouncing
BALL_PENETRATION = 5e-4  # m: at most 2e-4 per step at the landing speed of 2 m/s; skin 0.05 m
SICONOS_PYTHON = "/usr/bin/python3"

FIRST_STEP = textwrap.dedent("""
    import json, sys, time, warnings
    from mbds.model.load import load_model
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate
    warnings.simplefilter("ignore")
    model = load_model(sys.argv[2])
    dt = model.settings.maximum_timestep
    simulate(model, RunSettings(break_time=dt))
    print(json.dumps({"first_step": time.time() - float(sys.argv[1])}))
""")

SINGLE_THREAD = {name: "1" for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
"""Siconos runs on one thread, as mbds does: with its default thread count its woodpecker took
5.0 s per simulated second instead of 1.6 s while another process ran on the second core."""

RUNS = 3
"""Timed runs of each mbds and Siconos case; the fastest counts (the machine is shared)."""

WOODPECKER_TIME, WOODPECKER_STEP = 2.0, 1e-5  # s: simulated time of both runs, Siconos' fixed step
PUBLISHED_PERIOD = 0.1461  # s, Siconos' Woodpecker.ref (Leine, Glocker, van Campen 2003: 0.1452 s)
PRECISION_STEPS = (1e-5, 3e-5, 1e-4)  # s: steps of the work-precision comparison
REFERENCE_STEP = 2e-6  # s: each code's own reference run in that comparison

SICONOS_WOODPECKER = """
import json, sys, time
import numpy as np
import siconos.kernel as sk
import siconos.numerics as sn
rO, rM, hM, lM, lG, hS, lS = 0.0025, 0.0031, 0.0058, 0.010, 0.015, 0.02, 0.0201
mM, mS, JM, JS, c, g = 0.0003, 0.0045, 5.0e-9, 7.0e-7, 0.0056, 9.81
h, T = float(sys.argv[1]), float(sys.argv[2])
M = np.array([[mS + mM, mS * lM, mS * lG], [mS * lM, JM + mS * lM * lM, mS * lM * lG], [mS * lG, mS * lM * lG, JS + mS * lG * lG]])
K = np.array([[0, 0, 0], [0, c, -c], [0, -c, c]])
ds = sk.LagrangianLinearTIDS([0.0, -0.1036, -0.2788], [-0.3411, 0.0, -7.4583], M, K, np.zeros((3, 3)))
ds.setFExtPtr(np.array([-(mS + mM) * g, -mS * lM * g, -mS * lG * g]))
nsds = sk.NonSmoothDynamicalSystem(0.0, T)
nsds.insertDynamicalSystem(ds)
r1 = sk.LagrangianLinearTIR(np.array([[0, 0, -hS], [1, lM, lG - lS]]), np.array([lM + lG - lS - rO, 0]))
nsds.link(sk.Interaction(sk.NewtonImpactFrictionNSL(0.5, 0.0, 0.3, 2), r1), ds)
for sign in (1.0, -1.0):
    r = sk.LagrangianLinearTIR(np.array([[0, sign * hM, 0], [1, rM, 0]]), np.array([rM - rO, 0]))
    nsds.link(sk.Interaction(sk.NewtonImpactFrictionNSL(0.0, 0.0, 0.3, 2), r), ds)
td = sk.TimeDiscretisation(0.0, h)
sim = sk.TimeStepping(nsds, td)
sim.insertIntegrator(sk.MoreauJeanOSI(0.5))
sim.insertNonSmoothProblem(sk.FrictionContact(2, sn.SICONOS_FRICTION_2D_NSGS))
rows = []
start = time.perf_counter()
while sim.hasNextEvent():
    sim.computeOneStep()
    rows.append([sim.nextTime(), *ds.q()])
    sim.nextStep()
wall = time.perf_counter() - start
a = np.array(rows)
t, y, phiM, phiS = a.T
up = np.flatnonzero((phiS[:-1] < -0.05) & (phiS[1:] >= -0.05))
cross = t[up] + (-0.05 - phiS[up]) / (phiS[up + 1] - phiS[up]) * (t[up + 1] - t[up])
cross = cross[cross > 1.0]
late = t > 1.0
print(json.dumps({"steps": len(rows), "wall": wall, "period": float(np.diff(cross).mean()),
                  "descent": float(-(y[late][-1] - y[late][0]) / (t[late][-1] - t[late][0])),
                  "ring": [float(phiM[late].min()), float(phiM[late].max())], "bird": [float(phiS[late].min()), float(phiS[late].max())]}))
"""

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


def siconos_best(script: str, *args, runs: int = RUNS) -> dict | None:
    """The output (a dict with its ``wall`` time) of the fastest of ``runs`` runs of a Siconos
    script in SICONOS_PYTHON; None (and a line saying so) when Siconos is missing or fails."""
    best = None
    for _ in range(runs):
        try:
            out = subprocess.run([SICONOS_PYTHON, "-c", script, *map(str, args)], capture_output=True, text=True,
                                 check=True, env={**os.environ, **SINGLE_THREAD})
        except (OSError, subprocess.CalledProcessError) as error:
            detail = (getattr(error, "stderr", "") or str(error)).strip()
            print(f"Siconos: MISSING or failing ({detail.splitlines()[-1] if detail else error}); "
                  "install it with `apt-get install -y python3-siconos`")
            return None
        theirs = json.loads(out.stdout.strip().splitlines()[-1])
        if best is None or theirs["wall"] < best["wall"]:
            best = theirs
    return best


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


def timed_run(folder: Path, break_time: float, runs: int = RUNS) -> tuple[float, float, RunResult]:
    """(steps, wall seconds, result) of a warm in-process run of ``folder`` to ``break_time``;
    the time is the best of ``runs`` runs."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(folder)
    simulate(model, RunSettings(break_time=min(break_time, 0.01)))  # warm-up: compiles the stepper
    best = np.inf
    for _ in range(runs):
        start = time.perf_counter()
        result = simulate(model, RunSettings(break_time=break_time))
        best = min(best, time.perf_counter() - start)
    return result.state.clock[K.STEPS], best, result


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
        steps, wall, _ = timed_run(folder, break_time)
        shown = "missing" if command is None else f"{command:.2f}"
        print(f"| {name} | {break_time} | {steps:.0f} | {steps / wall:,.0f} | {break_time / wall:.2f} | {cold:.1f} | "
              f"{warm:.2f} | {shown} |")


def bouncing_ball(cache_root: Path) -> None:
    print("\n## bouncing ball, mbds against Siconos (Moreau-Jean)\n")
    e, radius, mass, drop = 0.8, 0.05, 1.0, 0.2
    os.environ["MBDS_CACHE_DIR"] = str(cache_root / "ball")
    with tempfile.TemporaryDirectory() as tmp:
        folder = BodyOnFloor(regular_polygon(64, radius), mass, 0.5 * mass * radius**2, position=(0.0, radius + drop, 0.0),
                             restitution=e, dt_min=BALL_STEP, dt_max=BALL_STEP, max_penetration=BALL_PENETRATION,
                             history_every=100, break_time=BALL_STEP * BALL_STEPS).write(Path(tmp) / "ball")
        steps, wall, result = timed_run(folder, BALL_STEP * BALL_STEPS)
    ours = steps / wall
    print(f"mbds: {steps:.0f} steps in {wall:.3f} s: {ours:,.0f} steps/s "
          f"({result.state.clock[K.IMPACTS]:.0f} impacts, y = {result.state.q[1]:.6f} m at the end)")
    theirs = siconos_best(SICONOS, e, radius, mass, drop, BALL_STEP, BALL_STEPS)
    if theirs is None:
        return
    rate = theirs["steps"] / theirs["wall"]
    print(f"Siconos: {theirs['steps']} steps in {theirs['wall']:.3f} s: {rate:,.0f} steps/s")
    print(f"ratio mbds/Siconos steps per second: {ours / rate:.2f}")


OMEGAS = (40.0, 50.0, 62.83185307, 80.0, 100.0)
"""c'omega (rad/s) of the wearballs drive swept by :func:`stick_slip`."""

AMPLITUDES = (0.005,)
"""c'amplitude (m) of the sweep; ``--amplitudes 0.003,0.004,0.005,0.006`` runs more."""

SWEEP_TIME = 1.5
"""Simulated time (s) of each run of the sweep: the whole run of campaigns/wearballs, so the
impacts of its later part count (``--sweep-time`` changes it)."""


def stick_slip(cache_root: Path, sweep_time: float = SWEEP_TIME, amplitudes=AMPLITUDES) -> None:
    """Wall time per simulated second of campaigns/wearballs across its drive frequency c'omega
    (and amplitude): resting and stick-slip regimes must not collapse the step (goal: all within
    3x of the fastest). The variants differ in constants only, so they share one compiled model."""
    print("\n## stick-slip: wearballs across c'omega\n")
    print("| c'amplitude m | c'omega rad/s | steps | impacts | mean step s | wall s per simulated s |")
    print("|---|---|---|---|---|---|")
    os.environ["MBDS_CACHE_DIR"] = str(cache_root / "wearballs")
    costs = []
    with tempfile.TemporaryDirectory() as tmp:
        for amplitude in amplitudes:
            for omega in OMEGAS:
                folder = Path(tmp) / f"a{amplitude:g}omega{omega:g}"
                shutil.copytree(ROOT / "campaigns" / "wearballs", folder)
                cns = folder / "wearballs.cns"
                cns.write_text("".join(f"c'omega = {omega!r}\n" if line.startswith("c'omega") else
                                       f"c'amplitude = {amplitude!r}\n" if line.startswith("c'amplitude") else line
                                       for line in cns.read_text().splitlines(keepends=True)))
                steps, wall, result = timed_run(folder, sweep_time)
                costs.append(wall / sweep_time)
                print(f"| {amplitude:g} | {omega:g} | {steps:.0f} | {result.state.clock[K.IMPACTS]:.0f} | "
                      f"{sweep_time / steps:.2e} | {costs[-1]:.3f} |")
    print(f"\nslowest / fastest: {max(costs) / min(costs):.2f} (goal: at most 3)")


def woodpecker(cache_root: Path) -> None:
    """The woodpecker toy in mbds (campaigns/woodpecker) and in Siconos (the published
    small-angle model: LagrangianLinearTIDS, three LagrangianLinearTIR contacts with
    NewtonImpactFrictionNSL, Moreau-Jean theta = 1/2, 2-D friction contact solved by NSGS, fixed
    steps of WOODPECKER_STEP): period error against PUBLISHED_PERIOD, descent and wall time per
    simulated second, both over the second of a 2 s run."""
    print("\n## woodpecker, mbds against Siconos (Moreau-Jean)\n")
    print("| | period ms | period error | descent mm/s | sleeve rad | bird rad | wall s per simulated s |")
    print("|---|---|---|---|---|---|---|")
    os.environ["MBDS_CACHE_DIR"] = str(cache_root / "woodpecker")
    _, wall, result = timed_run(ROOT / "campaigns" / "woodpecker", WOODPECKER_TIME)
    ours = woodpecker_cycle(result)
    print(f"| mbds | {1e3 * ours.period:.2f} | {ours.period / PUBLISHED_PERIOD - 1:+.2%} | "
          f"{1e3 * ours.descent_speed:.1f} | {ours.ring_limits[0]:.4f} .. {ours.ring_limits[1]:.4f} | "
          f"{ours.bird_limits[0]:.4f} .. {ours.bird_limits[1]:.4f} | {wall / WOODPECKER_TIME:.2f} |")
    theirs = siconos_best(SICONOS_WOODPECKER, WOODPECKER_STEP, WOODPECKER_TIME)
    if theirs is None:
        return
    ring, bird = theirs["ring"], theirs["bird"]
    print(f"| Siconos | {1e3 * theirs['period']:.2f} | {theirs['period'] / PUBLISHED_PERIOD - 1:+.2%} | "
          f"{1e3 * theirs['descent']:.1f} | {ring[0]:.4f} .. {ring[1]:.4f} | {bird[0]:.4f} .. {bird[1]:.4f} | "
          f"{theirs['wall'] / WOODPECKER_TIME:.2f} |")


def woodpecker_precision(cache_root: Path) -> None:
    """Work against precision on the woodpecker: both codes at the steps PRECISION_STEPS (mbds:
    maximumTimestep of a copy of campaigns/woodpecker; Siconos: its fixed step), each measured
    against its own run at REFERENCE_STEP, so that the model differences (mbds' polygons
    against the small-angle model) drop out. The deviation is the largest relative difference
    of the period, the descent, the sleeve's amplitude and the bird's range from the reference
    run. The last line compares Siconos at WOODPECKER_STEP with the fastest mbds run that
    deviates no more."""
    print("\n## woodpecker, work against precision (each code against its own run at "
          f"{REFERENCE_STEP:g} s)\n")
    print("| | step s | period ms | descent mm/s | sleeve amplitude rad | bird range rad | deviation | "
          "wall s per simulated s |")
    print("|---|---|---|---|---|---|---|---|")
    os.environ["MBDS_CACHE_DIR"] = str(cache_root / "woodpecker")
    ours, theirs = {}, {}
    for step in (REFERENCE_STEP, *PRECISION_STEPS):
        runs = 1 if step == REFERENCE_STEP else RUNS
        _, wall, result = timed_run(woodpecker_copy(cache_root / f"woodpecker-{step:g}", step), WOODPECKER_TIME, runs)
        found = woodpecker_cycle(result)
        ring, bird = found.ring_limits, found.bird_limits
        ours[step] = (found.period, found.descent_speed, 0.5 * (ring[1] - ring[0]), bird[1] - bird[0],
                      wall / WOODPECKER_TIME)
        out = siconos_best(SICONOS_WOODPECKER, step, WOODPECKER_TIME, runs=runs)
        if out is not None:
            theirs[step] = (out["period"], out["descent"], 0.5 * (out["ring"][1] - out["ring"][0]),
                            out["bird"][1] - out["bird"][0], out["wall"] / WOODPECKER_TIME)
    deviation = {}
    for name, figures in (("mbds", ours), ("Siconos", theirs)):
        reference = np.array(figures.get(REFERENCE_STEP, (np.nan,) * 5)[:4])
        for step, (period, descent, sleeve, bird, cost) in figures.items():
            deviation[name, step] = float(np.max(np.abs(np.array((period, descent, sleeve, bird)) / reference - 1.0)))
            print(f"| {name} | {step:g} | {1e3 * period:.3f} | {1e3 * descent:.2f} | {sleeve:.5f} | {bird:.5f} | "
                  f"{deviation[name, step]:.3%} | {cost:.3f} |")
    if WOODPECKER_STEP not in theirs:
        return
    allowed = deviation["Siconos", WOODPECKER_STEP]
    within = [step for step in PRECISION_STEPS if deviation["mbds", step] <= allowed]
    if within:
        step = max(within)
        print(f"\nSiconos at {WOODPECKER_STEP:g} s deviates by {allowed:.3%}; mbds at {step:g} s by "
              f"{deviation['mbds', step]:.3%}, {theirs[WOODPECKER_STEP][4] / ours[step][4]:.1f} x faster "
              f"(at the same step: {theirs[WOODPECKER_STEP][4] / ours[WOODPECKER_STEP][4]:.1f} x)")
    else:
        print(f"\nno mbds run deviates by no more than Siconos at {WOODPECKER_STEP:g} s ({allowed:.3%})")


def woodpecker_cycle(result: RunResult):
    """The limit cycle's figures of a woodpecker run (tests.physics.limit_cycle), over its second
    second."""
    impacts = velocity_jumps(result.time, result.u, result.a, (1.0, 0.01, 0.015), 1e-3)
    return cycle_figures(result.time, result.q, impacts, 1.0)


def woodpecker_copy(folder: Path, step: float) -> Path:
    """A copy of campaigns/woodpecker in ``folder`` with maximumTimestep ``step`` (s)."""
    shutil.copytree(ROOT / "campaigns" / "woodpecker", folder, dirs_exist_ok=True)
    world = folder / "woodpecker.wld"
    text, count = re.subn(r"(?m)^maximumTimestep\s*=.*$", f"maximumTimestep = {step!r}", world.read_text())
    if count != 1:
        raise SystemExit(f"{world}: no single maximumTimestep line to replace")
    world.write_text(text)
    return folder


PARTS = {"examples": examples, "stick-slip": stick_slip, "woodpecker": woodpecker, "precision": woodpecker_precision,
         "ball": bouncing_ball}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default=",".join(PARTS), help=f"comma-separated parts of {', '.join(PARTS)}")
    parser.add_argument("--sweep-time", type=float, default=SWEEP_TIME,
                        help=f"simulated seconds of each stick-slip run (default {SWEEP_TIME})")
    parser.add_argument("--amplitudes", default=",".join(map(str, AMPLITUDES)),
                        help="comma-separated c'amplitude values (m) of the stick-slip sweep")
    args = parser.parse_args()
    write_bytecode()
    chosen = args.only.split(",")
    unknown = sorted(set(chosen) - set(PARTS))
    if unknown:
        parser.error(f"unknown part(s): {', '.join(unknown)}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, part in PARTS.items():
            if name == "stick-slip" and name in chosen:
                stick_slip(Path(tmp), args.sweep_time, tuple(float(a) for a in args.amplitudes.split(",")))
            elif name in chosen:
                part(Path(tmp))
    print("\ngoals: start-up warm < 2 s; woodpecker sim s / wall s > 1 (1 s simulated in under 1 s)")


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
