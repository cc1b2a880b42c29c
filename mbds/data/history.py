"""``history.nc``: the samples of one run as a CF-style NetCDF file, and the exact state the run
ended in (group ``final_state``) for continuing it. The schema is documented in docs/outputs.md.

Written and read with netCDF4 alone (:mod:`mbds.io.netcdf`): a campaign's worker ranks do not
import xarray; ``xarray.open_dataset`` reads the file as if xarray had written it."""

from __future__ import annotations

import contextlib
from pathlib import Path

import netCDF4
import numpy as np

from mbds._version import version as mbds_version
from mbds.data.record import RunHeader, RunRecord, SampleSeries, empty_series
from mbds.data.run_result import RunState
from mbds.errors import ModelError
from mbds.io.netcdf import Variable, opened, write_variables
from mbds.kernel import layout as K

FILE_NAME = "history.nc"
STATE_GROUP = "final_state"
COMPRESSED = {"zlib": True, "complevel": 1, "shuffle": False}
"""Deflate level 1, without byte shuffling, for the time variables: the watch tables are mostly
zeros, which this packs as small as level 4 with shuffling at half the cost of writing and reading
(and the unused end of a run's last chunk packs to nothing)."""
CLOCK_ENTRIES = (
    "time next_step next_sample steps impacts rejected_steps lost_work driver_work max_penetration "
    "lcp_failures over_penetrations last_penetration"
)


CHUNK_VALUES = 32768
"""Values per chunk of a time variable on disk (256 KiB): 64 to 4096 samples, fewer the more
columns it has, so that the unused end of the last chunk of a short run stays small."""


CHUNK_CACHE = 1 << 20
"""Bytes of HDF5's chunk cache per time variable (4 chunks). The library's default, tens of MB
per variable, adds up to gigabytes for a model with many variables and a long run."""


class HistoryStream:
    """``history.nc`` written while the run goes: :meth:`append` adds samples to its time
    variables, :meth:`finish` its summary, attributes and final state. Write it in a temporary
    file (see :func:`mbds.io.text.atomic_path`): until then the file is incomplete."""

    def __init__(self, path: str | Path, header: RunHeader):
        self.path, self.header = Path(path), header
        self.file = netCDF4.Dataset(self.path, "w", format="NETCDF4")
        write_variables(self.file, static_variables(header))
        self.file.createDimension("time", None)
        self.variables: dict[str, netCDF4.Variable] = {}
        self.count = 0

    def append(self, series: SampleSeries) -> None:
        """Add ``series`` after the samples so far."""
        count = len(series.time)
        for name, (dims, values, attributes) in series_variables(self.header, series).items():
            variable = self.variables.get(name) or self._create(name, dims, values, attributes)
            variable[self.count : self.count + count] = values
        self.count += count

    def finish(self, record: RunRecord) -> None:
        """Write what the run ended with: the per-point losses, the attributes and the exact
        final state (group ``final_state``); the file is then complete."""
        if not self.variables:  # no sample at all: the time variables exist, empty
            self.append(empty_series(record))
        write_variables(self.file, [
            Variable("point_lost_work", ("point",), record.point_lost_work,
                     _cf("mechanical energy lost at the point in this run", "J")),
            Variable("point_lost_work_smoothed", ("point",), record.point_lost_work_smoothed,
                     _cf("point_lost_work smoothed by smoothWorkLeftRight", "J",
                         half_width=record.options["smooth_work_left_right"])),
        ])
        self.file.setncatts(_attributes(record))
        self._close_with_state(record)

    def _close_with_state(self, record: RunRecord) -> None:
        """Write the group ``final_state`` and close the file."""
        state = self.file.createGroup(STATE_GROUP)
        state.setncatts({"Conventions": "CF-1.10"})
        write_variables(state, state_variables(record.final_state, record.coordinate_units))
        self.file.close()

    def close(self) -> None:
        """Release the file (after :meth:`finish`, or when the run failed)."""
        if self.file.isopen():
            self.file.close()

    def _create(self, name: str, dims: tuple[str, ...], values: np.ndarray, attributes: dict) -> netCDF4.Variable:
        columns = int(np.prod(values.shape[1:]))
        shape = (min(max(CHUNK_VALUES // max(columns, 1), 64), 4096), *values.shape[1:])
        options = {"chunksizes": shape, **COMPRESSED} if all(shape) else {}
        fill = False if name == "time" else np.nan  # (as xarray writes an index coordinate)
        variable = self.file.createVariable(name, "f8", dims, fill_value=fill, **options)
        variable.set_var_chunk_cache(size=CHUNK_CACHE)
        variable.setncatts(attributes)
        self.variables[name] = variable
        return variable


def series_variables(header: RunHeader, s: SampleSeries) -> dict[str, tuple[tuple[str, ...], np.ndarray, dict]]:
    """The time-dependent variables of ``history.nc`` (dimensions, values, attributes) for the
    samples ``s``; ``time`` first."""
    tw, ts = ("time", "watch"), ("time", "coordinate")
    kind, imp_units = ("force", "N") if header.force else ("impulse", "N s")
    since = "since the run's start"
    out = {
        "time": (("time",), s.time, _cf("time", "s", axis="T")),
        "q": (ts, s.q, _per_coordinate("generalized coordinates", "coordinate_unit")),
        "qd": (ts, s.qd, _per_coordinate("generalized velocities", "velocity_unit")),
        "qdd": (ts, s.qdd, _per_coordinate("generalized accelerations", "acceleration_unit")),
        "dependent_q": (("time", "dependent"), s.dependent_position,
                        _per_coordinate("dependent coordinates (.dc)", "dependent_unit")),
        "body_x": (("time", "body"), s.pose[:, :, 0], _cf("x of the body frame's origin", "m")),
        "body_y": (("time", "body"), s.pose[:, :, 1], _cf("y of the body frame's origin", "m")),
        "body_angle": (("time", "body"), s.pose[:, :, 2], _cf("rotation Rz of the body frame", "rad")),
        "mechanical_energy": (("time",), s.energy, _cf("mechanical energy (.me expression)", "J")),
        "lost_work": (("time",), s.lost_work, _cf(f"mechanical energy lost at contacts {since}", "J")),
        "driver_work": (("time",), s.driver_work, _cf(f"work of rheonomic drivers {since}", "J")),
    }
    for direction, values in s.watches.impulse.items():
        out[f"impulse_{direction}"] = (tw, values, _cf(f"{direction} {kind} at the watch per sample interval", imp_units))
    if s.watches.work is not None:
        what = since if header.options["cumulative_work"] else "per sample interval"
        out["work"] = (tw, s.watches.work, _cf(f"mechanical energy lost at the watch {what}", "J"))
    if s.watches.angle is not None:
        out["angle"] = (tw, s.watches.angle, _cf("angle of the last contact normal to the x axis", "rad"))
    if s.watches.t_div_n is not None:
        out["t_div_n"] = (tw, s.watches.t_div_n, _cf("running ratio of summed tangential to normal impulse", "1"))
    if s.watches.temperature is not None:
        out["temperature"] = (tw, s.watches.temperature, _cf("contact temperature of the hottest watched point",
                                                               "degree_Celsius"))
    return out


def static_variables(h: RunHeader) -> list[Variable]:
    """The variables of ``history.nc`` that do not depend on time: names, units, bodies, shape
    points and watches (the attributes come with the summary)."""
    frames = ["xy" if a else "nt" for a in h.watch_absolute]
    data = [
        Variable("shape_x", ("point",), h.shape[:, 0], _cf("shape point x in the body frame", "m")),
        Variable("shape_y", ("point",), h.shape[:, 1], _cf("shape point y in the body frame", "m")),
    ]
    coords = {
        "coordinate": ("coordinate", _text(h.coordinates), _named("generalized coordinate")),
        "coordinate_unit": ("coordinate", _text(h.coordinate_units), _named("UDUNITS unit of the coordinate")),
        "velocity_unit": ("coordinate", _text([_rate(u, 1) for u in h.coordinate_units]),
                          _named("UDUNITS unit of the coordinate's velocity")),
        "acceleration_unit": ("coordinate", _text([_rate(u, 2) for u in h.coordinate_units]),
                              _named("UDUNITS unit of the coordinate's acceleration")),
        "dependent": ("dependent", _text(h.dependent), _named("dependent coordinate")),
        "dependent_unit": ("dependent", _text(h.dependent_units), _named("UDUNITS unit of the dependent coordinate")),
        "watch": ("watch", _text(h.watch_labels), _named("watch label")),
        "watch_body": ("watch", _text(h.watch_body), _named("body of the watched points")),
        "watch_first_point": ("watch", np.array([p[0] for p in h.watch_points], dtype=np.int32).reshape(-1),
                              _named("first watched point (point_number)")),
        "watch_last_point": ("watch", np.array([p[1] for p in h.watch_points], dtype=np.int32).reshape(-1),
                             _named("last watched point (point_number)")),
        "watch_frame": ("watch", _text(frames), _named("frame of the legacy impulse columns (nt or xy)")),
        "body": ("body", _text(h.bodies), _named("body name")),
        "body_kind": ("body", _text(h.body_kind), _named("moving, fixed or virtual")),
        "body_color": (("body", "rgb"), h.body_color, _named("RGBColor of the body (red, green, blue; 0-1)")),
        "point_body": ("point", h.point_body.astype(np.int32), _named("index of the point's body")),
        "point_body_name": ("point", _text([h.bodies[i] for i in h.point_body]), _named("name of the point's body")),
        "point_number": ("point", h.point_number.astype(np.int32), _named("point number in its body's shape")),
    }
    return data + [Variable(name, _dims(dims), values, attrs, coordinate=True)
                   for name, (dims, values, attrs) in coords.items()]


def _dims(dims: str | tuple[str, ...]) -> tuple[str, ...]:
    return (dims,) if isinstance(dims, str) else dims


def _cf(long_name: str, units: str, **extra) -> dict:
    return {"long_name": long_name, "units": units, **extra}


def _per_coordinate(long_name: str, unit_variable: str) -> dict:
    """Attributes of a variable whose columns have different units: they are in ``unit_variable``."""
    return {"long_name": long_name, "ancillary_variables": unit_variable,
            "comment": f"each column's UDUNITS unit is in {unit_variable}"}


def _rate(unit: str, order: int) -> str:
    """The unit of the ``order``-th time derivative of a coordinate in ``unit``."""
    return f"{unit} s-{order}" if unit != "1" else f"s-{order}"


def _named(long_name: str) -> dict:
    return {"long_name": long_name}


def _text(values: list[str]) -> np.ndarray:
    return np.array(values, dtype=object)


def _attributes(r: RunRecord) -> dict:
    attrs = {
        "Conventions": "CF-1.10",
        "title": f"mbds run of model {r.model}, version {r.version:03d}",
        "mbds_version": mbds_version(),
        "model": r.model,
        "version": r.version,
        "seed": r.seed,
        "continued_from": -1 if r.continued_from is None else r.continued_from,
        "start_time": r.start_time,
        "end_time": r.end_time,
        "break_time": r.break_time,
        "complete": int(r.complete),
        "stop_reason": r.stopped,
        "start_energy": r.start_energy,
        "end_energy": r.end_energy,
        "run_lost_work": r.run_lost_work,
        "run_driver_work": r.run_driver_work,
        "energy_residual": r.energy_residual,
        "max_penetration": r.max_penetration,
        "wall_time": r.wall_time,
        **r.counters,
        **{f"watch_{k}": v for k, v in r.options.items()},
        "input_files": " ".join(r.inputs),
    }
    attrs.update({f"input_{name.replace('/', ':')}": text for name, text in r.inputs.items()})
    return attrs


def state_variables(state: RunState, units: list[str]) -> list[Variable]:
    """The variables of the ``final_state`` group: the kernel state, exactly; ``units`` of the
    coordinates."""
    columns = "impN impT impX impY work angle"
    variables = {
        "clock": ("clock_entry", state.clock, {**_named("kernel clock and counters"), "entries": CLOCK_ENTRIES}),
        "q": ("coordinate", state.q, _per_coordinate("generalized coordinates", "coordinate_unit")),
        "qd": ("coordinate", state.u, _per_coordinate("generalized velocities", "velocity_unit")),
        "coordinate_unit": ("coordinate", _text(units), _named("UDUNITS unit of the coordinate")),
        "velocity_unit": ("coordinate", _text([_rate(u, 1) for u in units]), _named("UDUNITS unit of the velocity")),
        "rng": ("rng_word", state.rng, _named("state of the generator of lexicographic tolerances")),
        "point_loss": ("kernel_point", state.point_loss, _cf("lost work per kernel point (closing points too)", "J")),
        "point_interval": (("kernel_point", "point_column"), state.point_interval,
                           {**_named("per-point sums since the last sample"), "columns": columns}),
    }
    return [Variable(name, _dims(dims), values, attrs) for name, (dims, values, attrs) in variables.items()]


def read_final_state(path: str | Path) -> tuple[RunState, dict]:
    """The state a run ended in and the attributes of its ``history.nc``; ModelError when the
    file is missing or not a complete mbds history."""
    with _opened(path, STATE_GROUP) as ds:
        values = {name: ds.variables[name][:] for name in ("clock", "q", "qd", "rng", "point_loss", "point_interval")}
    state = RunState(clock=values["clock"], q=values["q"], u=values["qd"], rng=values["rng"].astype(np.uint64),
                     point_loss=values["point_loss"], point_interval=values["point_interval"])
    if state.point_interval.shape[1:] == (K.TEMP,):  # written before contact temperatures: none
        state.point_interval = np.column_stack([state.point_interval, np.full(len(state.point_interval), np.nan)])
    if state.clock.shape != (K.CLOCK,) or state.point_interval.shape[1:] != (K.POINT_COLUMNS,):
        raise ModelError("written by an incompatible mbds version (its state has another layout)", path)
    return state, read_attributes(path)


def read_attributes(path: str | Path) -> dict:
    """The global attributes of a ``history.nc`` (``complete``, ``end_time``, ...), as xarray
    shows them (without ``coordinates``, which names coordinate variables)."""
    with _opened(path) as ds:
        return {name: ds.getncattr(name) for name in ds.ncattrs() if name != "coordinates"}


def read_point_losses(path: str | Path) -> dict[str, np.ndarray]:
    """The lost work (J) at each distinct shape point of each body during the run of a
    ``history.nc``, by body name, in point order."""
    with _opened(path) as ds:
        bodies = [str(name) for name in ds.variables["body"][:]]
        owner, number = ds.variables["point_body"][:], ds.variables["point_number"][:]
        loss = ds.variables["point_lost_work"][:]
    losses = {}
    for index, name in enumerate(bodies):
        mine = owner == index
        losses[name] = np.zeros(int(number[mine].max(initial=-1)) + 1)
        losses[name][number[mine]] = loss[mine]
    return losses


@contextlib.contextmanager
def _opened(path: str | Path, group: str | None = None):
    """``history.nc`` open (or one of its groups: see :func:`mbds.io.netcdf.opened`);
    ModelError when the file is missing or not an mbds history."""
    path = Path(path)
    if not path.is_file():
        raise ModelError(f"no {FILE_NAME} here: run this version first", path.parent)
    with opened(path, group, "mbds history") as ds:
        yield ds
