"""Whole models: writing one and reading it back gives the same model; copies keep the bytes."""

import warnings
from pathlib import Path

import pytest

from mbds.io.folder import (
    copy_model_files,
    read_model_files,
    version_name,
    version_number,
    write_model_files,
)

CAMPAIGNS = Path(__file__).resolve().parents[2] / "campaigns"


@pytest.mark.parametrize("name", ["2mass", "wearballs", "woodpecker"])
def test_written_model_reads_back_the_same(tmp_path, name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        files = read_model_files(CAMPAIGNS / name)
        world = write_model_files(files, tmp_path / name)
        again = read_model_files(world)
    assert again == files
    assert [p.name for p in again.paths()] == [p.name for p in files.paths()]


def test_copy_keeps_every_byte(tmp_path):
    files = read_model_files(CAMPAIGNS / "woodpecker")
    copy_model_files(files, tmp_path)
    for path in files.paths():
        assert (tmp_path / path.name).read_bytes() == path.read_bytes()
    assert not (tmp_path / "woodpecker.job").exists()  # only the model's files


def test_version_names():
    assert version_name(7) == "007" and version_number(Path("a/013")) == 13
    assert version_number(Path("a/13")) is None and version_number(Path("a/0133")) is None
