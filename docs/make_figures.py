"""Make the figures of docs/results.md (and README's) from the example models.

    python docs/make_figures.py            # writes docs/figures/*.png (a few minutes)

Runs copies of campaigns/wearballs (its job: versions 000-013), campaigns/woodpecker (0.3 s),
campaigns/2mass (its job file's break time), the 2mass campaign and the DAP_BC models
campaigns/dap_bc/SP and Cart_A in a temporary folder, then draws them with mbds.plot.
"""

from __future__ import annotations

import re
import shutil
import sys
import tempfile
from pathlib import Path

import matplotlib
from matplotlib.figure import Figure

matplotlib.use("Agg")

import mbds  # noqa: E402
from mbds import plot  # noqa: E402
from mbds.cli.campaign import app as campaign_app  # noqa: E402
from mbds.cli.main import app  # noqa: E402

DOCS = Path(__file__).resolve().parent
EXAMPLES = DOCS.parent / "campaigns"
FIGURES = DOCS / "figures"


def copy(name: str, into: Path) -> Path:
    """A copy of an example model's files (no runs)."""
    return Path(shutil.copytree(EXAMPLES / name, into / name,
                                ignore=lambda _, names: [n for n in names if re.fullmatch(r"\d{3}|campaign", n)]))


def command(application, *args) -> None:
    """Run an mbds command; stop when it fails."""
    try:
        application([str(a) for a in args], standalone_mode=False)
    except SystemExit as exc:
        if exc.code:
            sys.exit(f"{' '.join(map(str, args))} failed ({exc.code})")


def dap_bc_figure(work: Path) -> None:
    """SP (manual Example B.1, 4 s) at t = 1.3 s and Cart_A (2 s) at t = 1 s, as DAP_BC's anim draws them."""
    figure = Figure(figsize=(11, 3.6), layout="constrained")
    panels = figure.subplots(1, 2, width_ratios=[2.5, 3.2])
    for ax, name, final, step, time in zip(panels, ("SP", "Cart_A"), (4, 2), (0.02, 0.01), (1.3, 1.0)):
        folder = copy(f"dap_bc/{name}", work)
        command(app, "run", folder, "--final-time", final, "--report-step", step, "--correct-ic")
        with plot.open_run(folder) as run:
            plot.shapes(run, time=time, ax=ax)
    plot.save(figure, FIGURES / "dap_bc_shapes.png")


def main() -> None:
    FIGURES.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        wearballs = copy("wearballs", work)
        command(app, "job", wearballs / "wearballs.job")  # versions 000-013, as the manual's Figure 2.10
        plot.save(plot.wear(wearballs, "ball3"), FIGURES / "wearballs_worn.png")
        with plot.open_run(wearballs / "013") as run:
            plot.save(plot.shapes(run, time=0.5), FIGURES / "wearballs_shapes.png")
            plot.save(plot.lost_work_outline(run, "ball3"), FIGURES / "wearballs_outline.png")

        woodpecker = copy("woodpecker", work)
        command(app, "run", woodpecker, "--break-time", 0.3)
        with plot.open_run(woodpecker) as run:
            plot.save(plot.shapes(run, time=0.15), FIGURES / "woodpecker_shapes.png")
            plot.save(plot.coordinates(run), FIGURES / "woodpecker_coordinates.png")
            plot.save(plot.watches(run), FIGURES / "woodpecker_watches.png")

        two_mass = copy("2mass", work)
        command(app, "run", two_mass)
        with plot.open_run(two_mass) as run:
            plot.save(plot.energy(run), FIGURES / "2mass_energy.png")
        job = two_mass / "2mass_campaign.job"
        command(campaign_app, "run", job)
        command(campaign_app, "collect", job)
        with mbds.open_campaign(two_mass / "campaign") as tree:
            plot.save(plot.campaign_summary(tree), FIGURES / "2mass_campaign_summary.png")
            plot.save(plot.wear(tree, "mass1"), FIGURES / "2mass_campaign_wear.png")
        dap_bc_figure(work)
    for path in sorted(FIGURES.glob("*.png")):
        print(f"wrote {path.relative_to(DOCS.parent)}")


if __name__ == "__main__":
    main()
