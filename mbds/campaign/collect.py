"""One file for a whole campaign: the runs' ``history.nc`` files merged into ``campaign.nc``.

``collect(plan) -> path`` writes ``<campaign folder>/campaign.nc`` (atomically) as NetCDF
groups; ``open_campaign(path)`` reads it back as an ``xarray.DataTree``:

- the root dataset, the summary: dimensions ``variant``, ``version``, ``body``, ``point`` (and
  ``replicate`` when the campaign has replicates) with ``shape_x``, ``shape_y`` (m, the shape
  every version ran on) and ``point_lost_work`` (J, lost at each shape point in the run), the
  per-run scalars ``end_energy`` (J), ``run_lost_work`` (J), ``steps``, ``wall`` (s) and
  ``status`` (the run task's state), each chain's ``seed``, and the varied keys as coordinates
  along ``variant``;
- one node per run with that run's ``history.nc`` root dataset: ``/<variant>/<version>``,
  ``/<variant>/<version>/r<k>`` (ensemble replicates), ``/<variant>/r<k>/<version>`` (a chain
  per replicate).

In ``mode = ensemble`` the shapes have no ``replicate`` dimension (the replicates of a version run
on one shape); in ``mode = chains`` every variable of a run has it. A run that is not done has
NaN (``steps``: -1) and its state in ``status``. Provenance is in the root's attributes.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
from pathlib import Path

import netCDF4
import numpy as np
import xarray as xr

from mbds import __version__
from mbds.campaign.ledger import DONE, Ledger
from mbds.campaign.plan import RUN, Plan, Task
from mbds.campaign.section import ENSEMBLE
from mbds.data.history import FILE_NAME as HISTORY
from mbds.errors import ModelError
from mbds.io.text import atomic_path

CAMPAIGN_FILE = "campaign.nc"
POINT_VARIABLES = ("shape_x", "shape_y", "point_lost_work")
SUMMARY_VARIABLES = POINT_VARIABLES + ("body", "point_body", "point_number")


def collect(plan: Plan) -> Path:
    """Merge the runs of ``plan`` into ``campaign.nc`` in its campaign folder; its path.
    ModelError when no run of the campaign is done.

    Each run's root group is copied into its node, one run at a time, variable by variable with
    the run file's own types, attributes, chunks and compression (memory holds one variable at a
    time, whatever the campaign's size); then the summary is written into the root group."""
    ledger = Ledger.read(plan.folder)
    ledger.check(plan)
    runs = [t for t in plan.tasks if t.kind == RUN]
    done = [t for t in runs if ledger.state(t.id) == DONE and (t.folder / HISTORY).is_file()]
    if not done:
        raise ModelError("no run of the campaign is done yet; run it first: mbds-campaign run", plan.job.path)
    path = plan.folder / CAMPAIGN_FILE
    with atomic_path(path) as tmp:
        with netCDF4.Dataset(tmp, "w") as out:
            histories = {task.id: copy_root_group(task.folder / HISTORY, out.createGroup(node_path(plan, task)))
                         for task in done}
        summary(plan, ledger, runs, histories).to_netcdf(tmp, mode="a", engine="netcdf4")
    return path


def open_campaign(path: str | Path, load: bool = False) -> xr.DataTree:
    """The campaign file at ``path`` (``campaign.nc``, or a campaign folder holding one), opened
    lazily as xarray opens files (values are read when used; ``tree.close()`` releases the file),
    or read whole into memory and closed with ``load=True``. ModelError when there is none.
    The varied keys are indexed: ``tree.ds.sel(c_mu=0.3)`` (one key at a time; several with
    :func:`mbds.data.analysis.select`)."""
    path = Path(path)
    if path.is_dir():
        path = path / CAMPAIGN_FILE
    if not path.is_file():
        raise ModelError("no campaign file; collect the campaign first: mbds-campaign collect", path)
    tree = xr.open_datatree(path, engine="netcdf4")
    root = tree.ds
    for name in [name for name, c in root.coords.items() if "key" in c.attrs and c.dims == ("variant",)]:
        root = root.set_xindex(name)
    tree.dataset = root
    if not load:
        return tree
    with tree:
        return tree.load()


def copy_root_group(source: Path, group: netCDF4.Group) -> xr.Dataset:
    """Copy the root group of the run file ``source`` (dimensions, variables with their
    attributes, chunks and compression, and its attributes; not its subgroups) into ``group``;
    what the summary takes from it: the variables ``SUMMARY_VARIABLES`` and the attributes."""
    kept, pairs = {}, []
    with netCDF4.Dataset(source) as run:
        run.set_auto_maskandscale(False)
        for name, dimension in run.dimensions.items():
            group.createDimension(name, None if dimension.isunlimited() else len(dimension))
        for name, variable in run.variables.items():  # define all first: each switch to writing costs
            attributes = {key: variable.getncattr(key) for key in variable.ncattrs()}
            filters = variable.filters() or {}
            chunks = variable.chunking()
            copy = group.createVariable(
                name, variable.datatype, variable.dimensions, fill_value=attributes.pop("_FillValue", None),
                zlib=bool(filters.get("zlib")), complevel=filters.get("complevel") or 4,
                shuffle=bool(filters.get("shuffle")), contiguous=chunks == "contiguous",
                chunksizes=None if chunks == "contiguous" else chunks)
            copy.set_auto_maskandscale(False)
            copy.setncatts(attributes)
            pairs.append((name, variable, copy, attributes))
        attributes = {key: run.getncattr(key) for key in run.ncattrs()}
        group.setncatts(attributes)
        for name, variable, copy, variable_attributes in pairs:
            copy[...] = values = variable[...]
            if name in SUMMARY_VARIABLES:
                kept[name] = (variable.dimensions, values, variable_attributes)
    return xr.Dataset(kept, attrs=attributes)


def node_path(plan: Plan, task: Task) -> str:
    """Where the run of ``task`` is in the tree: its chain, then its folder within the chain."""
    chain = next(c for c in plan.chains if c.id == task.chain)
    return f"/{chain.id}/{task.folder.relative_to(chain.folder).as_posix()}"


def summary(plan: Plan, ledger: Ledger, runs: list[Task], histories: dict[str, xr.Dataset]) -> xr.Dataset:
    """The root dataset: shapes, losses and scalars of every run, by variant and version."""
    variants = [v.id for v in plan.variants] or [plan.job.path.stem]
    versions = sorted({t.version for t in runs})
    replicates = plan.campaign.replicates if plan.campaign else 1
    ensemble = plan.campaign is not None and plan.campaign.mode == ENSEMBLE
    first = next(iter(histories.values()))
    points = first.sizes["point"]
    index = {(t.variant.index if t.variant else 0, t.replicate or 0, t.version): t for t in runs}
    shape = (len(variants), replicates, len(versions))
    arrays = {name: np.full(shape + (points,), np.nan) for name in POINT_VARIABLES}
    scalars = {name: np.full(shape, np.nan) for name in ("end_energy", "run_lost_work", "wall")}
    steps = np.full(shape, -1, dtype=np.int64)
    status = np.empty(shape, dtype=object)
    seeds = np.zeros(shape[:2], dtype=np.int64)
    for (v, r, k), task in index.items():
        at = (v, r, versions.index(k))
        seeds[v, r] = task.seed
        status[at] = ledger.state(task.id)
        history = histories.get(task.id)
        if history is None:
            continue
        if history.sizes["point"] != points:
            raise ModelError(f"{history.sizes['point']} shape points, the campaign's runs {points}",
                             task.folder / HISTORY)
        for name in POINT_VARIABLES:
            arrays[name][at] = history[name].values
        scalars["end_energy"][at] = history.attrs["end_energy"]
        scalars["run_lost_work"][at] = history.attrs["run_lost_work"]
        scalars["wall"][at] = ledger.entry(task.id).get("wall", np.nan)
        steps[at] = history.attrs["steps"]
    run_dims = ("variant", "replicate", "version")
    shape_dims = ("variant", "version", "point") if ensemble else run_dims + ("point",)
    data = {}
    for name in POINT_VARIABLES:
        values = arrays[name][:, 0] if ensemble and name != "point_lost_work" else arrays[name]
        dims = shape_dims if name != "point_lost_work" else run_dims + ("point",)
        data[name] = (dims, values, dict(first[name].attrs))
    units = {"end_energy": ("mechanical energy at the run's end", "J"),
             "run_lost_work": ("mechanical energy lost at contacts in the run", "J"),
             "wall": ("wall time of the run task", "s")}
    for name, (long_name, unit) in units.items():
        data[name] = (run_dims, scalars[name], {"long_name": long_name, "units": unit})
    data["steps"] = (run_dims, steps, {"long_name": "time steps of the run (-1: not done)"})
    data["status"] = (run_dims, status.astype(str), {"long_name": "state of the run task in the ledger"})
    data["seed"] = (("variant", "replicate"), seeds, {"long_name": "seed of the chain's runs"})
    coords = {
        "variant": ("variant", np.array(variants, dtype=object), {"long_name": "variant of the campaign"}),
        "replicate": ("replicate", np.arange(replicates, dtype=np.int32), {"long_name": "replicate", "units": "1"}),
        "version": ("version", np.array(versions, dtype=np.int32), {"long_name": "model version", "units": "1"}),
        "body": ("body", first["body"].values),
        "point_body": ("point", first["point_body"].values),
        "point_number": ("point", first["point_number"].values),
    }
    for p in plan.campaign.parameters if plan.campaign else ():
        coords[_name(p.key)] = ("variant", _values([v.values[p.key] for v in plan.variants]),
                                {"key": p.key, "long_name": f"varied key {p.key}", "units": "1",
                                 "comment": "in the unit the model's files give it"})
    ds = xr.Dataset(data, coords=coords, attrs=provenance(plan, ledger))
    return ds if replicates > 1 else ds.squeeze("replicate", drop=True)


def provenance(plan: Plan, ledger: Ledger) -> dict:
    """Attributes of the campaign file: what made it, where and when."""
    runs = ledger.campaign.get("runs", [])
    return {
        "Conventions": "CF-1.10",
        "title": f"mbds campaign of {plan.job.path.name}",
        "mbds_version": __version__,
        "git_commit": _git_commit(),
        "job_file": str(plan.job.path),
        "job_text": plan.job.path.read_text(encoding="utf-8"),
        "variants": json.dumps({v.id: v.values for v in plan.variants}),
        "mode": plan.campaign.mode if plan.campaign else "",
        "campaign_seed": plan.campaign.seed if plan.campaign else 0,
        "host": " ".join(sorted({r["host"] for r in runs})),
        "workers": max((r["workers"] for r in runs), default=0),
        "start": runs[0]["start"] if runs else "",
        "end": runs[-1]["end"] if runs else "",
        "runs": json.dumps(runs),
    }


def _values(texts: list[str]) -> np.ndarray:
    """Values of a varied key as numbers when they all are, else as written."""
    try:
        return np.array([float(text) for text in texts])
    except ValueError:
        return np.array(texts, dtype=object)


def _name(key: str) -> str:
    """A variable name for a varied key (``c'mu`` -> ``c_mu``)."""
    return re.sub(r"[^0-9A-Za-z_]", "_", key)


def _git_commit() -> str:
    """The commit of the source tree mbds runs from, when it is a git checkout ('' otherwise)."""
    try:
        done = subprocess.run(["git", "rev-parse", "HEAD"], cwd=os.path.dirname(__file__), capture_output=True,
                              text=True, timeout=10, check=False)
    except OSError:
        return ""
    return done.stdout.strip() if done.returncode == 0 else ""
