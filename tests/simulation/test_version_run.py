"""Runs of a version folder: history.nc schema, interruption, determinism, exact continuation."""

import copy
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from mbds.data.history import CLOCK_ENTRIES, read_final_state
from mbds.kernel import layout as K
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import continue_from, simulate
from mbds.simulation.version_run import PROGRESS_CHUNK, RunOptions, run_version
from mbds.simulation.versions import ensure_version
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]


def model_copy(tmp_path, name="2mass", edits=()):
    """A copy of an example model folder; ``edits``: (file, old, new) text replacements."""
    folder = copy_example(name, tmp_path / name)
    for file, old, new in edits:
        text = (folder / file).read_text()
        assert old in text
        (folder / file).write_text(text.replace(old, new, 1))
    return folder


def run(folder, number=0, **options):
    return run_version(ensure_version(folder, number), RunOptions(**options))


def test_history_has_the_documented_variables_and_attributes(tmp_path):
    folder = model_copy(tmp_path)
    record = run(folder, duration=0.1)
    with xr.open_dataset(folder / "000" / "history.nc") as ds:
        assert list(ds["coordinate"].values) == ["b'mass1'x", "b'mass1'y", "b'mass1'Rz"]
        assert list(ds["coordinate_unit"].values) == ["m", "m", "rad"]
        assert list(ds["watch"].values) == ["mass1#0", "mass1#1", "mass1#2"]
        units = {
            "mechanical_energy": "J", "body_x": "m", "body_y": "m", "body_angle": "rad",
            "lost_work": "J", "driver_work": "J", "impulse_normal": "N s", "impulse_tangential": "N s",
            "impulse_x": "N s", "impulse_y": "N s", "work": "J", "shape_x": "m", "shape_y": "m",
            "point_lost_work": "J", "point_lost_work_smoothed": "J", "time": "s",
        }
        for name, unit in units.items():
            assert ds[name].attrs["units"] == unit, name
            assert ds[name].attrs["long_name"], name
        for name, units in {"q": "coordinate_unit", "qd": "velocity_unit", "qdd": "acceleration_unit"}.items():
            assert ds[name].attrs["ancillary_variables"] == units and "units" not in ds[name].attrs
        assert list(ds["velocity_unit"].values) == ["m s-1", "m s-1", "rad s-1"]
        # mass1's pose is its own coordinates; mass2 has none (fixed at its start pose)
        np.testing.assert_array_equal(ds["body_x"].sel(body="mass1").values, ds["q"].values[:, 0])
        np.testing.assert_array_equal(ds["body_angle"].sel(body="mass1").values, ds["q"].values[:, 2])
        assert list(ds["body_kind"].values) == ["moving", "fixed"]
        assert list(ds["point_body_name"].values) == ["mass1"] * 5 + ["mass2"] * 4
        assert ds["q"].dims == ("time", "coordinate") and ds["work"].dims == ("time", "watch")
        assert "angle" not in ds and "t_div_n" not in ds
        assert ds.sizes["point"] == 5 + 4  # distinct points of mass1 and mass2
        assert ds["time"].values[0] == 0.0 and ds["time"].values[-1] == pytest.approx(0.1)
        assert ds.attrs["complete"] == 1 and ds.attrs["end_time"] == pytest.approx(0.1)
        assert ds.attrs["model"] == "2mass" and ds.attrs["version"] == 0 and ds.attrs["seed"] == 0
        assert ds.attrs["mbds_version"] and ds.attrs["Conventions"].startswith("CF")
        assert "breakTime = 0.5" in ds.attrs["input_2mass.wld"]
        assert "contactWatch = 0-2" in ds.attrs["input_2mass.wtc"]
        assert ds.attrs["input_files"].split()[0] == "2mass.wld"
        direct = simulate(load_model(folder / "000", version=0), RunSettings(0.1))  # the samples, kept in memory
        np.testing.assert_array_equal(ds["time"].values, direct.time)
        np.testing.assert_array_equal(ds["q"].values, direct.q)
        np.testing.assert_array_equal(ds["lost_work"].values, direct.lost)
        assert record.samples == len(direct.time) and record.last_sample == direct.time[-1]
        # each contact's loss goes to the points of both bodies
        assert ds["point_lost_work"].sum() == pytest.approx(2 * ds.attrs["run_lost_work"])
        assert abs(ds.attrs["energy_residual"]) < 1e-9
    with xr.open_dataset(folder / "000" / "history.nc", group="final_state") as state:
        np.testing.assert_array_equal(state["clock"].values, record.final_state.clock)
        assert state["rng"].dtype == np.uint64
    assert len(CLOCK_ENTRIES.split()) == K.CLOCK


def test_interrupted_run_is_written_and_marked_incomplete(tmp_path):
    folder = model_copy(tmp_path)
    calls = []

    def progress(start, now, end, steps):
        calls.append(now)
        if len(calls) == 2:
            raise KeyboardInterrupt

    version = ensure_version(folder, 0)
    record = run_version(version, RunOptions(), progress)
    assert not record.complete and record.stopped == "interrupted"
    with xr.open_dataset(version / "history.nc") as ds:
        assert ds.attrs["complete"] == 0 and ds.attrs["stop_reason"] == "interrupted"
        assert ds.attrs["end_time"] == pytest.approx(calls[-1]) and calls[-1] < 0.5
        assert ds.sizes["time"] == 2 * PROGRESS_CHUNK
        partial = ds["q"].values
    log = (version / "log.txt").read_text().splitlines()
    assert log[-1].startswith("[Alert] Run stopped at") and "incomplete" in log[-1]
    other = model_copy(tmp_path / "b")
    run(other, duration=0.5)  # what was kept is the start of the full run
    with xr.open_dataset(other / "000" / "history.nc") as ds:
        np.testing.assert_array_equal(partial, ds["q"].values[: len(partial)])


def _data_variables(path):
    with xr.open_dataset(path) as ds:
        return {name: ds[name].values for name in ds.data_vars}


def test_same_seed_gives_bit_identical_history(tmp_path):
    randomized = [("2mass.job", "lexicoRandomizationRange = 0.0,0.0", "lexicoRandomizationRange = 1e-12,1e-8")]
    outputs = []
    for case, seed in (("a", 7), ("b", 7), ("c", 8)):
        folder = model_copy(tmp_path / case, edits=randomized)
        outputs.append((run(folder, duration=0.3, seed=seed), _data_variables(folder / "000" / "history.nc")))
    (ra, a), (rb, b), (rc, _) = outputs
    assert a.keys() == b.keys()
    for name in a:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)
    np.testing.assert_array_equal(ra.final_state.rng, rb.final_state.rng)
    assert not np.array_equal(ra.final_state.rng, rc.final_state.rng)


def test_from_starts_exactly_where_the_version_ended(tmp_path):
    folder = model_copy(tmp_path)
    first = run(folder, duration=0.2)
    ended = copy.deepcopy(first.final_state)
    stored, _ = read_final_state(folder / "000" / "history.nc")
    for name in ("clock", "q", "u", "rng", "point_loss", "point_interval"):
        np.testing.assert_array_equal(getattr(stored, name), getattr(ended, name), err_msg=name)
    version = ensure_version(folder, 1, folder / "000")
    second = run_version(version, RunOptions(duration=0.15, start_from=0))
    assert second.start_time == first.end_time and second.end_time == pytest.approx(0.35)
    assert second.first_sample == first.end_time  # its first sample is its start state
    # the same as continuing the in-memory state without going through the file
    model = load_model(version, version=1)
    continue_from(ended)
    reference = simulate(model, RunSettings(second.break_time, 0), ended, chunk=PROGRESS_CHUNK)
    np.testing.assert_array_equal(reference.state.clock, second.final_state.clock)
    with xr.open_dataset(version / "history.nc") as ds:
        np.testing.assert_array_equal(ds["q"].values[0], stored.q)
        np.testing.assert_array_equal(ds["q"].values, reference.q)
        assert ds.attrs["continued_from"] == 0 and ds.attrs["start_time"] == first.end_time
        # lost work counts from this run's start
        assert ds["lost_work"].values[-1] == pytest.approx(ds.attrs["run_lost_work"])


def test_log_overflow_stops_the_run(tmp_path):
    edits = [
        ("2mass.wld", "minimumTimestep = 1e-10", "minimumTimestep = 5e-4"),  # steps cannot shrink at impact
        ("2mass.job", "maxMinutesForJob = 5", "maxMinutesForJob = 5\nmaxLinesInLog = 7"),
    ]
    folder = model_copy(tmp_path, edits=edits)
    record = run(folder)
    assert not record.complete and "maxLinesInLog = 7" in record.stopped
    log = (folder / "000" / "log.txt").read_text().splitlines()
    assert len(log) == 8 and "exceeds maximumPenetration" in log[6]
    assert "maxLinesInLog" in log[7]
    assert record.end_time < 0.5


def test_watch_options_change_the_outputs(tmp_path):
    plain = model_copy(tmp_path / "plain")
    options = model_copy(
        tmp_path / "options",
        edits=[
            ("2mass.wtc", "[mass1]", "[common]\ncummulativeWork = 1\nconvertImpulseToForce = 1\n"
             "writeAveragedTDivN = 1\nsmoothWorkLeftRight = 1\n[mass1]"),
            ("2mass.wtc", "contactWatch = 0-2", "contactWatch = 0-2,[0:1]"),
        ],
    )
    run(plain, duration=0.2)
    run(options, duration=0.2)
    with xr.open_dataset(plain / "000" / "history.nc") as p, xr.open_dataset(options / "000" / "history.nc") as o:
        dt = np.diff(p["time"].values, prepend=0.0)[:, None]
        three = {"watch": ["mass1#0", "mass1#1", "mass1#2"]}
        np.testing.assert_allclose(o["work"].sel(three), np.cumsum(p["work"].values, axis=0))
        force = np.divide(p["impulse_normal"].values, dt, out=np.zeros_like(dt * p["impulse_normal"].values), where=dt > 0)
        np.testing.assert_allclose(o["impulse_normal"].sel(three), force)
        assert o["impulse_normal"].attrs["units"] == "N"
        combined = o["impulse_y"].sel(watch="mass1#[0:1]").values
        np.testing.assert_allclose(combined, o["impulse_y"].sel(watch=["mass1#0", "mass1#1"]).sum("watch"))
        assert "t_div_n" in o and "t_div_n" not in p
        assert not np.allclose(o["point_lost_work_smoothed"], o["point_lost_work"])
        np.testing.assert_array_equal(o["point_lost_work"], p["point_lost_work"])
    header = (options / "000" / "log.txt").read_text().splitlines()[4].split()
    assert header[1:5] == ["mass1#0-forceN", "mass1#0-forceT", "mass1#0-work", "mass1#0-TdivN"]
    assert header[-4:] == ["mass1#[0:1]-forceX", "mass1#[0:1]-forceY", "mass1#[0:1]-work", "mass1#[0:1]-TdivN"]


def test_killed_while_writing_leaves_the_previous_history(tmp_path):
    folder = model_copy(tmp_path)
    run(folder, duration=0.1)
    history = folder / "000" / "history.nc"
    before = history.read_bytes()
    marker = tmp_path / "writing"
    script = f"""
import time
from pathlib import Path
import mbds.data.history as H
from mbds.simulation.version_run import RunOptions, run_version

def stall(*args):
    Path({str(marker)!r}).touch()
    time.sleep(60)

H.state_variables = stall
run_version(Path({str(folder / '000')!r}), RunOptions(duration=0.2))
"""
    child = subprocess.Popen([sys.executable, "-c", script], env=os.environ.copy())
    try:
        deadline = time.monotonic() + 120
        while not marker.exists():
            assert child.poll() is None, "the run ended before writing"
            assert time.monotonic() < deadline
            time.sleep(0.05)
        child.send_signal(signal.SIGKILL)
        child.wait(30)
    finally:
        child.kill()
    assert history.read_bytes() == before
    with xr.open_dataset(history) as ds:
        assert ds.attrs["complete"] == 1 and ds.attrs["end_time"] == pytest.approx(0.1)
    assert list(history.parent.glob(".history.nc.*.tmp"))  # the half-written file was a temporary one
    run(folder, duration=0.1)  # the next run clears it away
    assert not list(history.parent.glob(".*.tmp"))


def test_max_lines_in_log_counts_the_fixed_lines(tmp_path):
    """A log of six fixed lines exceeds maxLinesInLog = 1 without any alert: the run stops."""
    edits = [("2mass.job", "maxMinutesForJob = 5", "maxMinutesForJob = 5\nmaxLinesInLog = 1")]
    folder = model_copy(tmp_path, edits=edits)
    record = run(folder)
    assert not record.complete and "maxLinesInLog = 1" in record.stopped
    assert record.end_time < 0.5  # the world's breakTime is 0.5 s


def test_a_job_keeps_a_continued_version_and_runs_it_again_from_where_it_continues(tmp_path):
    """`mbds run --from 000` made 001; a job listing 000-001 must neither replace 001's start by
    the model's start nor run a complete continuation again."""
    from mbds.simulation.job import run_job

    edits = [("2mass.job", "jobs = 000", "jobs = 000-001")]
    world = [("2mass.wld", "breakTime = 0.5", "breakTime = 0.1\nwriteToHistoryMultipleOfMaximumTimestep = 1")]
    folder = model_copy(tmp_path, edits=[*edits, *world])
    first = run(folder)
    run(folder, 1, duration=0.3, start_from=0)  # 600 samples: longer than one progress chunk
    before = (folder / "001" / "history.nc").stat().st_mtime_ns
    assert run_job(folder / "2mass.job").runs == []  # both complete
    assert (folder / "001" / "history.nc").stat().st_mtime_ns == before

    def interrupt(*args):
        raise KeyboardInterrupt

    run_version(folder / "001", RunOptions(duration=0.3, start_from=0), interrupt)  # now incomplete
    result = run_job(folder / "2mass.job")
    assert [number for number, *_ in result.runs] == [1]
    record = result.runs[0][1]
    assert record.complete and record.continued_from == 0
    assert record.start_time == first.end_time and record.end_time == pytest.approx(first.end_time + 0.3)


def test_job_minutes_may_be_fractional(tmp_path):
    from mbds.io.job import parse_job

    job = parse_job("[main]\njobs = 000\ndelayStartMinutes = 0.05\nmaxMinutesForJob = 2.5\n", tmp_path / "a.job")
    assert job.settings.delay_start_minutes == 0.05 and job.settings.max_minutes_for_job == 2.5
