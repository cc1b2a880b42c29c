"""A model's compiled module, as it lies in the compile cache: loading it, and knowing whether
the cache holds its machine code for this environment. Neither needs sympy, which only
generating a module's text does (:mod:`mbds.expr.codegen`).

- :func:`load_compiled`: the :class:`CompiledModel` of the module at a path.
- :func:`cached_module`: the compiled module of structure ``key`` (the hash of its text), loaded
  from the cache when the cache holds it compiled for this environment, else None.
- :func:`mark_compiled` / :func:`compiled`: ``<cache>/mbds_model_<key>.ready``, written once a
  process has run the structure's stepper from this cache, holding the versions of numba and
  Python, the machine it ran on and the names of numba's index files of the module; it counts
  only while these match this process's, the index files are there, and it is newer than the
  module file (numba keys its machine code on that file's time).
"""

from __future__ import annotations

import functools
import json
import platform
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from mbds.expr import cache

GENERATED_FUNCTIONS = ("mass_matrix", "h_vector", "dependent_state", "dependent_jacobian", "mechanical_energy",
                       "contact_law")
"""The six functions of a generated module (see :mod:`mbds.expr.codegen`)."""
READY_SUFFIX = ".ready"


@dataclass(frozen=True)
class CompiledModel:
    """The compiled functions of one model (see :mod:`mbds.expr.codegen` for their signatures)."""

    mass_matrix: Callable
    h_vector: Callable
    dependent_state: Callable
    dependent_jacobian: Callable
    mechanical_energy: Callable
    contact_law: Callable
    advance: Callable  # the kernel's time stepper bound to these functions
    n: int  # generalized coordinates
    m: int  # dependent coordinates
    n_contact_laws: int
    n_parameters: int  # length of p
    source_path: Path
    source_hash: str

    def dispatchers(self) -> dict[str, Callable]:
        """The six numba dispatchers by name."""
        return {name: getattr(self, name) for name in GENERATED_FUNCTIONS}


def load_compiled(path: Path, key: str) -> CompiledModel:
    """The compiled model of the module at ``path`` (of structure ``key``), imported once per
    process."""
    from mbds.kernel.function_table import address_table  # (numba: only where a model is loaded)
    from mbds.kernel.layout import MODEL_FUNCTIONS
    from mbds.kernel.stepper import advance  # (compiled or loaded from the kernel's cache on its first call)

    module = cache.load(path)
    return CompiledModel(
        **{name: getattr(module, name) for name in GENERATED_FUNCTIONS},
        advance=functools.partial(advance, address_table(module, MODEL_FUNCTIONS)),
        n=module.N,
        m=module.M,
        n_contact_laws=module.CONTACT_LAWS,
        n_parameters=module.PARAMETERS,
        source_path=path,
        source_hash=key,
    )


def cached_module(key: str) -> CompiledModel | None:
    """The compiled model of structure ``key`` from the default cache, when the cache holds it
    compiled for this environment (:func:`compiled`) and the module's text has that hash; else None."""
    path = cache.default_cache_dir() / f"{cache.PREFIX}{key}.py"
    if not compiled(key):
        return None
    cache.check_private(path.parent)
    cache.check_owned(path)
    if cache.source_hash(path.read_text(encoding="utf-8")) != key:
        return None
    return load_compiled(path, key)


def _environment() -> dict:
    """What numba's machine code depends on besides the module: numba, Python, the machine."""
    import importlib.metadata  # reading a distribution's metadata costs 40-60 ms at first: only when asked

    return {"numba": importlib.metadata.version("numba"), "python": sys.version, "machine": platform.machine()}


def _ready_path(key: str) -> Path:
    return cache.default_cache_dir() / f"{cache.PREFIX}{key}{READY_SUFFIX}"


def _index_files(key: str) -> list[str]:
    """The names of numba's index files of structure ``key``'s functions in the cache."""
    return sorted(path.name for path in (cache.default_cache_dir() / "__pycache__").glob(f"{cache.PREFIX}{key}.*.nbi"))


def mark_compiled(key: str) -> None:
    """Note that this process ran the stepper of structure ``key`` from the cache."""
    cache.write_private(_ready_path(key), json.dumps(_environment() | {"index": _index_files(key)}))


def compiled(key: str) -> bool:
    """Whether the cache holds structure ``key`` compiled for this environment."""
    marker, module = _ready_path(key), cache.default_cache_dir() / f"{cache.PREFIX}{key}.py"
    try:
        if marker.stat().st_mtime < module.stat().st_mtime:
            return False
        noted = json.loads(marker.read_text())
    except (OSError, ValueError):
        return False
    index = noted.pop("index", None)
    return noted == _environment() and bool(index) and set(index) <= set(_index_files(key))
