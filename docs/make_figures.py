"""Make the figures of docs/results.md (and README's) from the example models.

    python docs/make_figures.py            # writes docs/figures/*.png (a few minutes)

Runs copies of campaigns/wearballs (its job: versions 000-013), campaigns/woodpecker (0.3 s),
campaigns/2mass (its job file's break time) and the 2mass campaign in a temporary folder, then
draws them with mbds.plot.
"""

from __future__ import annotations

import re
import shutil
import sys
import tempfile
from pathlib import Path

import matplotlib

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
    for path in sorted(FIGURES.glob("*.png")):
        print(f"wrote {path.relative_to(DOCS.parent)}")


if __name__ == "__main__":
    main()
