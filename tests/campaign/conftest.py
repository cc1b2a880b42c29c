"""Fixtures shared by the campaign tests."""

import os
import shutil
from pathlib import Path

import pytest

from mbds.model.load import load_model

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A private cache folder holding the 2mass model compiled (copied from the session's)."""
    folder = tmp_path / "cache"
    shared = Path(os.environ["MBDS_CACHE_DIR"])
    monkeypatch.setenv("MBDS_CACHE_DIR", str(shared))
    key = load_model(ROOT / "campaigns" / "2mass").compiled.source_hash  # compiled into the shared cache
    folder.mkdir(mode=0o700)
    (folder / "__pycache__").mkdir(mode=0o700)
    for path in shared.glob(f"*{key}*"):
        shutil.copy2(path, folder / path.name)
    for path in (shared / "__pycache__").glob(f"*{key}*"):
        shutil.copy2(path, folder / "__pycache__" / path.name)
    monkeypatch.setenv("MBDS_CACHE_DIR", str(folder))
    return folder
