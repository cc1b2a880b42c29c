"""Writing and reading mbds's NetCDF files with netCDF4 alone, as xarray would write them.

A worker rank of a campaign writes ``history.nc`` and ``wear.nc`` and reads them back without
importing xarray and pandas (docs/performance.md): :func:`write_variables` lays out variables
the way ``xarray.Dataset.to_netcdf`` encodes them, so that ``xarray.open_dataset`` reads the same
dataset as from a file xarray wrote:

- text becomes a variable-length string variable; empty text an empty ``f8`` variable;
- a float variable gets ``_FillValue = NaN``, an integer one no fill value;
- a coordinate that is not a dimension's own is named in the ``coordinates`` attribute of every
  data variable whose dimensions hold its dimensions, else in the group's ``coordinates``.
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import NamedTuple

import netCDF4
import numpy as np

from mbds.errors import ModelError


class Variable(NamedTuple):
    """One variable: its dimensions, values (text as a list of str or an object array),
    attributes, and whether it is a coordinate (xarray's ``coords``)."""

    name: str
    dims: tuple[str, ...]
    values: object
    attrs: dict
    coordinate: bool = False


def write_variables(group: netCDF4.Dataset | netCDF4.Group, variables: list[Variable]) -> None:
    """Create ``variables`` in ``group`` in their order, with the dimensions they need (those of a
    parent group are used, as xarray does), and write their values."""
    for v in variables:
        for dim, size in zip(v.dims, np.shape(v.values)):
            if not _visible_dimension(group, dim):
                group.createDimension(dim, size)  # a size of 0 makes it unlimited, as with xarray
    linked = {v.name: v.dims for v in variables if v.coordinate and v.dims != (v.name,)}
    unused = set(linked)
    for v in variables:
        values = np.asarray(v.values)
        if values.dtype.kind in "OU" and values.size:
            datatype, fill, values = str, None, values.astype(object)
        elif values.dtype.kind in "OU":  # empty text: xarray writes an empty f8 variable, without fill value
            datatype, fill = "f8", None
        else:
            datatype, fill = values.dtype, np.nan if values.dtype.kind == "f" else None
        variable = group.createVariable(v.name, datatype, v.dims, fill_value=fill)
        attrs = dict(v.attrs)
        if not v.coordinate:
            mine = sorted(name for name, dims in linked.items() if set(dims) <= set(v.dims))
            unused -= set(mine)
            if mine:
                attrs["coordinates"] = " ".join(mine)
        variable.setncatts(attrs)
        if values.size:
            variable[:] = values
    if unused:
        group.setncattr("coordinates", " ".join(sorted(unused)))


def _visible_dimension(group, dim: str) -> bool:
    """Whether ``dim`` is a dimension of ``group`` or of one of its parents."""
    while group is not None:
        if dim in group.dimensions:
            return True
        group = group.parent
    return False


def write_file(path: str | Path, variables: list[Variable], attrs: dict) -> None:
    """A NETCDF4 file of ``variables`` and global ``attrs`` at ``path``."""
    with netCDF4.Dataset(path, "w", format="NETCDF4") as file:
        write_variables(file, variables)
        file.setncatts(attrs)


@contextlib.contextmanager
def opened(path: str | Path, group: str | None = None, what: str = "mbds file"):
    """The open file at ``path`` (or its ``group``), values read unmasked as xarray decodes them
    (NaN where the fill value is NaN); ModelError when it is not a readable NetCDF file with that
    group and the variables asked for."""
    try:
        with netCDF4.Dataset(path, "r") as file:
            file.set_auto_maskandscale(False)
            yield file if group is None else file.groups[group]
    except (OSError, KeyError, ValueError) as exc:
        raise ModelError(f"not a readable {what} ({exc})", path) from None
