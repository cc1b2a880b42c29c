"""The disk cache of generated modules, within and across processes."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numba
import pytest

from mbds.errors import ModelError
from mbds.expr import cache

# Compiles the test model with the cache directory of $MBDS_CACHE_DIR, calls every function once
# and reports numba's cache statistics.
CHILD = """
import json, sys, time
import numpy as np
import expr_models
from mbds.expr.codegen import compile_model
start = time.perf_counter()
compiled = compile_model(expr_models.expressions())
elapsed = time.perf_counter() - start
n, m, q, p = compiled.n, compiled.m, np.zeros(compiled.n), np.ones(compiled.n_parameters)
compiled.mass_matrix(q, 0.0, p, np.empty((n, n)))
compiled.h_vector(q, q, 0.0, p, np.empty(n))
compiled.dependent_state(q, q, q, 0.0, p, np.empty(m), np.empty(m), np.empty(m))
compiled.dependent_jacobian(q, q, 0.0, p, np.empty((m, n)), np.empty(m))
compiled.mechanical_energy(q, q, 0.0, p)
compiled.contact_law(0, 1.0, 1.0, p, np.empty(4))
stats = {
    name: [sum(d.stats.cache_hits.values()), sum(d.stats.cache_misses.values())]
    for name, d in compiled.dispatchers().items()
}
report = {"hash": compiled.source_hash, "path": str(compiled.source_path), "stats": stats, "seconds": elapsed}
json.dump(report, sys.stdout)
"""


def run_child(cache_dir: Path, hash_seed: str) -> dict:
    env = {
        **os.environ,
        "MBDS_CACHE_DIR": str(cache_dir),
        "PYTHONHASHSEED": hash_seed,
        "PYTHONPATH": os.pathsep.join([str(Path(__file__).parent), *sys.path]),
    }
    env.pop("NUMBA_CACHE_DIR", None)
    env.pop("MBDS_JIT_CACHE", None)
    done = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


@pytest.mark.skipif(numba.config.DISABLE_JIT, reason="numba's disk cache needs the JIT")
def test_second_process_compiles_nothing(tmp_path):
    cold = run_child(tmp_path, "11")
    warm = run_child(tmp_path, "22")
    assert cold["hash"] == warm["hash"]
    assert Path(cold["path"]).parent == tmp_path
    assert all(misses == 1 for _, misses in cold["stats"].values())
    assert all(hits >= 1 and misses == 0 for hits, misses in warm["stats"].values()), warm["stats"]


def test_store_writes_once(tmp_path):
    source = "X = 1\n"
    path = cache.store(source, tmp_path / "models")
    assert path == tmp_path / "models" / f"mbds_model_{cache.source_hash(source)}.py"
    assert path.read_text() == source
    os.utime(path, ns=(1_000_000_000, 1_000_000_000))
    assert cache.store(source, tmp_path / "models") == path
    assert path.stat().st_mtime_ns == 1_000_000_000  # identical file left alone
    path.write_text("X = 2\n")  # damaged
    cache.store(source, tmp_path / "models")
    assert path.read_text() == source
    assert sorted(p.name for p in path.parent.iterdir()) == ["__pycache__", path.name]  # no temporary files left


def test_the_cache_is_private_and_a_shared_one_is_refused(tmp_path):
    folder = tmp_path / "models"
    path = cache.store("X = 1\n", folder)
    assert folder.stat().st_mode & 0o777 == 0o700 and (folder / "__pycache__").stat().st_mode & 0o777 == 0o700
    assert path.stat().st_mode & 0o077 == 0
    folder.chmod(0o770)  # a group could leave code there
    with pytest.raises(ModelError, match="writable by other users"):
        cache.store("X = 1\n", folder)
    folder.chmod(0o700)
    (folder / "__pycache__").chmod(0o777)
    with pytest.raises(ModelError, match="writable by other users"):
        cache.store("X = 1\n", folder)
    (folder / "__pycache__").chmod(0o700)
    if os.getuid() == 0:  # only root can give a file away
        os.chown(path, 65534, -1)
        with pytest.raises(ModelError, match="belongs to another user"):
            cache.store("X = 1\n", folder)


def test_load_imports_once(tmp_path):
    path = cache.store("VALUE = 42\n", tmp_path)
    module = cache.load(path)
    assert module.VALUE == 42
    assert cache.load(path) is module


def test_default_cache_dir(monkeypatch, tmp_path):
    monkeypatch.setenv("MBDS_CACHE_DIR", str(tmp_path / "explicit"))
    assert cache.default_cache_dir() == tmp_path / "explicit"
    monkeypatch.delenv("MBDS_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache.default_cache_dir() == tmp_path / "xdg" / "mbds" / "models"
    monkeypatch.delenv("XDG_CACHE_HOME")
    if sys.platform.startswith("linux"):
        assert cache.default_cache_dir() == Path.home() / ".cache" / "mbds" / "models"
