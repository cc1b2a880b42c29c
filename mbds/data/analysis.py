"""Helpers for notebooks: a body's outline, one variable across a campaign's runs, selection of
variants by the values of their varied keys. They take what ``xr.open_dataset`` (a history.nc) and
:func:`mbds.open_campaign` return."""

from __future__ import annotations

import numpy as np
import xarray as xr

from mbds.errors import ModelError


def outline(ds: xr.Dataset, body: str, version: int | None = None, **selection) -> np.ndarray:
    """The closed polygon (first point repeated last) of ``body`` in its body frame (m), shape
    (points + 1, 2). ``ds`` is a run's history (``version`` not needed) or a campaign's root
    dataset (``version`` picks the version; ``selection`` the rest, e.g. ``variant="v000"``).
    ModelError when the body is unknown or the selection leaves more than one shape."""
    names = [str(n) for n in ds["body"].values]
    if body not in names:
        raise ModelError(f"no body {body!r}; the bodies are {', '.join(names)}")
    if version is not None and "version" in ds.dims:
        selection["version"] = version
    mine = ds["point_body"].values == names.index(body)
    x = ds["shape_x"].sel(selection).isel(point=mine)
    y = ds["shape_y"].sel(selection).isel(point=mine)
    if x.ndim != 1:
        left = [d for d in x.dims if d != "point"]
        raise ModelError(f"select one shape: give {', '.join(left)}")
    points = np.column_stack([x.values, y.values])
    return np.vstack([points, points[:1]])


def stack(tree: xr.DataTree, name: str, version: int) -> xr.DataArray:
    """History variable ``name`` of ``version``'s run of every variant (and replicate) of a
    collected campaign as one DataArray, dimensions (variant[, replicate], time, ...), with the
    variant parameters as coordinates. Runs of different lengths are padded with NaN."""
    root = tree.ds
    variants = [str(v) for v in root["variant"].values]
    replicates = [int(r) for r in root["replicate"].values] if "replicate" in root.dims else [None]
    rows = []
    for variant in variants:
        runs = [_run_node(tree, variant, version, r)[name] for r in replicates]
        rows.append(xr.concat(runs, "replicate", join="outer") if replicates != [None] else runs[0])
    out = xr.concat(rows, "variant", join="outer", coords="minimal", compat="override")
    keys = {k: ("variant", c.values, c.attrs) for k, c in root.coords.items() if c.dims == ("variant",) and k != "variant"}
    out = out.assign_coords(variant=variants, **keys)
    return out.assign_coords(replicate=replicates) if replicates != [None] else out


def _run_node(tree: xr.DataTree, variant: str, version: int, replicate: int | None) -> xr.Dataset:
    """The history of one run in a campaign tree (any of its three layouts)."""
    v = f"{version:03d}"
    paths = [f"{variant}/{v}"] if replicate is None else [f"{variant}/{v}/r{replicate}", f"{variant}/r{replicate}/{v}"]
    for path in paths:
        try:
            return tree[path].ds
        except KeyError:
            continue
    raise ModelError(f"no run {paths[0]} in the campaign (not done or not collected)")


def select(ds: xr.Dataset, **values) -> xr.Dataset:
    """The variants of a campaign's root dataset whose varied keys have ``values`` (by name as
    in the file, e.g. ``select(ds, c_mu=0.3, c_e=0.9)``); close floats match."""
    keep = np.ones(ds.sizes["variant"], dtype=bool)
    for key, value in values.items():
        if key not in ds.coords or ds[key].dims != ("variant",):
            raise ModelError(f"{key!r} is not a varied key of the campaign")
        column = ds[key].values
        keep &= np.isclose(column.astype(float), float(value)) if column.dtype.kind == "f" else column == value
    return ds.isel(variant=np.flatnonzero(keep))
