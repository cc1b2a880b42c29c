"""``mbds versions``: listing, deleting and resampling the versions of a model."""

import shutil

import numpy as np
import xarray as xr

from mbds.data.resample import resample
from tests.plot.test_plot_cli import mbds


def test_versions_lists_deletes_after_asking_and_resamples(model_runs, tmp_path):
    model = tmp_path / "2mass"
    shutil.copytree(model_runs["2mass"], model)
    shutil.copytree(model / "000", model / "001")
    (model / "001" / "history.nc").unlink()
    code, out, _ = mbds("versions", model)
    assert code == 0 and "complete" in out and "not run" in out
    code, out, _ = mbds("versions", model, "--delete", "001")  # no answer: nothing deleted
    assert (model / "001").is_dir()
    code, out, _ = mbds("versions", model, "--delete", "001", "--yes")
    assert code == 0 and not (model / "001").exists() and (model / "000").is_dir()
    code, _, err = mbds("versions", model, "--delete", "003-005", "--yes")
    assert code == 2 and "no version 003, 004, 005" in err


def test_resampling_keeps_the_totals(model_runs, tmp_path):
    path = tmp_path / "history.nc"
    shutil.copy(model_runs["2mass"] / "000" / "history.nc", path)
    with xr.open_dataset(path) as before:
        before = before.load()
    count = resample(path, 0.005)
    with xr.open_dataset(path) as after, xr.open_dataset(path, group="final_state") as state:
        assert after.sizes["time"] == count == 11  # 0.05 s run: t = 0 and the end of each 5 ms
        np.testing.assert_allclose(np.diff(after["time"].values[1:]), 0.005, rtol=1e-6)
        for name in ("impulse_normal", "impulse_x", "work"):
            np.testing.assert_allclose(after[name].sum("time"), before[name].sum("time"), rtol=1e-12, atol=1e-15)
        assert after["lost_work"].values[-1] == before["lost_work"].values[-1]
        assert after.attrs["resampled_interval"] == 0.005 and state["q"].size == before.sizes["coordinate"]
