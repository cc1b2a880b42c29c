"""A model loaded before is assembled from the compile cache's record, without sympy (issue 12):
the record's model is the one its expressions give, for worn shapes too; runs from it are
bit-identical to runs from the expressions; a worker's tasks on a warm cache import neither
sympy nor typer, xarray or pandas (the outputs are written with netCDF4 alone); a changed input
misses the record."""

import dataclasses
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from mbds.campaign.plan import expand
from mbds.campaign.run import warm_up
from mbds.campaign.tasks import run_task
from mbds.expr.compiled import mark_compiled
from mbds.io.folder import read_model_files
from mbds.model.arrays import flatten
from mbds.model.load import assemble_model, load_model, remembered_model
from tests.campaign.models import two_mass
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]


def assert_same_model(ours, theirs):
    """Every number a run takes from the two models is the same, bit for bit."""
    assert ours.parameters.constant_count == theirs.parameters.constant_count
    for a, b in ((ours.parameters.values, theirs.parameters.values), (ours.q0, theirs.q0), (ours.qd0, theirs.qd0)):
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes()
    assert ours.break_time == theirs.break_time and ours.settings == theirs.settings
    arrays, others = flatten(ours), flatten(theirs)
    for name in dataclasses.fields(arrays):
        a, b = getattr(arrays, name.name), getattr(others, name.name)
        assert np.asarray(a).tobytes() == np.asarray(b).tobytes(), name.name


def test_the_record_gives_the_model_its_expressions_give_for_worn_shapes_too(tmp_path, cache):
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    key = load_model(folder).compiled.source_hash  # from the expressions: the record is kept
    mark_compiled(key)
    files = read_model_files(folder)
    remembered = remembered_model(files)
    assert remembered is not None and remembered.expressions is None and remembered.compiled.source_hash == key
    assert_same_model(remembered, assemble_model(files))
    shape = folder / "mass1.exs"  # worn: the shape's points moved, so its mass properties change
    shape.write_text(shape.read_text().replace("0.05 0.06 0.05", "0.05 0.065 0.05"))
    worn = read_model_files(folder)
    remembered = remembered_model(worn)
    assert remembered is not None
    assert_same_model(remembered, assemble_model(worn))
    assert remembered.parameters.values.tobytes() != assemble_model(files).parameters.values.tobytes()
    constants = folder / "2mass.cns"
    constants.write_text(constants.read_text() + "\n")  # any other file changed: no record
    assert remembered_model(read_model_files(folder)) is None


WORKER = """
import json, pickle, sys
from mbds.campaign.tasks import import_for, run_task
plan = pickle.loads(open(sys.argv[1], "rb").read())
import_for({task.kind for task in plan.tasks})
results = [run_task(task) for task in plan.tasks]
print(json.dumps({"results": results, "loaded": [m for m in ("sympy", "typer", "xarray", "pandas") if m in sys.modules]}))
"""


def as_a_worker(plan, cache: Path, tmp_path: Path) -> dict:
    """The results of ``plan``'s tasks run in order by a fresh process as a worker rank runs
    them, and which of sympy, typer, xarray and pandas it imported."""
    import pickle

    plan_file = tmp_path / "plan.pickle"
    plan_file.write_bytes(pickle.dumps(plan))
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MBDS_CACHE_DIR": str(cache)}
    done = subprocess.run([sys.executable, "-c", WORKER, str(plan_file)], capture_output=True, text=True, env=env,
                          check=True)
    return json.loads(done.stdout.splitlines()[-1])


def test_a_worker_on_a_warm_cache_runs_a_chain_without_sympy_or_xarray_and_bit_identically(tmp_path, cache):
    first = two_mass(tmp_path / "first", None, jobs="000-001")
    results = {task.id: run_task(task) for task in expand(first).tasks}  # the records are kept here
    assert all(r["state"] == "done" for r in results.values()), results
    mark_compiled(load_model(first.parent / "000").compiled.source_hash)
    again = two_mass(tmp_path / "again", None, jobs="000-001")
    plan = expand(again)
    assert [task.kind for task in plan.tasks] == ["prepare", "run", "wear", "run", "wear"]
    worker = as_a_worker(plan, cache, tmp_path)
    assert [r["state"] for r in worker["results"]] == ["done"] * len(results)
    assert worker["loaded"] == [], f"a worker on a warm cache imported {worker['loaded']}"
    assert sum(r["compiled"] for r in worker["results"]) == 0
    for version in ("000", "001"):
        with xr.open_dataset(first.parent / version / "history.nc") as ours, \
                xr.open_dataset(again.parent / version / "history.nc") as theirs:
            for name in ("q", "qd", "qdd", "point_lost_work"):
                assert ours[name].values.tobytes() == theirs[name].values.tobytes(), (version, name)


def test_the_warm_up_of_all_variants_leaves_the_cache_as_a_campaign_run_before(tmp_path, cache):
    """``warm_up(plan)`` keeps every variant's record: a campaign after it needs no sympy on its
    workers, and its prepare tasks find the structures that its runs use."""
    job = two_mass(tmp_path / "a", "c'gravity = 9.81, 5\ncontact.mass1-mass2.friction = 0.1, 0.3\n", jobs="000-000")
    assert warm_up(expand(job)) == 1
    plan = expand(job)
    worker = as_a_worker(plan, cache, tmp_path)
    assert {r["state"] for r in worker["results"]} == {"done"} and worker["loaded"] == []
    assert sum(r["compiled"] for r in worker["results"]) == 0
