"""The wearballs job: versions run one after the other, each worn by the losses of the one
before; a killed job resumes without touching finished versions; a finished one does nothing."""

import hashlib
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from mbds.cli.main import app
from mbds.data.history import read_attributes, read_point_losses
from mbds.io.folder import read_model_files
from mbds.io.lock import LOCK_FILE
from mbds.model.geometry import polygon_properties
from mbds.wear.version import WEAR_FILE
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]
BALLS = [f"ball{k}" for k in range(1, 6)]
MAX_CHANGE = 0.002  # m, campaigns/wearballs/wearballs.wtc
BREAK_TIME = 0.3  # s, shortened from 1.5 s to keep the tests fast


def mbds(*args):
    """Exit code, output and error output (runs of white space as one space: lines wrap)."""
    result = CliRunner().invoke(app, list(map(str, args)))
    return result.exit_code, " ".join(result.stdout.split()), " ".join(result.stderr.split())


def wearballs(folder: Path, jobs: str) -> Path:
    """A copy of campaigns/wearballs with a shorter breakTime and a job file for ``jobs``."""
    copy_example("wearballs", folder)
    world = folder / "wearballs.wld"
    world.write_text(world.read_text().replace("breakTime = 1.5", f"breakTime = {BREAK_TIME}"))
    (folder / "wearballs.job").write_text(f"[main]\njobs = {jobs}\ncreateNextVersionAtEnd = 1\n")
    return folder / "wearballs.job"


def hashes(folder: Path) -> dict[str, str]:
    """Digests of the files below ``folder``, lock files (held while a command works) and their
    temporary files (left by a process killed while taking a lock) left out."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and not p.name.startswith(LOCK_FILE)}


def shape(version: Path, body: str) -> np.ndarray:
    files = read_model_files(version)
    return next(s.points for b, s in zip(files.bodies, files.shapes) if b.main.name == body)


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """The model folder after ``mbds job`` ran versions 000-003, and the job's output."""
    job = wearballs(tmp_path_factory.mktemp("job") / "wearballs", "000-003")
    code, out, err = mbds("job", job)
    assert code == 0, err
    return job.parent, out


def test_job_runs_each_version_and_creates_its_successor(finished):
    folder, out = finished
    assert sorted(p.name for p in folder.iterdir() if p.is_dir()) == ["000", "001", "002", "003", "004"]
    assert out.count("running ") == 4 and out.count("created ") == 4 and "job finished" in out
    for number in range(4):
        attrs = read_attributes(folder / f"{number:03d}" / "history.nc")
        assert attrs["complete"] == 1 and attrs["break_time"] == BREAK_TIME and attrs["version"] == number
    assert not (folder / "004" / "history.nc").exists()
    for number in range(1, 5):
        with xr.open_dataset(folder / f"{number:03d}" / WEAR_FILE) as wear:
            assert wear.attrs["source_version"] == f"{number - 1:03d}"
            assert wear.attrs["reshaped_bodies"].split(",") == BALLS


@pytest.mark.parametrize("number", range(4))
def test_each_version_wears_by_the_losses_of_the_one_before(finished, number):
    folder, _ = finished
    old_version, new_version = folder / f"{number:03d}", folder / f"{number + 1:03d}"
    losses = read_point_losses(old_version / "history.nc")
    with xr.open_dataset(new_version / WEAR_FILE) as wear:
        for ball in BALLS:
            loss = losses[ball]
            assert loss.max() > 0  # every ball touches something in each run
            old, new = shape(old_version, ball), shape(new_version, ball)
            moved = new[:-1] - old[:-1]
            distance = np.linalg.norm(moved, axis=1)
            top = loss.argmax()
            assert distance[top] == pytest.approx(MAX_CHANGE, rel=1e-12)  # the top point moves by maxChange
            assert distance.max() <= MAX_CHANGE * (1 + 1e-12)
            assert np.all(moved[loss == 0] == 0.0) and np.any(loss == 0)  # points that lost nothing stay
            np.testing.assert_allclose(distance, MAX_CHANGE * loss / loss.max(), rtol=1e-12, atol=1e-18)
            # along the inward normal E (r[i+1] - r[i-1]) of the old shape, E the rotation by +90 degrees
            tangent = np.roll(old[:-1], -1, axis=0) - np.roll(old[:-1], 1, axis=0)
            inward = np.column_stack([-tangent[:, 1], tangent[:, 0]]) / np.linalg.norm(tangent, axis=1)[:, None]
            np.testing.assert_allclose(moved, distance[:, None] * inward, atol=1e-15)
            assert np.array_equal(new[-1], new[0])
            # wear.nc records the losses of the run and both shapes
            assert np.array_equal(wear[f"{ball}_loss"].values, loss)
            np.testing.assert_array_equal(wear[f"{ball}_old_x"].values, old[:-1, 0])
            np.testing.assert_array_equal(wear[f"{ball}_new_y"].values, new[:-1, 1])
            np.testing.assert_allclose(wear[f"{ball}_displacement"].values, distance, rtol=1e-12, atol=1e-18)
            # directionInside = 1: the ball loses area
            assert polygon_properties(new).area < polygon_properties(old).area
    for body in ("ground", "wall"):  # not watched: unchanged
        assert np.array_equal(shape(old_version, body), shape(new_version, body))


def test_next_makes_the_same_version_as_the_job(finished, tmp_path):
    folder, _ = finished
    shutil.copytree(folder / "000", tmp_path / "wearballs" / "000")
    code, out, err = mbds("next", tmp_path / "wearballs" / "000")
    assert code == 0, err
    created = tmp_path / "wearballs" / "001"
    assert str(created) in out
    for ball in BALLS:
        assert (created / f"{ball}.exs").read_bytes() == (folder / "001" / f"{ball}.exs").read_bytes()


def test_finished_job_does_nothing_again(finished):
    folder, _ = finished
    before = hashes(folder)
    code, out, err = mbds("job", folder / "wearballs.job")
    assert code == 0, err
    assert "nothing to do" in out and "running" not in out
    assert hashes(folder) == before


def test_killed_job_resumes_leaving_finished_versions_as_they_are(tmp_path):
    job = wearballs(tmp_path / "wearballs", "000-002")
    folder = job.parent
    exe = Path(sys.executable).with_name("mbds")
    child = subprocess.Popen([str(exe), "job", str(job)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=os.environ.copy())
    try:
        deadline = time.monotonic() + 300
        while not (folder / "001" / "wearballs.wld").exists():  # 000 has run, 001 exists and starts
            assert child.poll() is None and time.monotonic() < deadline, child.stderr.read() if child.stderr else ""
            time.sleep(0.005)
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=60)
    finally:
        child.kill()
        child.stderr.close()
    assert read_attributes(folder / "000" / "history.nc")["complete"] == 1
    assert not (folder / "001" / "history.nc").exists()  # killed while running 001
    assert (folder / LOCK_FILE).exists()  # left by the killed job: stale, taken over on resume
    assert not (folder / "002").exists()
    finished_before = hashes(folder / "000")
    created_before = hashes(folder / "001")
    code, out, err = mbds("job", job)
    assert code == 0, err
    assert "000: complete, not run again" in out.replace(str(folder) + os.sep, "")
    assert f"running {folder / '001'} (not run yet)" in out
    assert hashes(folder / "000") == finished_before
    assert {k: v for k, v in hashes(folder / "001").items() if k in created_before} == created_before
    for number in (1, 2):
        assert read_attributes(folder / f"{number:03d}" / "history.nc")["complete"] == 1
    assert (folder / "003" / WEAR_FILE).is_file()
    assert not (folder / LOCK_FILE).exists() and not (folder / "001" / LOCK_FILE).exists()
