"""Ensemble wear end to end: woodpecker replicates differ only in the seed of the
lexicographic-tolerance draws; the worn version is made from the mean of their per-point losses,
and the collected summary keeps each replicate's losses along ``replicate``.

The woodpecker's LCPs all have a unique solution: its contact-force LCPs are solved in closed
form (mbds.kernel.one_contact) and its impact LCPs are non-degenerate, so no draw decides a pivot
and its replicates come out bit-identical, which the summary reports. The mean itself, of
replicates that differ, is checked in tests/campaign/test_tasks.py."""

import json

import numpy as np
import xarray as xr

import mbds
from mbds.campaign.plan import expand
from mbds.wear.version import WEAR_FILE
from tests.campaign.models import campaign
from tests.examples import copy_example

JOB = """[main]
worldFile = woodpecker.wld
jobs = 000
lexicoRandomizationRange = 1e-10, 1e-6
createNextVersionAtEnd = 1
[campaign]
replicates = 3
mode = ensemble
seed = 3
world.breakTime = 0.5
"""


def test_ensemble_wear_uses_the_mean_of_the_replicates_runs(tmp_path):
    folder = copy_example("woodpecker", tmp_path / "woodpecker")
    wtc = folder / "woodpecker.wtc"
    wtc.write_text(wtc.read_text().replace("[bird]\ncontactWatch = 0\n",
                                           "[bird]\ncontactWatch = 0\ndirectionInside = 1\nmaxChange = 1e-4\n"))
    job = folder / "ensemble.job"
    job.write_text(JOB)
    code, _, err = campaign("run", job)
    assert code == 0, err
    plan = expand(job)
    losses = []
    for k in range(3):
        with xr.open_dataset(plan.folder / "v00" / "000" / f"r{k}" / "history.nc") as history:
            bird = history["point_body"].values == list(history["body"].values).index("bird")
            losses.append(history["point_lost_work"].values[bird])
    # no draw decided a pivot: the three runs' losses are the same, bit for bit
    assert all(np.array_equal(run, losses[0]) for run in losses) and losses[0][0] > 0
    mean = (losses[0] + losses[1] + losses[2]) / 3  # by hand
    with xr.open_dataset(plan.folder / "v00" / "001" / WEAR_FILE) as record:
        assert record.attrs["reshaped_bodies"] == "bird"
        watched = record["bird_point"].values  # contactWatch = 0
        np.testing.assert_allclose(record["bird_loss"].values, mean[watched], rtol=1e-14, atol=0)
        np.testing.assert_allclose(abs(record["bird_displacement"].values).max(), 1e-4, rtol=1e-12)
    code, _, err = campaign("collect", job)
    assert code == 0, err
    tree = mbds.open_campaign(plan.folder)
    summary = tree.ds
    assert json.loads(summary.attrs["identical_replicates"]) == ["v00/000"]
    assert summary.attrs["identical_replicates_note"].startswith("1 of 1 versions")
    assert summary["point_lost_work"].dims == ("variant", "replicate", "version", "point")
    assert summary["shape_x"].dims == ("variant", "version", "point")
    assert list(summary["seed"].sel(variant="v00").values) == [t.seed for t in plan.tasks if t.kind == "run"]
    for k in range(3):
        at = summary["point_lost_work"].sel(variant="v00", replicate=k, version=0).values
        np.testing.assert_array_equal(at[bird], losses[k])
        np.testing.assert_array_equal(tree[f"v00/000/r{k}"]["point_lost_work"].values, at)
