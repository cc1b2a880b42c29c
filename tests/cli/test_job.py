"""`mbds job` and `mbds next`: resuming short and stopped runs, time limits, Ctrl-C, bad input."""

from pathlib import Path

import pytest
from typer.testing import CliRunner

from mbds.cli.main import app
from mbds.data.history import read_attributes
from tests.cli.test_run import ctrl_c
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]


def mbds(*args):
    """Exit code, output and error output (runs of white space as one space: lines wrap)."""
    result = CliRunner().invoke(app, list(map(str, args)))
    return result.exit_code, " ".join(result.stdout.split()), " ".join(result.stderr.split())


def two_mass(tmp_path, job: str) -> Path:
    """A copy of campaigns/2mass (breakTime 0.5 s) with ``job`` as its job file."""
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    (folder / "2mass.job").write_text(job)
    return folder / "2mass.job"


def test_short_run_is_run_in_full(tmp_path):
    job = two_mass(tmp_path, "[main]\njobs = 000\n")
    assert mbds("run", job.parent, "--break-time", 0.05)[0] == 0  # "run the first version for a few moments"
    code, out, err = mbds("job", job)
    assert code == 0, err
    assert "its run lasted 0.05 s, not the world file's breakTime of 0.5 s" in out
    attrs = read_attributes(job.parent / "000" / "history.nc")
    assert attrs["complete"] == 1 and attrs["break_time"] == 0.5
    assert not (job.parent / "001").exists()  # createNextVersionAtEnd = 0


def test_max_minutes_for_job_stops_the_version_and_the_job(tmp_path):
    job = two_mass(tmp_path, "[main]\njobs = 000-001\ncreateNextVersionAtEnd = 1\nmaxMinutesForJob = 0\n")
    code, out, err = mbds("job", job)
    assert code == 1, err
    assert "job stopped" in out and "maxMinutesForJob = 0 min exceeded" in out
    attrs = read_attributes(job.parent / "000" / "history.nc")
    assert attrs["complete"] == 0 and attrs["stop_reason"] == "maxMinutesForJob = 0 min exceeded"
    assert "maxMinutesForJob = 0 min exceeded" in (job.parent / "000" / "log.txt").read_text().splitlines()[-1]
    assert not (job.parent / "001").exists()
    job.write_text("[main]\njobs = 000-001\ncreateNextVersionAtEnd = 1\n")  # the limit lifted: resumed
    code, out, err = mbds("job", job)
    assert code == 0, err
    assert "its run stopped at t = " in out
    assert read_attributes(job.parent / "001" / "history.nc")["complete"] == 1


def test_max_minutes_for_jobs_reached_runs_nothing(tmp_path):
    job = two_mass(tmp_path, "[main]\njobs = 000\nmaxMinutesForJobs = 0\n")
    code, out, err = mbds("job", job)
    assert code == 1, err
    assert "maxMinutesForJobs = 0 min reached" in out
    assert not (job.parent / "000" / "history.nc").exists()


@pytest.mark.parametrize(
    ("jobs", "create", "missing"),
    [("000,002", 1, "002"), ("000-001", 0, "001"), ("003-004", 1, "003")],
)
def test_missing_versions_are_refused_before_anything_runs(tmp_path, jobs, create, missing):
    job = two_mass(tmp_path, f"[main]\njobs = {jobs}\ncreateNextVersionAtEnd = {create}\n")
    code, out, err = mbds("job", job)
    assert code == 2
    assert f"error: {job}:2: version {missing} does not exist" in err and "Traceback" not in err
    assert sorted(p.name for p in job.parent.iterdir() if p.is_dir()) == []


def test_bad_job_files_name_file_and_line(tmp_path):
    job = two_mass(tmp_path, "[main]\nworldFile = other.wld\njobs = 000\n")
    code, out, err = mbds("job", job)
    assert code == 2 and f"error: {job}:2: world file other.wld not found" in err
    job.write_text("[main]\njobs = 002-001\n")
    code, out, err = mbds("job", job)
    assert code == 2 and f"error: {job}:2: range '002-001' runs backwards" in err
    code, out, err = mbds("job", job.parent / "2mass.wld")
    assert code == 2 and "expected a .job file" in err


def test_next_refuses_a_version_without_a_complete_run(tmp_path):
    folder = two_mass(tmp_path, "[main]\njobs = 000\n").parent
    code, out, err = mbds("next", folder / "000")
    assert code == 2 and "no such version folder" in err
    assert mbds("run", folder, "--break-time", 0.05)[0] == 0
    (folder / "000" / "history.nc").rename(folder / "000" / "kept.nc")
    code, out, err = mbds("next", folder / "000")
    assert code == 2 and f"error: {folder / '000' / 'history.nc'}: not run yet" in err
    (folder / "000" / "kept.nc").rename(folder / "000" / "history.nc")
    code, out, err = mbds("next", folder / "000")
    assert code == 2 and "its run lasted 0.05 s" in err and "Traceback" not in err
    assert not (folder / "001").exists()
    code, out, err = mbds("next", folder)
    assert code == 2 and "not a version folder" in err


def test_next_after_a_full_run_and_not_twice(tmp_path):
    folder = two_mass(tmp_path, "[main]\njobs = 000\n").parent
    assert mbds("run", folder)[0] == 0
    code, out, err = mbds("next", folder / "000")
    assert code == 0, err
    assert (folder / "001" / "wear.nc").is_file() and not (folder / "001" / "history.nc").exists()
    code, out, err = mbds("next", folder / "000")
    assert code == 2 and "version 001 exists already" in err


def test_ctrl_c_stops_the_version_and_the_job(tmp_path):
    folder = tmp_path / "woodpecker"
    copy_example("woodpecker", folder)
    world = folder / "woodpecker.wld"
    text = world.read_text()
    world.write_text(text.replace(next(x for x in text.splitlines() if x.startswith("breakTime")), "breakTime = 1000"))
    (folder / "woodpecker.job").write_text("[main]\njobs = 000-001\ncreateNextVersionAtEnd = 1\n")
    code, out, err, _ = ctrl_c("job", folder / "woodpecker.job", wait=0.0)
    assert code == 130, err
    assert "job stopped" in out
    attrs = read_attributes(folder / "000" / "history.nc")
    assert attrs["complete"] == 0 and attrs["stop_reason"] == "interrupted"
    assert not (folder / "001").exists()
