"""history.nc and wear.nc, written with netCDF4 alone (mbds.io.netcdf, so that campaign workers
need no xarray), are the files xarray wrote before: the same dataset for ``xarray.open_dataset``
(root and group ``final_state``) and the same layout on disk (dimensions, variables' types,
fill values, chunking, compression, attributes). The reference is written by xarray's
``to_netcdf`` from the same variables, as mbds wrote them until then."""

import dataclasses
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

import mbds.simulation.version_run as version_run
from mbds.data.history import (
    STATE_GROUP,
    HistoryStream,
    read_attributes,
    read_final_state,
    read_point_losses,
    state_variables,
    static_variables,
)
from mbds.errors import ModelError
from mbds.io.folder import read_model_files
from mbds.simulation.version_run import RunOptions, run_version
from mbds.simulation.versions import ensure_version
from mbds.wear.plan import plan_wear
from mbds.wear.version import (
    WEAR_FILE,
    create_next_version,
    wear_attributes,
    wear_variables,
)
from tests.examples import copy_example
from tests.wear.test_reshape import write_model
from tests.wear.test_version import WTC


def xarray_dataset(variables, attrs=None) -> xr.Dataset:
    """The dataset mbds built with xarray before: ``variables`` in their order, coordinates
    as coordinates."""
    ds = xr.Dataset(attrs=attrs)
    for v in variables:
        (ds.coords if v.coordinate else ds)[v.name] = (v.dims, v.values, v.attrs)
    return ds


class XarrayHistoryStream(HistoryStream):
    """history.nc as mbds wrote it before: the static variables and the group ``final_state``
    by xarray, the time variables and the summary by netCDF4 (as now)."""

    def __init__(self, path, header):
        super().__init__(path, header)
        self.file.close()
        xarray_dataset(static_variables(header)).to_netcdf(self.path, format="NETCDF4", engine="netcdf4")
        self.file = netCDF4.Dataset(self.path, "a")
        self.file.createDimension("time", None)

    def _close_with_state(self, record):
        self.file.close()
        state = xarray_dataset(state_variables(record.final_state, record.coordinate_units), {"Conventions": "CF-1.10"})
        state.to_netcdf(self.path, mode="a", group=STATE_GROUP, engine="netcdf4")


class BothStreams:
    """Every call goes to mbds's history.nc and to xarray's, written as ``reference/NNN.nc``."""

    def __init__(self, reference: Path):
        self.reference, self.headers = reference, []

    def __call__(self, path, header):
        self.headers.append(header)
        self.streams = (HistoryStream(path, header),
                        XarrayHistoryStream(self.reference / f"{header.version:03d}.nc", header))
        return self

    def append(self, series):
        for stream in self.streams:
            stream.append(series)

    def finish(self, record):
        for stream in self.streams:
            stream.finish(record)

    def close(self):
        for stream in self.streams:
            stream.close()


def layout(path: Path) -> list:
    """Everything netCDF4 tells of a file but the values: per group its attributes and
    dimensions, per variable its type, dimensions, filters, chunking, byte order and attributes."""
    def described(value):
        return (type(value).__name__, getattr(value, "dtype", None), repr(value))

    def group(g) -> list:
        out = [g.path, {k: described(g.getncattr(k)) for k in g.ncattrs()},
               [(d.name, d.size, d.isunlimited()) for d in g.dimensions.values()]]
        for v in g.variables.values():
            out.append((v.name, str(v.dtype), v.dimensions, v.filters(), v.chunking(), v.endian(),
                        {k: described(v.getncattr(k)) for k in v.ncattrs()}))
        return out + [group(sub) for sub in g.groups.values()]

    with netCDF4.Dataset(path) as file:
        return group(file)


def assert_same_file(ours: Path, theirs: Path, groups=(None,)):
    assert layout(ours) == layout(theirs)
    for name in groups:
        with xr.open_dataset(ours, group=name) as a, xr.open_dataset(theirs, group=name) as b:
            xr.testing.assert_identical(a, b)
            assert list(a.variables) == list(b.variables) and list(a.dims) == list(b.dims)


@pytest.fixture(scope="module")
def chain(tmp_path_factory):
    """2mass run for 0.1 s, its next version worn by the run's losses (mass1's watched points
    move up to 0.1 mm) and run on from where the first run ended; history.nc written by mbds and
    by xarray (``reference/``) at once."""
    tmp = tmp_path_factory.mktemp("layout")
    folder = copy_example("2mass", tmp / "2mass")
    (folder / "2mass.wtc").write_text("[mass1]\ncontactWatch = 0-2\ndirectionInside = 1\nmaxChange = 1e-4\n")
    reference = tmp / "reference"
    reference.mkdir()
    both = BothStreams(reference)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(version_run, "HistoryStream", both)
        run_version(ensure_version(folder, 0), RunOptions(duration=0.1))
        create_next_version(folder / "000", read_point_losses(folder / "000" / "history.nc"))
        run_version(folder / "001", RunOptions(duration=0.1, start_from=0))
    return folder, reference, both.headers[0]


@pytest.mark.parametrize("version", ["000", "001"])
def test_history_is_the_file_xarray_wrote(chain, version):
    folder, reference, _ = chain
    assert_same_file(folder / version / "history.nc", reference / f"{version}.nc", groups=(None, STATE_GROUP))


def test_final_state_reads_back_exactly(chain):
    folder, reference, _ = chain
    ours, attrs = read_final_state(folder / "000" / "history.nc")
    theirs, their_attrs = read_final_state(reference / "000.nc")
    for name in ("clock", "q", "u", "rng", "point_loss", "point_interval"):
        a, b = getattr(ours, name), getattr(theirs, name)
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), name
    with xr.open_dataset(reference / "000.nc") as ds:
        assert attrs == their_attrs == dict(ds.attrs)
        assert attrs["complete"] == 1
    losses = read_point_losses(folder / "000" / "history.nc")
    assert losses.keys() == {"mass1", "mass2"} and losses["mass1"].sum() > 0


def test_wear_record_is_the_file_xarray_wrote(chain, tmp_path):
    folder, _, _ = chain
    files = read_model_files(folder / "000")
    plan = plan_wear(files, read_point_losses(folder / "000" / "history.nc"), 0)
    assert [w.body for w in plan.bodies] == ["mass1"]
    xarray_dataset(wear_variables(plan, files), wear_attributes(plan, 0)).to_netcdf(tmp_path / "wear.nc")
    assert_same_file(folder / "001" / WEAR_FILE, tmp_path / "wear.nc")


def test_wear_record_with_constants_is_the_file_xarray_wrote(tmp_path):
    source = tmp_path / "model" / "000"
    write_model(source, WTC)
    losses = {"a": np.array([0.0, 2.0, 4.0, 1.0, 0.0, 0.0, 0.0, 0.0]), "b": np.zeros(8)}
    target = create_next_version(source, losses)
    files = read_model_files(source)
    plan = plan_wear(files, losses, 0)
    assert plan.constants_after
    xarray_dataset(wear_variables(plan, files), wear_attributes(plan, 0)).to_netcdf(tmp_path / "wear.nc")
    assert_same_file(target / WEAR_FILE, tmp_path / "wear.nc")


def test_text_empty_or_not_is_written_as_xarray_writes_it(chain, tmp_path):
    """A model without watches and with dependent coordinates: empty text variables become f8
    without fill value, as xarray writes them; the others variable-length strings."""
    header = dataclasses.replace(chain[2], watch_labels=[], watch_absolute=np.zeros(0, bool), watch_body=[],
                                 watch_points=[], dependent=["d1", "d2"], dependent_units=["m", "rad"])
    for stream in (HistoryStream(tmp_path / "ours.nc", header), XarrayHistoryStream(tmp_path / "theirs.nc", header)):
        stream.close()
    assert_same_file(tmp_path / "ours.nc", tmp_path / "theirs.nc")
    with netCDF4.Dataset(tmp_path / "ours.nc") as file:
        assert file["watch"].dtype == np.float64 and file["dependent"].dtype is str


def test_a_file_that_is_not_a_history_is_reported_with_its_path(chain, tmp_path):
    garbage = tmp_path / "000" / "history.nc"
    garbage.parent.mkdir()
    garbage.write_bytes(b"not a NetCDF file")
    with pytest.raises(ModelError, match=f"{garbage}: not a readable mbds history"):
        read_attributes(garbage)
    no_state = tmp_path / "001" / "history.nc"
    no_state.parent.mkdir()
    no_state.write_bytes((chain[0] / "001" / WEAR_FILE).read_bytes())  # a NetCDF file without final_state
    with pytest.raises(ModelError, match="not a readable mbds history"):
        read_final_state(no_state)
    with pytest.raises(ModelError, match="not a readable mbds history"):
        read_point_losses(no_state)
