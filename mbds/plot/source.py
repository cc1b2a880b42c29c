"""What the figures read: runs (history.nc) found from a path, their kind, axis labels and titles."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from mbds.errors import ModelError

HISTORY = "history.nc"
KINDS = ("mbds", "dap_bc")
"""Values of a history's ``kind`` attribute (absent: mbds). The figure functions dispatch on it."""


def history_paths(path: str | Path) -> list[Path]:
    """The history files ``path`` names: a history file, a version (or replicate) folder, or a
    model folder (its versions with a run, in order). ModelError when there is none."""
    path = Path(path)
    if path.is_file():
        return [path]
    if (path / HISTORY).is_file():
        return [path / HISTORY]
    found = sorted(p / HISTORY for p in path.iterdir() if p.is_dir() and (p / HISTORY).is_file()) if path.is_dir() else []
    if not found:
        raise ModelError(f"no {HISTORY} here: a history file, a version folder or a model folder with runs", path)
    return found


def open_run(path: str | Path) -> xr.Dataset:
    """The run at ``path`` opened lazily (values are read when drawn): a history file, a version
    folder, or a model folder (its highest version with a run)."""
    return open_history(history_paths(path)[-1])


def open_history(path: Path) -> xr.Dataset:
    """One history file, lazily; ModelError when it is not readable."""
    try:
        return xr.open_dataset(path, engine="netcdf4")
    except (OSError, ValueError) as exc:
        raise ModelError(f"not a readable history ({exc})", path) from None


def run_kind(ds: xr.Dataset) -> str:
    """``mbds`` or ``dap_bc`` (the dataset's ``kind`` attribute; mbds when absent)."""
    kind = str(ds.attrs.get("kind", "mbds")).lower()
    if kind not in KINDS:
        raise ModelError(f"unknown kind of run {kind!r} (known: {', '.join(KINDS)})")
    return kind


def label(da: xr.DataArray, unit: str | None = None) -> str:
    """Axis label ``long name (unit)`` from the variable's attributes."""
    name = da.attrs.get("long_name", da.name)
    unit = unit if unit is not None else da.attrs.get("units", "")
    return f"{name} ({unit})" if unit and unit != "1" else str(name)


def run_title(ds: xr.Dataset, what: str = "") -> str:
    """``model woodpecker, version 000`` (and the variant when the run belongs to a campaign)."""
    parts = [f"model {ds.attrs.get('model', '?')}"]
    if "version" in ds.attrs:
        parts.append(f"version {int(ds.attrs['version']):03d}")
    if ds.attrs.get("variant"):
        parts.append(f"variant {ds.attrs['variant']}")
    text = ", ".join(parts)
    return f"{what}: {text}" if what else text
