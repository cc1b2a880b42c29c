"""A tree of many nodes put together at once (mbds.data.tree.grown) is the tree
``DataTree.from_dict`` makes; nodes whose coordinates meet their parents' as a node checked
before did join without xarray checking them again, and any other node is checked."""

import numpy as np
import pytest
import xarray as xr
from xarray.core import datatree
from xarray.indexes import PandasIndex

from mbds.data.tree import grown

BODIES = np.array(["mass1", "mass2"])


def root() -> xr.Dataset:
    """A summary: the bodies indexed, 4 shape points, 3 variants."""
    return xr.Dataset({"shape_x": (("variant", "point"), np.arange(12.0).reshape(3, 4))},
                      coords={"variant": ["v0", "v1", "v2"], "body": BODIES})


def runs(count: int, points: int = 4, bodies=BODIES) -> dict[str, xr.Dataset]:
    """Run datasets of one layout (the body and watch indexes are the same objects), each with
    sample times of its own, under ``/v<k>/<version>``."""
    shared = {"body": PandasIndex(bodies, "body"), "watch": PandasIndex([0, 1, 2], "watch")}
    made = {}
    for k in range(count):
        time = np.linspace(0.0, 0.1, 5 + k)
        indexes = {**shared, "time": PandasIndex(time, "time")}
        coords = xr.Coordinates({name: xr.Variable(name, index.index.values) for name, index in indexes.items()},
                                indexes=indexes)
        made[f"/v{k % 3}/{k // 3:03d}"] = xr.Dataset(
            {"lost": (("time", "point"), np.full((time.size, points), float(k))),
             "impulse": (("time", "watch"), np.zeros((time.size, 3)))}, coords=coords)
    return made


@pytest.fixture
def checks(monkeypatch):
    """The number of nodes xarray checks against their parents."""
    counted = [0]
    check = datatree.check_alignment

    def counting(*args):
        counted[0] += 1
        return check(*args)

    monkeypatch.setattr(datatree, "check_alignment", counting)
    return counted


def test_the_tree_is_the_one_from_dict_makes(checks):
    tree = grown(root(), runs(30))
    assert checks[0] < 10  # the 3 variant nodes and one run of the layout, not all 30
    expected = xr.DataTree.from_dict({"/": root(), **runs(30)})
    xr.testing.assert_identical(tree, expected)
    assert [node.path for node in tree.subtree] == [node.path for node in expected.subtree]
    run = tree["v2/009"]
    assert "body" not in run.to_dataset(inherit=False).variables  # inherited from the root, as from_dict does
    assert run.ds.xindexes["body"] is tree.ds.xindexes["body"]


def test_a_node_that_meets_its_parents_otherwise_is_checked():
    nodes = runs(6)
    nodes["/v0/009"] = runs(1, points=5)["/v0/000"]  # 5 shape points where the summary has 4
    with pytest.raises(ValueError, match="not aligned"):
        grown(root(), nodes)
    nodes = runs(6)
    nodes["/v1/009"] = runs(1, bodies=np.array(["mass1", "wall"]))["/v0/000"]  # other bodies
    with pytest.raises(ValueError, match="not aligned"):
        grown(root(), nodes)


def test_a_node_named_like_a_variable_of_its_parent_is_refused():
    with pytest.raises(KeyError, match="already contains a variable named shape_x"):
        grown(root(), {"/shape_x": runs(1)["/v0/000"]})
