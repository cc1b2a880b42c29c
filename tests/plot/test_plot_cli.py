"""``mbds plot``, ``mbds animate`` and ``mbds-campaign plot``: files written, bad input exits 2."""

import matplotlib.image
import pytest
from typer.testing import CliRunner

from mbds.cli.main import app
from tests.campaign.models import campaign, two_mass


def mbds(*args):
    result = CliRunner().invoke(app, list(map(str, args)))
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("kind", ["shapes", "watches", "wear", "energy", "coordinates", "outline"])
def test_plot_writes_the_figure(model_runs, tmp_path, kind):
    out = tmp_path / f"{kind}.png"
    code, stdout, stderr = mbds("plot", kind, model_runs["2mass"], "-o", out)
    assert code == 0, stderr
    assert f"wrote {out}" in stdout
    assert matplotlib.image.imread(out)[..., :3].std() > 0.01


def test_plot_writes_svg_and_pdf_beside_the_run(model_runs):
    for suffix in ("svg", "pdf"):
        code, _, stderr = mbds("plot", "shapes", model_runs["woodpecker"] / "000", "-o",
                               model_runs["woodpecker"] / f"bodies.{suffix}")
        assert code == 0, stderr
    code, stdout, _ = mbds("plot", "energy", model_runs["woodpecker"] / "000" / "history.nc")
    assert code == 0 and (model_runs["woodpecker"] / "000" / "energy.png").is_file()


@pytest.mark.parametrize("args, message", [
    (["plot", "bars"], "unknown figure 'bars'"),
    (["plot", "multipliers"], "no Lagrange multipliers"),
    (["plot", "shapes", "--time", "7"], "outside the run"),
    (["plot", "shapes", "-o", "x.txt"], "a figure is saved as png, svg, pdf"),
    (["animate", "-o", "x.avi"], "an animation is saved as mp4 or gif"),
])
def test_bad_requests_exit_2_with_a_message(model_runs, args, message):
    position = 2 if args[0] == "plot" else 1
    args = args[:position] + [model_runs["2mass"]] + args[position:]
    code, _, stderr = mbds(*args)
    assert code == 2 and message in stderr


def test_animate_writes_a_gif(model_runs, tmp_path):
    out = tmp_path / "run.gif"
    code, _, stderr = mbds("animate", model_runs["2mass"], "-o", out, "--fps", 5, "--speed", 0.05)
    assert code == 0, stderr
    assert out.stat().st_size > 0


def test_campaign_plot_writes_the_summary_and_the_worn_shapes(campaign_job, tmp_path):
    code, stdout, stderr = campaign("plot", campaign_job, "-o", tmp_path)
    assert code == 0, stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["summary.png", "wear_mass1.png", "wear_mass2.png"]


@pytest.mark.parametrize(("section", "message"), [
    ("c'gravity = 9, 10\nfolder = results\n", "results/campaign.nc: no campaign file; collect the campaign first"),
    ("c'gravity = 9, 10\nfolder = ../elsewhere\n", "folder '../elsewhere' is not inside the job file's folder"),
    (None, "campaign/campaign.nc: no campaign file"),
])
def test_campaign_plot_finds_the_campaign_folder_the_job_names(tmp_path, section, message):
    job = two_mass(tmp_path, section)
    code, _, stderr = campaign("plot", job)
    assert code == 2 and message in stderr
