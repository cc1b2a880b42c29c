"""Shared set-up of the physics tests: one compiled-model cache for the whole session."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session", autouse=True)
def model_cache(tmp_path_factory):
    """Compile models into one session-wide cache (not the user's): each model structure
    compiles once, models that differ only in constants or data reuse it."""
    with pytest.MonkeyPatch.context() as patch:
        path = tmp_path_factory.mktemp("mbds-cache")
        patch.setenv("MBDS_CACHE_DIR", str(path))
        yield path

