"""A collected campaign keeps its runs' histories in their files: a run's node equals its
history.nc as xarray opens it, no run file is read before a value is used, and a moved run
file gives a clear error."""

import json

import numpy as np
import pytest
import xarray as xr

import mbds
from mbds.campaign.collect import collect
from mbds.campaign.plan import expand
from mbds.data.references import Described, describe, open_described
from mbds.errors import ModelError
from tests.campaign.models import two_mass
from tests.campaign.test_run import campaign


@pytest.fixture(scope="module")
def collected(tmp_path_factory):
    job = two_mass(tmp_path_factory.mktemp("refs"), "c'gravity = 9.81, 5\nworld.breakTime = 0.2, 0.15\n",
                   jobs="000-001")
    code, _, err = campaign("run", job)
    assert code == 0, err
    plan = expand(job)
    return plan, collect(plan)


def test_a_described_history_opens_as_xarray_opens_it(collected):
    plan, _ = collected
    history = plan.folder / "v01" / "001" / "history.nc"
    description, times, _ = describe(history)
    with xr.open_dataset(history) as direct:
        assert open_described(history, description, times).load().identical(direct.load())


def test_runs_of_one_layout_share_it_and_still_open_as_xarray_opens_them(collected):
    plan, _ = collected
    opener, opened = Described(), []
    for history in sorted(plan.folder.glob("v*/*/history.nc")):
        ds = opener.open(history, *describe(history)[:2])
        with xr.open_dataset(history) as direct:
            assert ds.load().identical(direct.load()), history
        opened.append(ds)
    assert {ds.sizes["time"] for ds in opened} == {301, 401}  # breakTime 0.15 s and 0.2 s, a sample per 0.5 ms
    assert all(ds.xindexes["watch"] is opened[0].xindexes["watch"] for ds in opened)  # one layout, shared


def test_descriptions_read_their_shared_parts_once(collected):
    plan, _ = collected
    opener = Described()
    descriptions = [describe(history)[0] for history in sorted(plan.folder.glob("v*/*/history.nc"))]
    headers = [opener._parsed(text) for text in descriptions]
    assert headers == [json.loads(text) for text in descriptions]
    assert all(h["variables"] is headers[0]["variables"] and h["index"] is headers[0]["index"] for h in headers)
    assert len({id(h["attrs"]) for h in headers}) == len(headers)  # each run its own attributes
    spaced = json.dumps(headers[0], indent=1)
    assert opener._parsed(spaced) == headers[0]
    with pytest.raises(ValueError, match="expected ':'"):
        opener._parsed('{"dims" {}}')


def test_the_tree_is_the_summary_with_a_node_per_run_file(collected):
    plan, path = collected
    with mbds.open_campaign(path) as tree:
        runs = [node.path for node in tree.subtree if "time" in node.ds.dims]
        assert len(runs) == 8
        files = {run: xr.open_dataset(plan.folder / run.strip("/") / "history.nc") for run in runs}
        assert tree.identical(xr.DataTree.from_dict({"/": tree.to_dataset(inherit=False), **files}))
        for ds in files.values():
            ds.close()


def test_run_nodes_are_the_run_files_read_when_used(collected, monkeypatch):
    plan, path = collected
    from mbds.data import references

    opened = []
    real = references._FileVariable._read
    monkeypatch.setattr(references._FileVariable, "_read", lambda self, key: opened.append(self.path) or real(self, key))
    tree = mbds.open_campaign(path)
    assert opened == []  # opening reads no run file
    lost = tree["v00/001"]["lost_work"].values
    assert opened == [plan.folder / "v00" / "001" / "history.nc"]
    with xr.open_dataset(plan.folder / "v00" / "001" / "history.nc") as run:
        np.testing.assert_array_equal(lost, run["lost_work"].values)
    tree.close()


def test_a_moved_run_file_is_named(collected, tmp_path):
    plan, path = collected
    tree = mbds.open_campaign(path)
    history = plan.folder / "v01" / "000" / "history.nc"
    moved = tmp_path / "moved.nc"
    history.rename(moved)
    try:
        with pytest.raises(ModelError, match="collect the campaign again"):
            tree["v01/000"]["q"].values
    finally:
        moved.rename(history)
        tree.close()


def test_the_summary_alone_is_the_trees_root(collected):
    _, path = collected
    with mbds.open_campaign(path) as tree, mbds.open_campaign(path, runs=False) as summary:
        assert not summary.children and len(tree.children) == 4
        assert summary.to_dataset().identical(tree.to_dataset())
