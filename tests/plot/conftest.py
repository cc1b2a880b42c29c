"""Short runs of the example models and a small collected campaign, shared by the plot tests."""

import matplotlib
import pytest

from mbds.simulation.version_run import RunOptions, run_version
from mbds.simulation.versions import ensure_version
from tests.campaign.models import campaign, two_mass
from tests.examples import copy_example

matplotlib.use("Agg")

BREAK = {"woodpecker": 0.03, "wearballs": 0.02, "2mass": 0.05}
GRID = "contact.mass1-mass2.friction = 0.1, 0.3\nworld.breakTime = 0.2\nfolder = campaign\n"


@pytest.fixture(scope="session")
def model_runs(tmp_path_factory):
    """Model folders of the three examples, each with a run of version 000."""
    root = tmp_path_factory.mktemp("runs")
    folders = {}
    for name, duration in BREAK.items():
        folder = copy_example(name, root / name)
        run_version(ensure_version(folder, 0), RunOptions(duration=duration))
        folders[name] = folder
    return folders


@pytest.fixture(scope="session")
def campaign_job(tmp_path_factory):
    """A collected 2mass campaign: two frictions, versions 000-001 (worn in between)."""
    job = two_mass(tmp_path_factory.mktemp("campaign"), GRID, jobs="000-001")
    for command in ("run", "collect"):
        code, out, err = campaign(command, job)
        assert code == 0, out + err
    return job
