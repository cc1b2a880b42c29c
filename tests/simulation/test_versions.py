"""Version folders: created whole from checked model files, found from a model or version path."""

from pathlib import Path

import pytest

from mbds.errors import ModelError
from mbds.io.folder import read_model_files
from mbds.simulation.versions import (
    ensure_version,
    existing_versions,
    job_settings,
    run_folder,
)
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def model(tmp_path):
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    return folder


def test_ensure_version_copies_the_model_files(model):
    version = ensure_version(model, 0)
    assert version == model / "000"
    assert read_model_files(version) == read_model_files(model)
    (version / "2mass.cns").write_text("c'gravity = 1.62\n")
    assert ensure_version(model, 0) == version  # an existing version is left as it is
    assert (version / "2mass.cns").read_text() == "c'gravity = 1.62\n"
    assert existing_versions(model) == [0]


def test_bad_model_files_create_no_version(model):
    (model / "2mass.hv").write_text("0\n-(c'gravity*b'mass1'm\n0\n")
    with pytest.raises(ModelError) as error:
        ensure_version(model, 0)
    assert "2mass.hv" in str(error.value)
    assert list(model.glob("*0*")) == []


def test_run_folder_rules(model):
    assert run_folder(model) == model / "000"
    with pytest.raises(ModelError, match="run this version first"):
        run_folder(model, start_from=0)
    assert existing_versions(model) == [0]
    (model / "000" / "history.nc").touch()
    assert run_folder(model, start_from=0) == model / "001"  # the next version
    (model / "001" / "history.nc").touch()
    (model / "001" / "2mass.cns").write_text("c'gravity = 1.62\n")
    assert run_folder(model / "002", start_from=1) == model / "002"  # files of the version started from
    assert (model / "002" / "2mass.cns").read_text() == "c'gravity = 1.62\n"
    with pytest.raises(ModelError, match="its own end"):
        run_folder(model / "002", start_from=2)
    with pytest.raises(ModelError, match="no version 007"):
        run_folder(model, start_from=7)
    with pytest.raises(ModelError, match="expected a model folder"):
        run_folder(model / "2mass.wld")


def test_job_settings_come_from_the_model_folder(model):
    assert job_settings(model, "2mass").max_minutes_for_job == 5
    (model / "2mass.job").unlink()
    assert job_settings(model, "2mass").max_lines_in_log == 0
