"""`mbds run`: the examples reach their break time, --from continues, Ctrl-C and bad input."""

import os
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
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]


def mbds(*args):
    result = CliRunner().invoke(app, list(map(str, args)))
    return result.exit_code, result.stdout, result.stderr


def example(tmp_path, name):
    folder = tmp_path / name
    copy_example(name, folder)
    return folder


def attributes(path):
    with xr.open_dataset(path) as ds:
        return dict(ds.attrs)


@pytest.mark.parametrize(("name", "length"), [("2mass", 0.05), ("wearballs", 0.05), ("woodpecker", 0.01)])
def test_examples_reach_break_time(tmp_path, name, length):
    folder = example(tmp_path, name)
    code, out, err = mbds("run", folder, "--break-time", length)
    assert code == 0, err
    assert "break time reached" in out and "energy balance residual" in out
    attrs = attributes(folder / "000" / "history.nc")
    assert attrs["complete"] == 1 and attrs["end_time"] == pytest.approx(length)
    assert (folder / "000" / "log.txt").read_text().splitlines()[-1].startswith("[Alert] Break time of")
    if name == "wearballs":  # every ball point is watched: the watches add up to the points' losses
        with xr.open_dataset(folder / "000" / "history.nc") as ds:
            for body in range(5):
                name_ = str(ds["body"].values[body])
                watched = [w for w in ds["watch"].values if w.startswith(f"{name_}#")]
                points = ds["point_lost_work"].where(ds["point_body"] == body).sum()
                assert ds["work"].sel(watch=watched).sum() == pytest.approx(float(points), rel=1e-9, abs=1e-15)


def test_full_run_of_2mass_writes_the_manual_files(tmp_path):
    folder = example(tmp_path, "2mass")
    code, out, err = mbds("run", folder)
    assert code == 0, err
    version = folder / "000"
    log = (version / "log.txt").read_text().splitlines()
    assert log[0].split()[:5] == ["time", "mechanicalEnergy", "b'mass1'x", "b'mass1'x'", 'b\'mass1\'x"']
    assert log[1] == "" and float(log[2]) == 0 and float(log[3]) == pytest.approx(0.5)
    assert log[4].split() == ["time"] + [f"mass1#{p}-{c}" for p in range(3) for c in ("impN", "impT", "work")]
    assert log[5] == "***********" and log[6] == "[Alert] Break time of 0.5 s reached."
    data = np.loadtxt(version / "data.txt")
    watches = np.loadtxt(version / "watches.txt")
    assert data.shape == (1001, 2 + 3 * 3) and watches.shape == (1001, 1 + 3 * 3)
    with xr.open_dataset(version / "history.nc") as ds:
        np.testing.assert_allclose(data[:, 1], ds["mechanical_energy"], rtol=1e-9)
        np.testing.assert_allclose(data[:, 5], ds["q"].sel(coordinate="b'mass1'y"), rtol=1e-9, atol=1e-12)
        assert ds.attrs["impacts"] > 0 and ds["lost_work"].values[-1] > 0.1


def test_from_continues_in_the_next_version(tmp_path):
    folder = example(tmp_path, "2mass")
    assert mbds("run", folder, "--break-time", 0.1)[0] == 0
    code, out, err = mbds("run", folder, "--from", "000", "--break-time", 0.1)
    assert code == 0, err
    assert "001" in out
    first, second = attributes(folder / "000" / "history.nc"), attributes(folder / "001" / "history.nc")
    assert second["start_time"] == first["end_time"] and second["end_time"] == pytest.approx(0.2)
    assert second["continued_from"] == 0 and second["version"] == 1


def test_bad_input_names_file_and_line_and_writes_nothing(tmp_path):
    folder = example(tmp_path, "2mass")
    path = folder / "mass1.bdy"
    path.write_text(path.read_text().replace("density = 2500", "density = 25OO"))
    code, out, err = mbds("run", folder)
    assert code == 2
    assert f"{path}:" in err and "'25OO' is not a number" in err and "Traceback" not in err
    assert not (folder / "000").exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [(["--from", "3"], "no version 003"), (["--break-time", "-1"], "--break-time")],
)
def test_bad_options_exit_2(tmp_path, args, message):
    folder = example(tmp_path, "2mass")
    code, out, err = mbds("run", folder, *args)
    assert code == 2 and message in err


def ctrl_c(*args, wait=1.0, sent=signal.SIGINT):
    """Run ``mbds ARGS`` in a subprocess, press Ctrl-C (or send ``sent``) ``wait`` s after its
    first line ("running ..."); its exit code, output and error output, and the seconds from
    the signal to its end."""
    exe = Path(sys.executable).with_name("mbds")
    child = subprocess.Popen(
        [str(exe), *map(str, args)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=os.environ.copy(),
    )
    try:
        assert child.stdout.readline().startswith("running")
        time.sleep(wait)
        child.send_signal(sent)
        signalled = time.monotonic()
        out, err = child.communicate(timeout=120)
        took = time.monotonic() - signalled
    finally:
        child.kill()
    return child.returncode, out, err, took


def test_ctrl_c_keeps_the_results_marked_incomplete(tmp_path):
    folder = example(tmp_path, "woodpecker")
    code, out, err, _ = ctrl_c("run", folder, "--break-time", 1000)
    assert code == 130, err
    assert "incomplete" in out
    attrs = attributes(folder / "000" / "history.nc")
    assert attrs["complete"] == 0 and attrs["stop_reason"] == "interrupted" and 0 < attrs["end_time"] < 1000


def test_sigterm_stops_within_a_second_between_sparse_samples(tmp_path):
    """A sample every 100 s: the stepper still hands control back every few thousand steps, so
    SIGTERM stops the run within about a second and what it computed is written."""
    folder = example(tmp_path, "woodpecker")
    world = folder / "woodpecker.wld"
    world.write_text(world.read_text().replace("writeToHistoryMultipleOfMaximumTimestep = 1",
                                               "writeToHistoryMultipleOfMaximumTimestep = 10000000"))
    code, out, err, took = ctrl_c("run", folder, "--break-time", 1000, wait=4.0, sent=signal.SIGTERM)
    assert code == 130, err
    assert took < 3.0  # the signal is seen within a second; the rest is writing and exiting
    attrs = attributes(folder / "000" / "history.nc")
    assert attrs["complete"] == 0 and attrs["stop_reason"] == "interrupted" and 0 < attrs["end_time"] < 100
