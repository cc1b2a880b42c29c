"""A wear campaign of 8 chains on MPI ranks: 1 worker against 2 workers, in one run.

The campaign: a copy of campaigns/wearballs with ``[campaign]`` varying ``c'amplitude`` (2 values)
and ``c'omega`` (4 values), 8 chains of versions 000-009 (full breakTime of 1.5 s each), every
version worn into the next: 80 runs and 80 wear steps. It runs from scratch as

- ``mpiexec -n 2``: the scheduling rank and 1 worker,
- ``mpiexec -n 3``: the scheduling rank and 2 workers (the machine has 2 cores; rank 0 only
  hands out tasks and writes the ledger, sleeping between polls),

each twice, alternating, the faster of each counting; and, for the path without MPI, once with
``mbds-campaign run --workers 2`` (a process pool).
All share one compile cache (``MBDS_CACHE_DIR``), filled first by a cold warm-up whose time is
shown on its own.

Figures:

- ``wall s``: the whole command, interpreter start, imports and the warm-up (a cache load) in;
  ``loop s``: the first task's start on its worker (its end in the ledger less its own wall
  time) to the last task's end in the ledger (the fan-out alone; what a worker does before its
  first task, imports and loading the compiled model, counts as start-up);
- ``tasks s``: the sum of the tasks' wall times (measured by the worker around each task);
- efficiency: t(1 worker) / (2 t(2 workers)), for the whole command and for the loop; the
  loop's is split into how busy the scheduler kept the 2 workers, how fast tasks ran with two
  at once against one alone (the machine's share), and how busy it kept 1 worker;
- per-task overhead: ``sched ms``, the ledger's end - start of a task minus its own wall time
  (sending, polling, receiving, ledger write; each worker's first task left out, since its
  start in the ledger comes before the worker's own start-up), and ``idle ms``, a worker's mean gap between the
  end of one task and the start of the next; ``start-up`` and ``writing``: a run task's wall time
  split by timing, in this process, the model load and the simulation of the same versions
  (the rest is writing the outputs);
- ``compiled``: functions numba compiled in the tasks (numba's compile events, recorded per task
  in the ledger): 0 proves that no worker compiled;
- collection: ``mbds-campaign collect`` of the 2-worker campaign, against its compute (the sum
  of its tasks' wall times); and the same for the campaign with a history sample every 10 ms
  (``writeToHistoryMultipleOfMaximumTimestep = 100``) instead of every 1 ms (10), run once more
  on 2 workers. Collecting reads each run file's summary variables and describes its root group;
  the histories stay in the run files;
- opening: ``mbds.open_campaign`` of a campaign file holding 1000 run references (the 80 runs of
  the 2-worker campaign, each referenced 12 or 13 times), the size the documentation promises
  to open in under 2 s.

The two MPI campaigns' collected data are compared bit for bit.

Scaling mode, ``--scaling [--chains 48] [--versions 5] [--workers 1,2,4,8,15]``: the campaign
with ``--chains`` chains (``c'amplitude`` takes chains / 4 values) and versions 000 to
``--versions`` - 1 runs for real on 1 worker, and on every N of ``--workers`` that the machine's
cores allow (N + 1 ranks); for the other N, the measured task times are replayed
(``benchmarks/scaling.py``) with the scheduler's own rules and the measured round trip, and the
start-up and shut-down of the measured run are added. It prints N, wall, parallel efficiency
(wall(1) / (N wall(N))), whether the row was measured or replayed, and the split of the time
lost against a perfect speed-up: start-up and shut-down, idle workers (the tail), round trips,
and the extra time of each worker's first run over what the run takes later (its chain's next
version's run scaled by the other chains' ratio of the two versions' runs; measured, and for
replayed rows the 1-worker run's, charged in the replay to every worker's first run). The same replay with
tasks handed out in plan order shows what ordering by remaining work gains.

Opening mode, ``--opening [--repeat 5]``: only the opening figure. The campaign above runs once
on a pool of 2 workers (compiled models from the usual cache), is collected, and the campaign
file of 1000 references is opened ``--repeat`` times; each time is printed.

Run from the repository root: ``.venv/bin/python benchmarks/campaign.py [--scaling ... | --opening]``.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from datetime import datetime
from pathlib import Path

import numpy as np
from bytecode import write_bytecode

ROOT = Path(__file__).resolve().parents[1]
PYTHON = Path(sys.executable)
MPIEXEC = PYTHON.parent / "mpiexec"
JOB = """[main]
worldFile = wearballs.wld
jobs = 000-009
lexicoRandomizationRange = 0.0, 0.0
maxMinutesForJob = 10
createNextVersionAtEnd = 1
[campaign]
c'amplitude = 0.004, 0.005
c'omega = 62.83185307, 70, 80, 90
"""
COARSE = "world.writeToHistoryMultipleOfMaximumTimestep = 100\n"
"""The same campaign with a history sample every 10 ms instead of every 1 ms."""
LAUNCHES = {
    "MPI, 1 worker": [str(MPIEXEC), "-n", "2", str(PYTHON), "-m", "mpi4py", "-m", "mbds.cli.campaign", "run"],
    "MPI, 2 workers": [str(MPIEXEC), "-n", "3", str(PYTHON), "-m", "mpi4py", "-m", "mbds.cli.campaign", "run"],
    "pool, 2 workers": [str(PYTHON), "-m", "mbds.cli.campaign", "run", "--workers", "2"],
}
ROUNDS = 2
"""Each MPI launch runs this many times, alternating, and the fastest counts: the two vCPUs of a
shared machine do not always run two processes at full speed at once."""
SINGLE_THREAD = {name: "1" for name in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS",
                                        "NUMBA_NUM_THREADS")}


def make_campaign(folder: Path, extra: str = "", job_text: str = JOB) -> Path:
    """A copy of campaigns/wearballs (model files only) with the campaign's job file (``extra``
    added to its [campaign] section); its path."""
    shutil.copytree(ROOT / "campaigns" / "wearballs", folder,
                    ignore=shutil.ignore_patterns("[0-9][0-9][0-9]", "campaign", ".*"))
    job = folder / "campaign.job"
    job.write_text(job_text + extra)
    return job


def scaling_job(chains: int, versions: int) -> str:
    """The job file of the scaling campaign: ``chains`` / 4 amplitudes x 4 frequencies."""
    if chains % 4:
        raise SystemExit("--chains must be a multiple of 4 (amplitudes x 4 frequencies)")
    amplitudes = np.linspace(0.003, 0.006, chains // 4)
    return (JOB.replace("jobs = 000-009", f"jobs = 000-{versions - 1:03d}")
            .replace("c'amplitude = 0.004, 0.005", "c'amplitude = " + ", ".join(f"{a:.6g}" for a in amplitudes)))


def mpi_launch(workers: int) -> list[str]:
    """The command that runs a campaign on ``workers`` MPI workers and one scheduling rank."""
    return [str(MPIEXEC), "-n", str(workers + 1), str(PYTHON), "-m", "mpi4py", "-m", "mbds.cli.campaign", "run"]


def cold_warm_up(job: Path, env: dict) -> tuple[float, int]:
    """Seconds to compile the campaign's models into an empty cache, and how many structures."""
    code = ("import sys, time; from mbds.campaign.plan import expand; from mbds.campaign.run import warm_up; "
            "t = time.perf_counter(); n = warm_up(expand(sys.argv[1])); print(time.perf_counter() - t, n)")
    out = subprocess.run([str(PYTHON), "-c", code, str(job)], env=env, capture_output=True, text=True, check=True)
    seconds, structures = out.stdout.split()
    return float(seconds), int(structures)


def launch(name: str, job: Path, env: dict, command: list[str] | None = None) -> dict:
    """Run the campaign as ``name`` says (or with ``command``); the figures of its ledger."""
    begun = time.perf_counter()
    done = subprocess.run((command or LAUNCHES[name]) + [str(job)], env=env, capture_output=True, text=True)
    wall = time.perf_counter() - begun
    if done.returncode != 0:
        raise SystemExit(f"{name}: exit {done.returncode}\n{done.stderr}")
    tasks = json.loads((job.parent / "campaign" / "ledger.json").read_text())["tasks"]
    start = {k: _seconds(e["start"]) for k, e in tasks.items()}
    end = {k: _seconds(e["end"]) for k, e in tasks.items()}
    idle = []
    for rank in {e.get("rank") for e in tasks.values()} - {None}:
        mine = sorted((k for k, e in tasks.items() if e.get("rank") == rank), key=start.get)
        idle += [start[b] - end[a] for a, b in zip(mine, mine[1:])]
    return {
        "wall": wall,
        "loop": max(end.values()) - min(end[k] - e["wall"] for k, e in tasks.items()),
        "tasks": sum(e["wall"] for e in tasks.values()),
        "count": len(tasks),
        "all_done": all(e["state"] == "done" for e in tasks.values()),
        "sched": np.mean([end[k] - start[k] - e["wall"] for k, e in tasks.items() if k not in _firsts(tasks, start)]),
        "idle": np.mean(idle) if idle else float("nan"),
        "compiled": sum(e["compiled"] for e in tasks.values()),
        "ranks": sorted({e["rank"] for e in tasks.values() if "rank" in e}),
        "run_walls": {k: e["wall"] for k, e in tasks.items() if k.endswith("/run")},
        "walls": {k: e["wall"] for k, e in tasks.items()},
        "first_task_extra": _first_task_extra(tasks, start),
    }


def _firsts(tasks: dict, start: dict) -> set[str]:
    """The first task of each rank."""
    ranks = {e.get("rank") for e in tasks.values()} - {None}
    return {min((k for k, e in tasks.items() if e.get("rank") == rank), key=start.get) for rank in ranks}


def _first_task_extra(tasks: dict, start: dict) -> float:
    """Mean extra wall time (s) of each worker's first run task over what that run would take
    later in the campaign.

    The chains' runs differ (their variants, and the versions as the bodies wear), so the first
    run is compared with its own chain: its chain's next version's run, scaled by how the other
    chains' first two versions' runs compare (the median of their ratios). A plan of one version
    compares it with the other chains' runs of the same version instead."""
    runs = {k: e for k, e in tasks.items() if k.endswith("/run")}
    firsts = []
    for rank in {e.get("rank") for e in runs.values()} - {None}:
        first = min((k for k, e in runs.items() if e.get("rank") == rank), key=start.get)
        firsts.append(runs[first]["wall"] - _expected_run(first, runs))
    return float(np.mean(firsts)) if firsts else 0.0


def _expected_run(first: str, runs: dict) -> float:
    """The wall time (s) the run task ``first`` would take if it were not a worker's first (see
    :func:`_first_task_extra`)."""
    chain, version = first.rsplit("/", 2)[0], _version(first)
    later = sorted(k for k in runs if k.startswith(chain + "/") and _version(k) > version)
    if later:
        following = _version(later[0])
        ratios = [runs[k]["wall"] / runs[f"{c}/{following}/run"]["wall"]
                  for k in runs if _version(k) == version and (c := k.rsplit("/", 2)[0]) != chain
                  and f"{c}/{following}/run" in runs]
        if ratios:
            return runs[later[0]]["wall"] * float(np.median(ratios))
    others = [e["wall"] for k, e in runs.items() if k != first and _version(k) == version]
    return float(np.mean(others)) if others else runs[first]["wall"]


def _version(task_id: str) -> str:
    """The version number in a task id (``v03/002/run`` -> ``002``)."""
    return next(part for part in task_id.split("/") if part.isdigit())


def _seconds(stamp: str) -> float:
    return datetime.fromisoformat(stamp).timestamp()


def run_task_split(job: Path, run_walls: dict) -> tuple[float, float, float]:
    """Mean seconds per run task of loading the model and of simulating, timed here on chain
    v00's versions (after one untimed load), and the mean run task wall time of those versions."""
    from mbds.model.load import load_model
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate

    folders = sorted((job.parent / "campaign" / "v00").glob("[0-9][0-9][0-9]"))[:-1]  # the last is not run
    load_model(folders[0])
    loads, sims, walls = [], [], []
    for folder in folders:
        begun = time.perf_counter()
        model = load_model(folder)
        loads.append(time.perf_counter() - begun)
        begun = time.perf_counter()
        simulate(model, RunSettings(model.break_time))
        sims.append(time.perf_counter() - begun)
        walls.append(run_walls[f"v00/{folder.name}/run"])
    return float(np.mean(loads)), float(np.mean(sims)), float(np.mean(walls))


def collected(job: Path) -> tuple[float, object]:
    """Seconds to merge the campaign into campaign.nc (in this process), and the tree read back."""
    from mbds.campaign.collect import collect, open_campaign
    from mbds.campaign.plan import expand

    plan = expand(job)
    begun = time.perf_counter()
    path = collect(plan)
    seconds = time.perf_counter() - begun
    return seconds, open_campaign(path)


def opening(job: Path, runs: int = 1000) -> float:
    """Seconds for ``open_campaign`` of a campaign file with ``runs`` references, made from the
    collected campaign of ``job`` by referencing its runs again and again."""
    import netCDF4
    import xarray as xr

    from mbds.campaign.collect import RUNS_GROUP, open_campaign, write_references

    folder = job.parent / "campaign"
    with netCDF4.Dataset(folder / "campaign.nc") as f:
        group = f.groups[RUNS_GROUP]
        real = list(zip(group["node"][...], group["file"][...], group["description"][...]))
        times, starts = group["time"][...], list(group["time_start"][...]) + [len(group["time"])]
    references = []
    for k in range(runs):
        j = k % len(real)
        references.append((f"/copy{k // len(real):02d}{real[j][0]}", real[j][1], real[j][2],
                           times[starts[j]:starts[j + 1]]))
    target = folder / "many.nc"
    with xr.open_dataset(folder / "campaign.nc") as summary:
        summary.load().to_netcdf(target)
    with netCDF4.Dataset(target, "a") as out:
        write_references(out.createGroup(RUNS_GROUP), references)
    begun = time.perf_counter()
    tree = open_campaign(target)
    seconds = time.perf_counter() - begun
    assert len(tree.ds.data_vars) and sum(1 for node in tree.subtree if "time" in node.ds.dims) == runs
    tree.close()
    return seconds


def opening_only(repeat: int) -> int:
    """The opening mode (see the module docstring)."""
    from mbds.campaign.collect import collect
    from mbds.campaign.plan import expand

    with tempfile.TemporaryDirectory(prefix="mbds-campaign-opening-") as temp:
        job = make_campaign(Path(temp) / "opening")
        subprocess.run(LAUNCHES["pool, 2 workers"] + [str(job)], check=True, capture_output=True)
        collect(expand(job))
        seconds = [opening(job) for _ in range(repeat)]
    print(f"opening a campaign of 1000 runs, {repeat} times: " + ", ".join(f"{s:.2f}" for s in seconds)
          + f" s (min {min(seconds):.2f}, max {max(seconds):.2f}); load average {os.getloadavg()[0]:.2f}")
    return 0


def _megabytes(job: Path) -> str:
    """Size of the campaign file and the mean uncompressed size of a run's watch tables."""
    import netCDF4

    folder = job.parent / "campaign"
    with netCDF4.Dataset(folder / "v00" / "000" / "history.nc") as run:
        tables = sum(v.size * v.dtype.itemsize for v in run.variables.values() if v.dimensions == ("time", "watch"))
    return f"campaign.nc {(folder / 'campaign.nc').stat().st_size / 1e6:.1f} MB, watch tables {tables / 1e6:.1f} MB per run"


def identical(a, b) -> bool:
    """Whether two collected campaigns hold the same data (wall times aside)."""
    for node in a.subtree:
        for name, variable in node.ds.data_vars.items():
            if name != "wall" and not np.array_equal(variable.values, b[node.path].ds[name].values):
                return False
    return True


def scaling(chains: int, versions: int, counts: list[int]) -> int:
    """The scaling mode (see the module docstring)."""
    from scaling import replay

    from mbds.campaign.plan import expand

    cores = os.cpu_count() or 1
    with tempfile.TemporaryDirectory(prefix="mbds-campaign-scaling-") as temp:
        temp = Path(temp)
        env = dict(os.environ, MBDS_CACHE_DIR=str(temp / "cache"), **SINGLE_THREAD)
        job_text = scaling_job(chains, versions)
        cold, _ = cold_warm_up(make_campaign(temp / "warm-up", job_text=job_text), env)
        measured = {}
        for n in sorted({1, *counts}):
            if n == 1 or n + 1 <= cores:
                job = make_campaign(temp / f"n{n}", job_text=job_text)
                measured[n] = launch(f"MPI, {n} workers", job, env, mpi_launch(n))
        base = measured[1]
        plan = expand(job)
        startup = base["wall"] - base["loop"]
        print(f"campaign: {chains} chains x {versions} versions of wearballs (1.5 s each), {base['count']} tasks; "
              f"cold compile {cold:.1f} s; {cores} cores here; 1 worker: wall {base['wall']:.1f} s, "
              f"tasks {base['tasks']:.1f} s, start-up and shut-down {startup:.2f} s, round trip "
              f"{1e3 * base['sched']:.1f} ms")
        print(f"\n{'N':>3} {'how':>9} {'wall s':>8} {'efficiency':>10} {'start+end s':>11} {'idle s':>7} "
              f"{'round trips s':>13} {'first task s':>12} {'plan order: wall s':>19} {'efficiency':>10}")
        for n in counts:
            extra = max(base["first_task_extra"], 0.0)
            ordered = replay(plan, base["walls"], n, base["sched"], longest_first=True, first_run_extra=extra)
            planned = replay(plan, base["walls"], n, base["sched"], longest_first=False, first_run_extra=extra)
            if n in measured:
                how, wall, first = "measured", measured[n]["wall"], measured[n]["first_task_extra"]
            else:
                how, wall, first = "replayed", startup + ordered.loop, extra
            print(f"{n:>3} {how:>9} {wall:>8.2f} {base['wall'] / (n * wall):>10.3f} {startup:>11.2f} "
                  f"{ordered.idle / n:>7.2f} {len(base['walls']) * base['sched'] / n:>13.2f} {first:>12.2f} "
                  f"{startup + planned.loop:>19.2f} {base['wall'] / (n * (startup + planned.loop)):>10.3f}")
    return 0


def main() -> int:
    import warnings

    from mbds.errors import ModelWarning

    warnings.simplefilter("ignore", ModelWarning)
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scaling", action="store_true", help="the scaling mode")
    parser.add_argument("--chains", type=int, default=48, help="chains of the scaling campaign (a multiple of 4)")
    parser.add_argument("--versions", type=int, default=5, help="versions per chain of the scaling campaign")
    parser.add_argument("--workers", default="1,2,4,8,15", help="worker counts of the scaling mode")
    parser.add_argument("--opening", action="store_true", help="only the opening figure")
    parser.add_argument("--repeat", type=int, default=5, help="openings timed in the opening mode")
    args = parser.parse_args()
    write_bytecode()
    if args.opening:
        return opening_only(args.repeat)
    if args.scaling:
        return scaling(args.chains, args.versions, [int(n) for n in args.workers.split(",")])
    with tempfile.TemporaryDirectory(prefix="mbds-campaign-bench-") as temp:
        temp = Path(temp)
        env = dict(os.environ, MBDS_CACHE_DIR=str(temp / "cache"), **SINGLE_THREAD)
        os.environ["MBDS_CACHE_DIR"] = env["MBDS_CACHE_DIR"]
        cold, structures = cold_warm_up(make_campaign(temp / "warm-up"), env)
        print(f"campaign: 8 chains x 10 versions of wearballs (1.5 s each), 80 runs + 80 wear steps; "
              f"cold compile {cold:.1f} s ({structures} model structure), once, before the launches")
        figures, jobs = {}, {}
        print(f"\n{'launch':<16} {'round':>5} {'ranks':>6} {'wall s':>7} {'loop s':>7} {'tasks s':>8} "
              f"{'sched ms':>9} {'idle ms':>8} {'compiled':>9}")
        for round_, name in [(r, n) for r in range(1, ROUNDS + 1) for n in LAUNCHES if r == 1 or n.startswith("MPI")]:
            job = make_campaign(temp / f"{name.replace(' ', '_').replace(',', '')}_{round_}")
            f = launch(name, job, env)
            ranks = ",".join(map(str, f["ranks"])) if name.startswith("MPI") else "-"
            print(f"{name:<16} {round_:>5} {ranks:>6} {f['wall']:>7.2f} {f['loop']:>7.2f} {f['tasks']:>8.2f} "
                  f"{1e3 * f['sched']:>9.1f} {1e3 * f['idle']:>8.1f} {f['compiled']:>9d}"
                  + ("" if f["all_done"] else "  (not all tasks done)"))
            if name not in figures or f["wall"] < figures[name]["wall"]:
                figures[name], jobs[name] = f, job
        one, two, pool = (figures[name] for name in LAUNCHES)
        print(f"\nbest of {ROUNDS} rounds (alternating 1 and 2 workers):")
        print(f"speed-up, 2 workers over 1 (MPI): whole command {one['wall'] / two['wall']:.3f}, "
              f"loop {one['loop'] / two['loop']:.3f}")
        print(f"parallel efficiency (MPI, 3 processes: 1 scheduling + 2 workers on 2 cores): "
              f"whole command {one['wall'] / (2 * two['wall']):.3f}, loop {one['loop'] / (2 * two['loop']):.3f}")
        print(f"  = workers busy {two['tasks'] / (2 * two['loop']):.3f} of the 2-worker loop "
              f"x tasks' speed with 2 at once {one['tasks'] / two['tasks']:.3f} of alone "
              f"x 1 worker's loop over its tasks {one['loop'] / one['tasks']:.3f}")
        print(f"pool of 2 against MPI 1 worker: whole command {one['wall'] / (2 * pool['wall']):.3f}, "
              f"loop {one['loop'] / (2 * pool['loop']):.3f}")
        load, sim, wall = run_task_split(jobs["MPI, 1 worker"], one["run_walls"])
        print(f"\nrun task (v00's versions, mean): {wall:.3f} s = start-up {load:.3f} s (read, assemble, load "
              f"compiled code) + simulation {sim:.3f} s + writing and the rest {wall - load - sim:.3f} s; "
              f"overhead {(wall - sim) / wall:.1%}")
        seconds, tree = collected(jobs["MPI, 2 workers"])
        runs = len(two["run_walls"])
        print(f"collection, history every 1 ms: {seconds:.2f} s for {two['tasks']:.1f} s of compute "
              f"({seconds / two['tasks']:.2%}; {1e3 * seconds / runs:.0f} ms per run), "
              f"{_megabytes(jobs['MPI, 2 workers'])}")
        coarse = make_campaign(temp / "coarse", COARSE)
        sampled = launch("MPI, 2 workers", coarse, env)
        seconds_coarse, _ = collected(coarse)
        print(f"collection, history every 10 ms: {seconds_coarse:.2f} s for {sampled['tasks']:.1f} s of compute "
              f"({seconds_coarse / sampled['tasks']:.2%}; {1e3 * seconds_coarse / runs:.0f} ms per run), "
              f"{_megabytes(coarse)}")
        print(f"opening a campaign of 1000 runs: {opening(jobs['MPI, 2 workers']):.2f} s")
        _, other = collected(jobs["MPI, 1 worker"])
        print(f"collected data of 1 and 2 workers bit-identical: {identical(tree, other)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
