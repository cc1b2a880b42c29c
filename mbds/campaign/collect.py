"""One file for a whole campaign: the summary of its runs, and references to their histories.

``collect(plan) -> path`` writes ``<campaign folder>/campaign.nc`` (atomically); ``open_campaign``
reads it back as an ``xarray.DataTree``:

- the root dataset, the summary: dimensions ``variant``, ``version``, ``body``, ``point`` (and
  ``replicate`` when the campaign has replicates) with ``shape_x``, ``shape_y`` (m, the shape
  every version ran on) and ``point_lost_work`` (J, lost at each shape point in the run), the
  per-run scalars ``end_energy`` (J), ``run_lost_work`` (J), ``steps``, ``wall`` (s) and
  ``status`` (the run task's state), each chain's ``seed``, and the varied keys as coordinates
  along ``variant``;
- one node per run with that run's ``history.nc`` root dataset: ``/<variant>/<version>``,
  ``/<variant>/<version>/r<k>`` (ensemble replicates), ``/<variant>/r<k>/<version>`` (a chain
  per replicate).

The runs' histories stay in their files: the group ``runs`` of ``campaign.nc`` holds, per run,
its node, its file (relative to the campaign folder), a description of the file's root group and
its sample times (:mod:`mbds.data.references`). Collecting reads each run's summary variables
once; opening builds every node from the descriptions without opening a run file, and a node's
values are read from its run file when they are used.

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

from mbds._version import version as mbds_version
from mbds.campaign.ledger import DONE, Ledger
from mbds.campaign.plan import DAP_BC, RUN_KINDS, Plan, Task
from mbds.campaign.replicates import identical_replicates
from mbds.campaign.section import ENSEMBLE
from mbds.data.history import FILE_NAME as HISTORY
from mbds.data.references import Described, describe
from mbds.data.tree import grown
from mbds.errors import ModelError
from mbds.io.text import atomic_path

CAMPAIGN_FILE = "campaign.nc"
RUNS_GROUP = "runs"
POINT_VARIABLES = ("shape_x", "shape_y", "point_lost_work")
SUMMARY_VARIABLES = POINT_VARIABLES + ("body", "point_body", "point_number")


def collect(plan: Plan) -> Path:
    """Write ``campaign.nc`` in the campaign folder of ``plan`` from its done runs; its path.
    ModelError when no run of the campaign is done.

    Each run file is read once, for its summary variables and the description of its root group;
    the histories themselves stay in the run files."""
    ledger = Ledger.read(plan.folder)
    ledger.check(plan)
    runs = [t for t in plan.tasks if t.kind in RUN_KINDS]
    make_summary, read = summary, SUMMARY_VARIABLES
    if plan.model == DAP_BC:
        from mbds.campaign.dapbc_collect import SUMMARY_VARIABLES as read
        from mbds.campaign.dapbc_collect import dapbc_summary as make_summary
    done = [t for t in runs if ledger.state(t.id) == DONE and (t.folder / HISTORY).is_file()]
    if not done:
        raise ModelError("no run of the campaign is done yet; run it first: mbds-campaign run", plan.job.path)
    histories, references = {}, []
    for task in done:
        description, times, small = describe(task.folder / HISTORY, read=read)
        histories[task.id] = xr.decode_cf(xr.Dataset(small, attrs=json.loads(description)["attrs"]))
        references.append((node_path(plan, task), (task.folder / HISTORY).relative_to(plan.folder).as_posix(),
                           description, times))
    path = plan.folder / CAMPAIGN_FILE
    with atomic_path(path) as tmp:
        make_summary(plan, ledger, runs, histories).to_netcdf(tmp, engine="netcdf4")
        with netCDF4.Dataset(tmp, "a") as out:
            write_references(out.createGroup(RUNS_GROUP), references)
    return path


def write_references(group: netCDF4.Group, references: list[tuple[str, str, str, np.ndarray]]) -> None:
    """The runs' nodes, files, descriptions and sample times (concatenated, with each run's first
    index in ``time_start``) into ``group``."""
    group.createDimension("run", len(references))
    times = [r[3] for r in references]
    group.createDimension("sample", sum(len(t) for t in times))
    for k, name in enumerate(("node", "file", "description")):
        variable = group.createVariable(name, str, ("run",))
        variable[:] = np.array([r[k] for r in references], dtype=object)
    start = group.createVariable("time_start", "i8", ("run",))
    start[:] = np.concatenate([[0], np.cumsum([len(t) for t in times])[:-1]]).astype(np.int64)
    samples = group.createVariable("time", "f8", ("sample",), zlib=True, complevel=1)
    samples[:] = np.concatenate(times) if times else np.zeros(0)


def open_campaign(path: str | Path, load: bool = False, runs: bool = True) -> xr.DataTree:
    """The campaign file at ``path`` (``campaign.nc``, or a campaign folder holding one) as a
    tree: the summary opened lazily as xarray opens files, and each run's node built from its
    reference, its values read from the run's ``history.nc`` when used (``tree.close()`` releases
    the campaign file); or everything read into memory, files closed, with ``load=True``.
    ``runs=False``: the summary alone, a tree of one node (what reads only the summary, as the
    campaign figures do, skips making a node per run). The varied keys are indexed:
    ``tree.ds.sel(c_mu=0.3)`` (one key at a time; several with :func:`mbds.data.analysis.select`).
    ModelError when there is none."""
    path = Path(path)
    if path.is_dir():
        path = path / CAMPAIGN_FILE
    if not path.is_file():
        raise ModelError("no campaign file; collect the campaign first: mbds-campaign collect", path)
    nodes = run_nodes(path) if runs else {}
    opened = summary_ds = xr.open_dataset(path, engine="netcdf4")
    for name in [name for name, c in summary_ds.coords.items() if "key" in c.attrs and c.dims == ("variant",)]:
        summary_ds = summary_ds.set_xindex(name)
    tree = grown(summary_ds, nodes)
    tree.set_close(opened.close)  # the file itself: a handle left to the garbage collector may close inside HDF5
    if not load:
        return tree
    with tree:
        return tree.load()


def run_nodes(path: Path) -> dict[str, xr.Dataset]:
    """The run nodes of the campaign file ``path`` by their paths, built from their references."""
    nodes, described = {}, Described()
    with netCDF4.Dataset(path) as campaign:
        campaign.set_auto_mask(False)  # plain arrays: the references have no fill values
        runs = campaign.groups[RUNS_GROUP]
        times, starts = runs["time"][...], runs["time_start"][...]
        ends = np.append(starts[1:], len(times))
        for node, file, description, a, b in zip(runs["node"][...], runs["file"][...], runs["description"][...],
                                                 starts, ends):
            nodes[node] = described.open(path.parent / file, description, times[a:b])
    return nodes


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
    same, complete = identical_replicates(plan, ledger)
    return {
        "Conventions": "CF-1.10",
        "title": f"mbds campaign of {plan.job.path.name}",
        "mbds_version": mbds_version(),
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
        "identical_replicates": json.dumps(same),
        "identical_replicates_note": (f"{len(same)} of {complete} versions with all replicates run have "
                                      "bit-identical replicates: the lexicographic randomisation decided no pivot there"
                                      if complete else ""),
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
