"""How fast the pictures come: issue 14's two figures.

1. Animating the 1 s woodpecker run (campaigns/woodpecker, breakTime 1 s: 100 001 samples) at
   30 frames/s into a GIF: ``mbds animate`` timed as a command (interpreter start and imports in)
   and ``mbds.plot.animate`` + ``save`` timed in this process.
2. A campaign of 64 chains x 10 versions (a copy of campaigns/2mass varying ``c'gravity`` and the
   friction over 8 values each, breakTime 5 ms or ``--break-time``, versions 000-009, 640 runs), collected; then
   ``mbds-campaign plot`` (its summary, and the worn shapes of the bodies that lost work: none in
   runs this short) timed as a command, and opening the campaign, the summary and the worn shapes
   of mass1 (64 panels) timed in this process.

Run from the repository root: ``.venv/bin/python benchmarks/plot_speed.py``. The runs take a few
minutes on 2 cores; the figures are what is timed. Options: ``--campaign-only`` leaves out the
animation; ``--keep FOLDER`` makes the campaign in ``FOLDER`` and uses it again on the next call
(it is made again when ``FOLDER`` holds no collected campaign); ``--repeat N`` times the campaign's
figures N times; ``--break-time 0.1`` makes the campaign's runs 0.1 s long, so that both masses
lose work and wear and ``mbds-campaign plot`` draws their worn shapes too (with ``--keep``, the
campaign is made again when its job differs). The command is run as
``python -m mbds.cli.campaign plot``, the module behind the ``mbds-campaign`` script.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
CAMPAIGN = [sys.executable, "-m", "mbds.cli.campaign"]
GRID = ", ".join(f"{v:g}" for v in (8.0, 8.5, 9.0, 9.5, 9.81, 10.5, 11.0, 12.0))
FRICTION = ", ".join(f"{v:g}" for v in (0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5))
JOB = """[main]
worldFile = 2mass.wld
jobs = 000-009
createNextVersionAtEnd = 1
[campaign]
c'gravity = {grid}
contact.mass1-mass2.friction = {friction}
world.breakTime = {break_time:g}
folder = campaign
"""


def timed(*command) -> float:
    start = time.perf_counter()
    subprocess.run([str(c) for c in command], check=True, capture_output=True)
    return time.perf_counter() - start


def copy(name: str, into: Path) -> Path:
    return Path(shutil.copytree(ROOT / "campaigns" / name, into / name,
                                ignore=lambda _, names: [n for n in names if n == "campaign" or n[:3].isdigit()]))


def animation(work: Path) -> None:
    """The woodpecker animation's figures."""
    from mbds import plot

    woodpecker = copy("woodpecker", work)
    subprocess.run([BIN / "mbds", "run", woodpecker, "--break-time", "1"], check=True, capture_output=True)
    command = timed(BIN / "mbds", "animate", woodpecker, "-o", work / "run.gif", "--fps", "30")
    start = time.perf_counter()
    with plot.open_run(woodpecker) as run:
        plot.save(plot.animate(run, fps=30), work / "again.gif")
        samples = run.sizes["time"]
    print(f"woodpecker 1 s ({samples} samples) at 30 frames/s into a GIF: mbds animate {command:.2f} s, "
          f"animate + save in process {time.perf_counter() - start:.2f} s")


def campaign(work: Path, keep: Path | None, repeat: int, break_time: float) -> None:
    """The campaign's figures (runs of ``break_time`` s), ``repeat`` times."""
    from mbds import open_campaign, plot

    two_mass = keep / "2mass" if keep else work / "2mass"
    job = two_mass / "grid.job"
    text = JOB.format(grid=GRID, friction=FRICTION, break_time=break_time)
    if not (two_mass / "campaign" / "campaign.nc").is_file() or job.read_text() != text:
        shutil.rmtree(two_mass, ignore_errors=True)
        copy("2mass", two_mass.parent)
        job.write_text(text)
        subprocess.run([*CAMPAIGN, "run", job, "--workers", "2"], check=True, capture_output=True)
        subprocess.run([*CAMPAIGN, "collect", job], check=True, capture_output=True)
    size = (two_mass / "campaign" / "campaign.nc").stat().st_size / 2**20
    for _ in range(repeat):
        shutil.rmtree(work / "figures", ignore_errors=True)
        command = timed(*CAMPAIGN, "plot", job, "-o", work / "figures")
        figures = len(list((work / "figures").iterdir()))
        start = time.perf_counter()
        tree = open_campaign(two_mass / "campaign")
        opened = time.perf_counter() - start
        times = {}
        for name, draw in {"summary": lambda: plot.campaign_summary(tree),
                           "wear mass1": lambda: plot.wear(tree, "mass1")}.items():
            start = time.perf_counter()
            draw().savefig(work / f"{name}.png")
            times[name] = time.perf_counter() - start
        tree.close()
        shown = ", ".join(f"{k} {v:.2f} s" for k, v in times.items())
        print(f"campaign 64 chains x 10 versions ({size:.0f} MiB): mbds-campaign plot ({figures} figures) "
              f"{command:.2f} s; in process: open {opened:.2f} s, {shown}; load average {os.getloadavg()[0]:.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--campaign-only", action="store_true", help="leave out the animation")
    parser.add_argument("--keep", type=Path, help="make the campaign here, or use the one made here before")
    parser.add_argument("--repeat", type=int, default=1, help="time the campaign's figures this many times")
    parser.add_argument("--break-time", type=float, default=0.005,
                        help="the runs' breakTime in s (0.1: both masses lose work and wear)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        if not args.campaign_only:
            animation(work)
        campaign(work, args.keep.resolve() if args.keep else None, args.repeat, args.break_time)


if __name__ == "__main__":
    main()
