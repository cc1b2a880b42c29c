"""Test-session settings: one disk cache of compiled models shared by every test.

Compiled model modules go to ``.mbds-cache/tests`` in the repository (ignored by git) unless
``MBDS_CACHE_DIR`` is set: tests never write to the user's own cache, and a model compiled by
one test is loaded from the cache by the others.
"""

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def pytest_configure(config):
    os.environ.setdefault("MBDS_CACHE_DIR", str(ROOT / ".mbds-cache" / "tests"))
