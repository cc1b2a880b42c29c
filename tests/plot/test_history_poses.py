"""The poses and dependent coordinates written to history.nc, and the notebook helpers."""

import numpy as np
import pytest
import xarray as xr

import mbds
from mbds.errors import ModelError


def history(folder):
    return xr.open_dataset(folder / "000" / "history.nc")


def test_dependent_coordinates_and_poses_of_the_woodpecker(model_runs):
    with history(model_runs["woodpecker"]) as ds:
        sides = [f"b'ringSide{s}'{c}" for s in "UL" for c in ("x", "y", "Rz")]
        assert list(ds["dependent"].values) == ["b'bird'x", "b'bird'y", *sides]
        assert list(ds["dependent_unit"].values) == ["m", "m"] + ["m", "m", "rad"] * 2
        bird = ds.sel(body="bird")
        np.testing.assert_array_equal(bird["body_x"].values, ds["dependent_q"].values[:, 0])
        np.testing.assert_array_equal(bird["body_y"].values, ds["dependent_q"].values[:, 1])
        np.testing.assert_array_equal(bird["body_angle"].values, ds["q"].sel(coordinate="b'bird'Rz").values)
        assert list(ds["body_kind"].values) == ["moving", "fixed", "moving", "virtual", "moving", "moving"]
        # the virtual ringSideR moves rigidly with the ring: its origin keeps its distance and angle
        ring, side = ds.sel(body="ring"), ds.sel(body="ringSideR")
        distance = np.hypot(side["body_x"] - ring["body_x"], side["body_y"] - ring["body_y"]).values
        np.testing.assert_allclose(distance, distance[0], rtol=1e-12)
        np.testing.assert_allclose((side["body_angle"] - ring["body_angle"]).values, 0.0, atol=1e-12)
        assert ds["q"].attrs["ancillary_variables"] == "coordinate_unit"
        assert "units" not in ds["q"].attrs


def test_outline_is_the_closed_shape_of_the_body(model_runs):
    with history(model_runs["2mass"]) as ds:
        polygon = mbds.outline(ds, "mass2")
        mine = ds["point_body_name"].values == "mass2"
        assert polygon.shape == (mine.sum() + 1, 2)
        np.testing.assert_array_equal(polygon[0], polygon[-1])
        np.testing.assert_array_equal(polygon[:-1, 0], ds["shape_x"].values[mine])
        with pytest.raises(ModelError, match="no body 'moon'"):
            mbds.outline(ds, "moon")


def test_campaign_root_is_cf_and_selectable_by_value(campaign_job):
    with mbds.open_campaign(campaign_job.parent / "campaign") as tree:
        root = tree.ds
        assert root.attrs["Conventions"] == "CF-1.10"
        for name in ("version", "contact_mass1_mass2_friction"):
            assert root[name].attrs["long_name"] and root[name].attrs["units"] == "1"
        first, second = (str(v) for v in root["variant"].values)
        picked = root.sel(contact_mass1_mass2_friction=0.3)
        assert str(picked["variant"].values) == second
        assert mbds.select(root, contact_mass1_mass2_friction=0.1)["variant"].values.tolist() == [first]
        np.testing.assert_array_equal(mbds.outline(root, "mass1", 1, variant=second), mbds.outline(picked, "mass1", 1))
        with pytest.raises(ModelError, match="select one shape"):
            mbds.outline(root, "mass1", 1)


def test_stack_puts_every_variant_of_a_version_in_one_array(campaign_job):
    with mbds.open_campaign(campaign_job.parent / "campaign") as tree:
        energy = mbds.stack(tree, "mechanical_energy", 1)
        assert energy.dims == ("variant", "time")
        assert list(energy["contact_mass1_mass2_friction"].values) == [0.1, 0.3]
        second = str(tree.ds["variant"].values[1])
        np.testing.assert_array_equal(energy.sel(variant=second).values, tree[f"{second}/001"].ds["mechanical_energy"].values)


def test_simulate_runs_a_model_and_returns_its_history(tmp_path):
    from tests.examples import copy_example

    folder = copy_example("2mass", tmp_path / "2mass")
    ds = mbds.simulate(folder, break_time=0.01)
    assert ds.attrs["end_time"] == pytest.approx(0.01) and ds.attrs["model"] == "2mass"
    assert (folder / "000" / "history.nc").is_file()
