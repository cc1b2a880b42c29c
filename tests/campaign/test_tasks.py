"""Tasks performed in-process: the ensemble wear step uses the mean of the replicates' losses;
a chain run by its tasks is the chain `mbds job` runs; a run that stops early fails its task."""

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from mbds.campaign.ledger import DONE, FAILED
from mbds.campaign.plan import WEAR, Task, expand
from mbds.campaign.tasks import run_task
from mbds.cli.main import app
from mbds.data.history import read_attributes
from mbds.io.folder import read_model_files
from mbds.simulation.versions import create_model_copy
from mbds.wear.version import WEAR_FILE
from tests.campaign.models import two_mass
from tests.wear.test_reshape import SQUARE, write_model

WTC = "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 0.01\n"


def fake_history(folder, losses_a):
    """A complete run's history.nc with only what the wear step reads: losses of the 8 points
    of body a (J) and none on body b."""
    points = len(losses_a)
    ds = xr.Dataset(
        {"point_lost_work": ("point", np.concatenate([losses_a, np.zeros(points)]))},
        coords={
            "body": ("body", np.array(["a", "b"], dtype=object)),
            "point_body": ("point", np.repeat([0, 1], points).astype(np.int32)),
            "point_number": ("point", np.tile(np.arange(points), 2).astype(np.int32)),
        },
        attrs={"complete": 1, "start_time": 0.0, "end_time": 1.0, "break_time": 1.0, "stop_reason": ""},
    )
    ds.to_netcdf(folder / "history.nc")


def shape_of(folder, body):
    files = read_model_files(folder)
    return next(s.points for b, s in zip(files.bodies, files.shapes) if b.main.name == body)


def test_ensemble_wear_reshapes_by_the_mean_of_the_replicates_losses(tmp_path):
    version = tmp_path / "v00" / "000"
    files = write_model(version, WTC)
    first, second = np.array([0.0, 2, 4, 1, 0, 0, 0, 0]), np.array([0.0, 4, 0, 3, 0, 0, 0, 0])
    runs = []
    for k, losses in enumerate((first, second)):
        runs.append(create_model_copy(version / f"r{k}", files, 0))
        fake_history(runs[-1], losses)
    task = Task("v00/000/wear", WEAR, "v00", None, None, 0, version, 0, ("v00/000/r0/run", "v00/000/r1/run"),
                inputs=tuple(runs))
    result = run_task(task)
    assert result["state"] == DONE and result["output"] == str(tmp_path / "v00" / "001")
    mean = np.array([0.0, 3, 2, 2, 0, 0, 0, 0])  # by hand
    with xr.open_dataset(tmp_path / "v00" / "001" / WEAR_FILE) as record:
        np.testing.assert_array_equal(record["a_loss"].values, mean)
        np.testing.assert_allclose(record["a_displacement"].values, 0.01 * mean / 3)
    moved = np.linalg.norm(shape_of(tmp_path / "v00" / "001", "a")[:-1] - np.array(SQUARE, dtype=float), axis=1)
    assert moved.argmax() == 1 and moved.max() == pytest.approx(0.01)  # neither replicate alone has its top at 1
    again = run_task(task)
    assert again["state"] == DONE and again["note"] == "exists already, not replaced"


def test_ensemble_wear_refuses_an_incomplete_replicate(tmp_path):
    version = tmp_path / "v00" / "000"
    files = write_model(version, WTC)
    runs = [create_model_copy(version / f"r{k}", files, 0) for k in range(2)]
    fake_history(runs[0], np.ones(8))
    task = Task("v00/000/wear", WEAR, "v00", None, None, 0, version, 0, inputs=tuple(runs))
    result = run_task(task)
    assert result["state"] == FAILED and "r1/history.nc: not run yet" in result["reason"]
    assert not (tmp_path / "v00" / "001").exists()


def run_all(plan):
    """Every task of the plan in order, as a one-process executor would; their results."""
    return {task.id: run_task(task) for task in plan.tasks}


def test_chain_of_a_job_without_campaign_is_what_mbds_job_makes(tmp_path):
    job = two_mass(tmp_path / "tasks", None, jobs="000-001")
    results = run_all(expand(job))
    assert all(r["state"] == DONE for r in results.values()), results
    reference = two_mass(tmp_path / "job", None, jobs="000-001")
    assert CliRunner().invoke(app, ["job", str(reference)]).exit_code == 0
    for version in ("000", "001"):
        with xr.open_dataset(job.parent / version / "history.nc") as ours, \
                xr.open_dataset(reference.parent / version / "history.nc") as theirs:
            np.testing.assert_array_equal(ours["q"].values, theirs["q"].values)
            assert ours.attrs["seed"] == theirs.attrs["seed"] == 0
    assert (job.parent / "002").is_dir() and (reference.parent / "002").is_dir()
    assert run_all(expand(job))["2mass/000/run"]["note"] == "complete already, not run again"


def test_ensemble_replicates_run_in_their_own_folders_with_their_seeds(tmp_path):
    job = two_mass(tmp_path, "replicates = 2\nmode = ensemble\nseed = 3\n", jobs="000-001")
    plan = expand(job)
    results = run_all(plan)
    assert all(r["state"] == DONE for r in results.values()), results
    for task_id in ("v00/000/r0/run", "v00/000/r1/run", "v00/001/r1/run"):
        task = plan.task(task_id)
        attrs = read_attributes(task.folder / "history.nc")
        assert attrs["complete"] == 1 and attrs["seed"] == task.seed and attrs["version"] == task.version
    assert (job.parent / "campaign" / "v00" / "002" / WEAR_FILE).is_file()


def test_run_stopped_early_fails_its_task_with_the_reason(tmp_path):
    job = two_mass(tmp_path, None, jobs="000", create=0)
    job.write_text(job.read_text() + "maxMinutesForJob = 0\n")
    results = run_all(expand(job))
    assert results["2mass/000/run"]["state"] == FAILED
    assert "maxMinutesForJob = 0 min exceeded" in results["2mass/000/run"]["reason"]
