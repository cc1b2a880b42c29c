"""Creating the next version: copies, worn shapes, constants and the record of changes."""

import os

import numpy as np
import pytest
import xarray as xr

from mbds.errors import ModelError
from mbds.io.folder import read_model_files
from mbds.wear.version import WEAR_FILE, create_next_version
from tests.wear.test_reshape import SQUARE, write_model

WTC = "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 0.01\n[changeConstants]\nconstant = c'k\nchange = 0.5\n"


def test_next_version_has_worn_shape_constants_and_record(tmp_path):
    source = tmp_path / "model" / "000"
    write_model(source, WTC)
    (source / "m.hv").write_text("0 % a comment the copy keeps\n")
    (source / "history.nc").write_bytes(b"not a model file")
    loss = np.array([0.0, 2.0, 4.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    target = create_next_version(source, {"a": loss, "b": np.zeros(8)})
    assert target == tmp_path / "model" / "001"
    assert (target / "m.hv").read_text() == "0 % a comment the copy keeps\n"
    assert not (target / "history.nc").exists()
    new = read_model_files(target)
    a = next(s for b, s in zip(new.bodies, new.shapes) if b.main.name == "a")
    b = next(s for b, s in zip(new.bodies, new.shapes) if b.main.name == "b")
    moved = np.linalg.norm(a.points[:-1] - np.array(SQUARE, dtype=float), axis=1)
    assert moved.max() == pytest.approx(0.01) and moved.argmax() == 2
    assert np.array_equal(b.points[:-1], np.array(SQUARE, dtype=float))
    assert new.constants.values == {"k": 1.5, "m": 2.0}
    record = xr.open_dataset(target / WEAR_FILE)
    assert record.attrs["source_version"] == "000" and record.attrs["new_version"] == "001"
    assert record["a_displacement"].values == pytest.approx(0.01 * loss / 4.0)
    assert record["a_loss"].attrs["units"] == "J"
    assert float(record["constant_after"].sel(constant="k")) == 1.5
    record.close()


def test_existing_next_version_is_not_overwritten(tmp_path):
    source = tmp_path / "model" / "000"
    write_model(source, WTC)
    (tmp_path / "model" / "001").mkdir()
    with pytest.raises(ModelError, match="version 001 exists already"):
        create_next_version(source, {"a": np.zeros(8)})


def test_failed_reshaping_leaves_no_folder(tmp_path):
    source = tmp_path / "model" / "000"
    write_model(source, "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 1.5\n")
    with pytest.raises(ModelError, match="would break its shape"):
        create_next_version(source, {"a": np.array([0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0])})
    assert sorted(p.name for p in (tmp_path / "model").iterdir()) == ["000"]


def test_the_next_version_gets_the_umasks_permissions(tmp_path):
    source = tmp_path / "model" / "000"
    write_model(source, WTC)
    previous = os.umask(0o027)  # a group-shared project
    try:
        target = create_next_version(source, {"a": np.zeros(8), "b": np.zeros(8)})
    finally:
        os.umask(previous)
    assert target.stat().st_mode & 0o777 == 0o750
    assert all(p.stat().st_mode & 0o777 == 0o640 for p in target.iterdir() if p.suffix == ".cns")
