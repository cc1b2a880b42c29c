"""The double pendulum striking a wall, built only through mbds.build: its files are what the
script writes, its energy balances, and it runs as a wear job."""

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from mbds.cli.main import app
from mbds.data.history import read_point_losses
from mbds.io.folder import read_model_files
from tests.build.compare import CAMPAIGNS, load_script
from tests.physics.models import energy_residual, run_folder

FOLDER = CAMPAIGNS / "double_pendulum"
SCRIPT = load_script(FOLDER / "build_double_pendulum.py")

SMOOTH_TOLERANCE = 1e-9
"""Largest |E(0) - E(t) - lost(t)| before the first impact, relative to max |E|; measured 1e-10."""
BALANCE_TOLERANCE = 1e-6
"""The same over the whole run, impacts included; measured 3.5e-7. The step after an impact
starts from accelerations that use h(q, u) with the velocities before the impact; h has the
centripetal terms θ̇² here, and the balance is off by an amount proportional to the time step
(4e-6 at maximumTimestep = 1e-4, 3.5e-7 at 1e-5)."""


def test_the_model_files_are_what_the_script_writes(tmp_path):
    SCRIPT.build(tmp_path)
    written = sorted(p.name for p in tmp_path.iterdir())
    assert written == sorted(p.name for p in FOLDER.iterdir() if p.suffix not in (".py", ".job") and p.is_file())
    for name in written:
        assert (tmp_path / name).read_text() == (FOLDER / name).read_text(), name


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("double_pendulum")
    shutil.copytree(FOLDER, folder, dirs_exist_ok=True, ignore=shutil.ignore_patterns("[0-9][0-9][0-9]", "campaign"))
    return run_folder(folder)


@pytest.mark.physics
def test_energy_balance_closes(run):
    assert run.time[-1] == pytest.approx(1.0)
    scale = np.abs(run.energy).max()
    residual = np.abs(energy_residual(run))
    first_loss = np.flatnonzero(run.lost > 0)[0]
    print(f"balance: smooth {residual[:first_loss].max() / scale:.2e}, whole run {residual.max() / scale:.2e}")
    assert residual[:first_loss].max() < SMOOTH_TOLERANCE * scale
    assert residual.max() < BALANCE_TOLERANCE * scale


@pytest.mark.physics
def test_the_bob_strikes_the_wall(run):
    """The bob's centre (l1 cos θ1 + l2 cos θ2) comes within a sample's travel (1 ms at about
    1.5 m/s) of touching the wall, never beyond the 48-gon's inner radius r cos(π/48) plus the
    allowed penetration, and the impact loses energy."""
    x = SCRIPT.L1 * np.cos(run.q[:, 0]) + SCRIPT.L2 * np.cos(run.q[:, 1])
    assert SCRIPT.WALL_X - SCRIPT.RADIUS - 2e-3 < x.max() < SCRIPT.WALL_X - SCRIPT.RADIUS * np.cos(np.pi / 48) + 1e-6
    assert run.lost[-1] > 0.01  # J; measured 0.0574


def test_it_runs_as_a_wear_job(tmp_path):
    """Two versions of the job, 0.4 s each (the first impact is at 0.344 s): version 001's bob
    is worn inward by maxChange = 0.1 mm where 000 lost the most energy."""
    folder = tmp_path / "double_pendulum"
    shutil.copytree(FOLDER, folder, ignore=shutil.ignore_patterns("[0-9][0-9][0-9]", "campaign", "*.py"))
    world = folder / "double_pendulum.wld"
    world.write_text(re.sub(r"breakTime = .*", "breakTime = 0.4", world.read_text()))
    job = folder / "double_pendulum.job"
    job.write_text(job.read_text().replace("jobs = 000-002", "jobs = 000-001"))
    result = CliRunner().invoke(app, ["job", str(job)])
    assert result.exit_code == 0, result.stdout + result.stderr
    loss = read_point_losses(folder / "000" / "history.nc")["bob"]
    old, new = (_bob(folder / v) for v in ("000", "001"))
    moved = np.linalg.norm(new[:-1] - old[:-1], axis=1)
    assert loss.max() > 0
    assert moved[loss.argmax()] == pytest.approx(1e-4, rel=1e-9)
    assert np.linalg.norm(new[loss.argmax()]) < np.linalg.norm(old[loss.argmax()])  # inward
    assert (folder / "002").is_dir()


def _bob(version: Path) -> np.ndarray:
    files = read_model_files(version)
    return next(s.points for b, s in zip(files.bodies, files.shapes) if b.main.name == "bob")
