"""Datasets that stay in their files: a NetCDF file's root group described once, opened later
without touching the file until values are read.

A campaign holds hundreds or thousands of runs. Copying each run's history into one file costs
tens of milliseconds per run, and opening thousands of files costs as much again. Instead,
:func:`describe` reads a file's root group once (its dimensions, its variables' dimensions, types
and attributes, its attributes, and the values of its index coordinates and text variables); :func:`open_described`
turns such a description back into an ``xarray.Dataset`` whose variables are read from the file
only when their values are used, decoded as ``xarray.open_dataset`` decodes the files mbds
writes. Opening a
described dataset touches no file; :class:`Described` opens the runs of a campaign, sharing
what runs of one layout have in common, so a tree of a thousand runs opens in about a second.

The description is JSON text, apart from the values of one dimension's index coordinate (the
long ``time`` of a history), which :func:`describe` returns as an array to be stored beside it.
"""

from __future__ import annotations

import functools
import json
import re
from pathlib import Path
from typing import NamedTuple

import netCDF4
import numpy as np
import xarray as xr
from xarray.backends import BackendArray
from xarray.core import indexing
from xarray.indexes import Index, PandasIndex

from mbds.errors import ModelError

_JSON = json.JSONDecoder()
_SPACE = re.compile(r"\s*")
_SHARED = ("variables", "index")
"""The parts of a description that runs of one layout share (see ``Described._parsed``)."""


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
    return Described().open(path, description, long_values)


class Described:
    """Opens many described datasets, sharing what files of one layout have in common.

    The runs of a campaign mostly have one layout: the same variables, names and attributes,
    differing in their sample times, their file and their attributes. The first dataset of a
    layout is built as :func:`open_described` builds it; each further one is put together from
    it without xarray's checks: its indexes are shared, its variables copied (each dataset has
    variables of its own), and only its file's variables and its long index are made anew (about
    half a millisecond instead of 2 ms)."""

    def __init__(self):
        self._layouts: list[_Layout] = []
        self._long_indexes: dict[tuple, tuple[xr.Variable, Index]] = {}
        self._known: dict[str, dict[str, dict]] = {}  # key -> JSON text of a value -> the value

    def open(self, path: str | Path, description: str, long_values: np.ndarray) -> xr.Dataset:
        """The dataset of the file ``path`` that ``description`` describes (see :func:`open_described`)."""
        header = self._parsed(description)
        path = Path(path)
        long = header["long_index"]
        key = _LayoutKey(header["variables"], header["index"], long, header["attrs"].get("coordinates", ""),
                         {d: n for d, n in header["dims"].items() if d != long})
        layout = next((layout for layout in self._layouts if layout.key == key), None)  # a few at most
        if layout is None:
            layout = _Layout.of(key, _built(path, header, long_values), header)
            self._layouts.append(layout)
        variables = {name: variable.copy(deep=False) for name, variable in layout.variables.items()}
        for name, dims, attrs, encoding, dtype in layout.in_file:
            shape = tuple(header["dims"][d] for d in dims)
            lazy = indexing.LazilyIndexedArray(_FileVariable(path, name, shape, dtype), _whole(len(dims)))
            variables[name] = xr.Variable(dims, lazy, attrs, encoding, fastpath=True)  # lazy: taken as it is
        sizes, indexes = dict(layout.sizes), dict(layout.indexes)
        if long in sizes:
            sizes[long] = header["dims"][long]
        if long in indexes:
            variables[long], indexes[long] = self._long_index(layout.variables[long], long_values)
        attrs = {key: value for key, value in header["attrs"].items() if key != "coordinates"}
        # xarray's constructor would check again what the layout's first dataset was checked for
        return xr.Dataset._construct_direct(variables, set(layout.coord_names), sizes, attrs, indexes)

    def _parsed(self, description: str) -> dict:
        """The description read from its JSON text. Its variables and index values, half of the
        text and the same for runs of one layout, are read once: where the text of a layout's
        value stands in a description, the value read before is taken (a JSON object's text ends
        where the object does), which also makes comparing layouts an identity check."""
        if not description.startswith("{"):
            return json.loads(description)  # json says what is wrong
        header, at = {}, _past(description, 0, "{")
        while not description.startswith("}", at):
            key, at = _JSON.raw_decode(description, at)
            at = _past(description, at, ":")
            known = self._known.setdefault(key, {}) if key in _SHARED else {}
            text = next((text for text in known if description.startswith(text, at)), None)
            if text is None:
                header[key], end = _JSON.raw_decode(description, at)
                if key in _SHARED:
                    known[description[at:end]] = header[key]
            else:
                header[key], end = known[text], at + len(text)
            at = _SPACE.match(description, end).end()
            if not description.startswith("}", at):
                at = _past(description, at, ",")
        return header

    def _long_index(self, variable: xr.Variable, values: np.ndarray) -> tuple[xr.Variable, Index]:
        """The long index coordinate (the sample times) with ``values``, one per distinct values."""
        values = np.asarray(values, dtype=variable.dtype)
        key = (values.dtype.str, values.tobytes())
        if key not in self._long_indexes:
            name = variable.dims[0]
            index = PandasIndex(values, name)
            fresh = xr.Variable(variable.dims, values, variable.attrs, variable.encoding)
            self._long_indexes[key] = (index.create_variables({name: fresh})[name], index)
        return self._long_indexes[key]


class _LayoutKey(NamedTuple):
    """What makes datasets of one layout: their description but for the attributes and the length
    of the long index."""

    variables: dict
    index: dict
    long_index: str
    coordinates: str
    sizes: dict


class _Layout(NamedTuple):
    """What the datasets of one layout share: the variables not read from the file, with their
    indexes, coordinate names and sizes, and how to make the variables of the file."""

    key: _LayoutKey
    variables: dict[str, xr.Variable]
    indexes: dict[str, Index]
    coord_names: frozenset[str]
    sizes: dict[str, int]
    in_file: tuple[tuple[str, tuple[str, ...], dict, dict, np.dtype], ...]

    @classmethod
    def of(cls, key: _LayoutKey, first: xr.Dataset, header: dict) -> _Layout:
        """The layout of ``first``, the dataset built from ``header`` (a copy of its variables is kept)."""
        first = first.copy(deep=False)
        in_file = tuple((name, first[name].dims, first[name].attrs, first[name].encoding, first[name].dtype)
                        for name in _in_file(header))
        return cls(key, dict(first.variables), dict(first.xindexes), frozenset(first.coords), dict(first.sizes),
                   in_file)


@functools.cache
def _whole(ndim: int) -> indexing.BasicIndexer:
    """The key that takes the whole of an array of ``ndim`` dimensions (made once per ``ndim``)."""
    return indexing.BasicIndexer((slice(None),) * ndim)


def _in_file(header: dict) -> list[str]:
    """The variables of a description whose values stay in the file."""
    long = header["long_index"]
    return [name for name, spec in header["variables"].items()
            if not (name == long and spec["dims"] == [name]) and name not in header["index"]]


def _built(path: Path, header: dict, long_values: np.ndarray) -> xr.Dataset:
    """The dataset ``header`` describes, built and checked by xarray's constructor."""
    variables, coordinates, in_file = {}, set(), set(_in_file(header))
    for name, spec in header["variables"].items():
        dims, attributes = tuple(spec["dims"]), dict(spec["attrs"])
        fill = attributes.pop("_FillValue", None)
        coordinates.update(attributes.pop("coordinates", "").split())
        if name not in in_file and name in header["index"]:
            data = np.asarray(header["index"][name], dtype=spec["dtype"] if spec["dtype"] != "object" else str)
        elif name not in in_file:
            data = np.asarray(long_values, dtype=spec["dtype"])
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


def _past(text: str, at: int, mark: str) -> int:
    """Where the JSON ``text`` goes on after the ``mark`` (with spaces around it) at ``at``."""
    at = _SPACE.match(text, at).end()
    if not text.startswith(mark, at):
        raise json.JSONDecodeError(f"expected {mark!r}", text, at)
    return _SPACE.match(text, at + 1).end()


def _plain(value):
    """A NetCDF attribute value as JSON can hold it."""
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value
