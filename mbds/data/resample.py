"""A run's history at a coarser sample interval, written over its ``history.nc``."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from mbds.data.history import COMPRESSED, STATE_GROUP
from mbds.errors import ModelError
from mbds.io.text import atomic_path

INTERVAL_SUMS = ("impulse_normal", "impulse_tangential", "impulse_x", "impulse_y")
"""Watch variables that hold sums over each sample interval (``work`` too, unless cumulative)."""


def resample(path: str | Path, interval: float) -> int:
    """Keep one sample of ``history.nc`` at ``path`` per ``interval`` s (the last one of each;
    the first sample stays), adding up the watch impulses and per-interval work of the samples
    left out (forces: their time-weighted mean), so totals are unchanged. The final state is kept
    as it is. Written atomically; the number of samples left."""
    path = Path(path)
    if not interval > 0:
        raise ModelError("the interval must be a positive time (s)", path)
    with xr.open_dataset(path, engine="netcdf4") as ds, xr.open_dataset(path, group=STATE_GROUP, engine="netcdf4") as st:
        root, state = ds.load(), st.load()
    time = root["time"].values
    bins = np.ceil((time - time[0]) / interval - 1e-9).astype(np.int64)  # (k-1, k] intervals
    keep = np.unique(np.concatenate([[0], np.flatnonzero(np.diff(bins, append=bins[-1] + 1))]))
    starts = np.concatenate([[0], keep[:-1] + 1])
    out = root.isel(time=keep)
    summed = [n for n in INTERVAL_SUMS if n in root]
    if "work" in root and not root.attrs.get("watch_cumulative_work", 0):
        summed.append("work")
    force = bool(root.attrs.get("watch_convert_impulse_to_force", 0))
    spans = np.diff(time, prepend=root.attrs.get("start_time", time[0]))[:, None]
    for name in summed:
        values = root[name].values
        if force and name != "work":
            total = np.add.reduceat(values * spans, starts, axis=0)
            length = np.add.reduceat(spans, starts, axis=0)
            merged = np.divide(total, length, out=np.zeros_like(total), where=length > 0)
        else:
            merged = np.add.reduceat(values, starts, axis=0)
        out[name] = (root[name].dims, merged, root[name].attrs)
    out.attrs["resampled_interval"] = interval
    encoding = {n: dict(COMPRESSED) for n, v in out.data_vars.items() if v.ndim == 2 and v.size}
    with atomic_path(path) as tmp:
        out.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
        state.to_netcdf(tmp, mode="a", group=STATE_GROUP, engine="netcdf4")
    return len(keep)
