"""Fixtures shared by the campaign tests."""

import os
import shutil
from pathlib import Path

import pytest

from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import simulate

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A private cache folder holding the 2mass model compiled, its stepper included (copied from
    the session's cache after compiling it there)."""
    folder = tmp_path / "cache"
    shared = Path(os.environ["MBDS_CACHE_DIR"])
    monkeypatch.setenv("MBDS_CACHE_DIR", str(shared))
    model = load_model(ROOT / "campaigns" / "2mass")  # compiled into the shared cache
    simulate(model, RunSettings(break_time=0.0))  # and its stepper
    key = model.compiled.source_hash
    folder.mkdir(mode=0o700)
    (folder / "__pycache__").mkdir(mode=0o700)
    for path in shared.glob(f"*{key}*"):
        shutil.copy2(path, folder / path.name)
    for path in (shared / "__pycache__").glob(f"*{key}*"):
        shutil.copy2(path, folder / "__pycache__" / path.name)
    monkeypatch.setenv("MBDS_CACHE_DIR", str(folder))
    return folder
