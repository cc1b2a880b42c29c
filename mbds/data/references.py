"""Datasets that stay in their files: a NetCDF file's root group described once, opened later
without touching the file until values are read.

A campaign holds hundreds or thousands of runs. Copying each run's history into one file costs
tens of milliseconds per run, and opening thousands of files costs as much again. Instead,
:func:`describe` reads a file's root group once (its dimensions, its variables' dimensions, types
and attributes, its attributes, and the values of its index coordinates and text variables); :func:`open_described`
turns such a description back into an ``xarray.Dataset`` whose variables are read from the file
only when their values are used, decoded as ``xarray.open_dataset`` decodes the files mbds
writes. Opening a
described dataset touches no file, so a tree of a thousand runs opens in a fraction of a second.

The description is JSON text, apart from the values of one dimension's index coordinate (the
long ``time`` of a history), which :func:`describe` returns as an array to be stored beside it.
"""

from __future__ import annotations

import json
from pathlib import Path

import netCDF4
import numpy as np
import xarray as xr
from xarray.backends import BackendArray
from xarray.core import indexing

from mbds.errors import ModelError


def describe(path: str | Path, long_index: str = "time", read: tuple[str, ...] = ()) -> tuple[str, np.ndarray, dict]:
    """The description of the root group of the NetCDF file ``path`` (JSON text), the values of
    its ``long_index`` coordinate (empty when it has none), and the raw values of the variables
    named in ``read`` (name -> (dimensions, values, attributes))."""
    variables, index, values, long_values = {}, {}, {}, np.zeros(0)
    with netCDF4.Dataset(path) as ds:
        ds.set_auto_maskandscale(False)
        for name, variable in ds.variables.items():
            attributes = {key: _plain(variable.getncattr(key)) for key in variable.ncattrs()}
            text = variable.dtype is str
            variables[name] = {"dims": list(variable.dimensions), "dtype": "object" if text else variable.dtype.str,
                               "attrs": attributes}
            if variable.dimensions == (name,) and name == long_index:
                long_values = np.asarray(variable[...])
            elif variable.dimensions == (name,) or text:  # index coordinates and names: small
                index[name] = [_plain(v) for v in np.asarray(variable[...]).tolist()]
            if name in read:
                values[name] = (variable.dimensions, np.asarray(variable[...]), attributes)
        header = {
            "dims": {name: len(dimension) for name, dimension in ds.dimensions.items()},
            "variables": variables,
            "index": index,
            "long_index": long_index,
            "attrs": {key: _plain(ds.getncattr(key)) for key in ds.ncattrs()},
        }
    return json.dumps(header), long_values, values


def open_described(path: str | Path, description: str, long_values: np.ndarray) -> xr.Dataset:
    """The dataset that :func:`describe` described, its variables read from ``path`` when used.

    Decoded as mbds writes its files: ``_FillValue`` (NaN for floats) goes to the encoding and
    the variables named in ``coordinates`` attributes (of variables or of the file) become
    coordinates, as
    ``xarray.open_dataset`` makes them."""
    header = json.loads(description)
    path = Path(path)
    variables, coordinates = {}, set()
    for name, spec in header["variables"].items():
        dims, attributes = tuple(spec["dims"]), dict(spec["attrs"])
        fill = attributes.pop("_FillValue", None)
        coordinates.update(attributes.pop("coordinates", "").split())
        if name == header["long_index"] and dims == (name,):
            data = np.asarray(long_values, dtype=spec["dtype"])
        elif name in header["index"]:
            data = np.asarray(header["index"][name], dtype=spec["dtype"] if spec["dtype"] != "object" else str)
        else:
            if fill is not None and not (isinstance(fill, float) and np.isnan(fill)):
                raise ModelError(f"variable {name} has a fill value other than NaN; mbds did not write it", path)
            shape = tuple(header["dims"][d] for d in dims)
            data = indexing.LazilyIndexedArray(_FileVariable(path, name, shape, np.dtype(spec["dtype"])))
        encoding = {} if fill is None else {"_FillValue": fill}
        variables[name] = xr.Variable(dims, data, attributes, encoding)
    attrs = dict(header["attrs"])
    coordinates.update(attrs.pop("coordinates", "").split())
    coordinates |= {name for name, v in variables.items() if v.dims == (name,)}
    data_vars = {n: v for n, v in variables.items() if n not in coordinates}
    coords = {n: v for n, v in variables.items() if n in coordinates}
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


class _FileVariable(BackendArray):
    """A variable of a NetCDF file's root group, read (undecoded) when indexed."""

    def __init__(self, path: Path, name: str, shape: tuple[int, ...], dtype: np.dtype):
        self.path, self.name, self.shape, self.dtype = path, name, shape, dtype

    def __getitem__(self, key):
        return indexing.explicit_indexing_adapter(key, self.shape, indexing.IndexingSupport.BASIC, self._read)

    def _read(self, key: tuple) -> np.ndarray:
        try:
            with netCDF4.Dataset(self.path) as ds:
                variable = ds.variables[self.name]
                variable.set_auto_maskandscale(False)
                return np.asarray(variable[key], dtype=self.dtype)
        except (OSError, KeyError) as exc:
            raise ModelError(f"cannot read {self.name} from this run file ({exc}); collect the campaign again "
                             "if its runs were moved or run again", self.path) from None


def _plain(value):
    """A NetCDF attribute value as JSON can hold it."""
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value
