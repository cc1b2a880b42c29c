"""Test-session settings: the tests share the compiled-model cache that mbds itself uses.

Unless ``MBDS_CACHE_DIR`` is set, the tests compile into the user's default cache
(mbds.expr.cache.default_cache_dir), the one README.md's set-up command has just filled with the
example models: a model compiled there, or by one test, is loaded by the others instead of being
compiled again. Entries are keyed by the hash of their generated source, so sharing is safe; tests
that need a cache of their own set ``MBDS_CACHE_DIR`` themselves.
"""

import os

from mbds.expr.cache import default_cache_dir


def pytest_configure(config):
    os.environ.setdefault("MBDS_CACHE_DIR", str(default_cache_dir()))
