"""One call for notebooks: run a model version and get its history as an xarray Dataset."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from mbds.data.history import FILE_NAME
from mbds.simulation.version_run import RunOptions, run_version
from mbds.simulation.versions import run_folder


def simulate(path: str | Path, *, break_time: float | None = None, seed: int = 0,
             start_from: int | None = None, force: bool = False) -> xr.Dataset:
    """Run the model at ``path`` (a model folder: its version 000, or the next one after
    ``start_from``; or a version folder) for ``break_time`` s (default: the world's breakTime)
    and return its ``history.nc``, read into memory. The outputs stay in the version folder,
    as ``mbds run`` writes them; a run there is replaced. When the model folder's files were
    edited after its version 000 was made, ModelError names them unless ``force`` (then 000's
    copies are replaced by them), as ``mbds run`` does. ModelError on bad input."""
    folder = run_folder(path, start_from, force)
    run_version(folder, RunOptions(duration=break_time, seed=seed, start_from=start_from))
    with xr.open_dataset(folder / FILE_NAME, engine="netcdf4") as ds:
        return ds.load()
