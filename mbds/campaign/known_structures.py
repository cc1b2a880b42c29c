"""What the compile cache already holds, known without generating code.

Finding a variant's structure (the hash of its generated model source, :mod:`mbds.campaign.structures`)
means assembling its model and generating the code with sympy; making it ready means loading the
compiled module with numba and running its stepper for no time. For a campaign whose models were
compiled before, the scheduling process needs neither: it asks the cache.

- :func:`input_digest`: a digest of everything the generated code is made from: mbds's own
  code (its version and every source file of the package), sympy's and Python's versions, the
  bytes of every model file the world file names (by name relative to the world file's folder,
  absent files listed), and the variant's values. Any change to the inputs changes it.
- :func:`remember` / :func:`remembered`: the cache's memo, ``<cache>/keys/<digest>`` holding the
  structure found for these inputs by code generation. A memo is only ever a hint for
  scheduling: a run always generates its own code, whose hash names the module it loads, so a
  stale memo can at worst let a task compile (counted in the ledger), never run wrong code.
- :func:`mark_compiled` / :func:`compiled`: ``<cache>/mbds_model_<key>.ready``, written once a
  process has run the structure's stepper from this cache, holding the versions of numba and
  Python, the machine it ran on and the names of numba's index files of the module; it counts
  only while these match this process's, the index files are there, and it is newer than the
  module file (numba keys its machine code on that file's time).
"""

from __future__ import annotations

import functools
import hashlib
import importlib.metadata
import json
import os
import platform
import sys
import tempfile
from pathlib import Path

from mbds._version import __version__
from mbds.expr import cache

MEMO_FOLDER = "keys"
READY_SUFFIX = ".ready"


@functools.cache
def code_digest() -> str:
    """sha256 of the versions of mbds, sympy (which writes the code) and Python, and of every
    source file of the package (names and bytes)."""
    package = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256(f"{__version__} {importlib.metadata.version('sympy')} {sys.version}".encode())
    for path in sorted(package.rglob("*.py")):
        digest.update(str(path.relative_to(package)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def input_digest(files, variant=None) -> str:
    """The digest of the model of ``files`` (as read from its folder) with ``variant``'s values
    written in (None: as it is)."""
    folder = files.world.path.parent
    digest = hashlib.sha256(code_digest().encode())
    for path in sorted(files.paths()):
        digest.update(b"\0file\0" + os.path.relpath(path, folder).encode() + b"\0")
        digest.update(Path(path).read_bytes())
    for name in sorted(files.missing):
        digest.update(b"\0missing\0" + str(name).encode())
    if variant is not None:
        for parameter, pick in zip(variant.parameters, variant.picks):
            digest.update(b"\0value\0" + repr(parameter.target + (parameter.values[pick],)).encode())
    return digest.hexdigest()


def remembered(digest: str) -> str | None:
    """The structure remembered for the inputs of ``digest``, if any."""
    try:
        key = (cache.default_cache_dir() / MEMO_FOLDER / digest).read_text().strip()
    except OSError:
        return None
    return key if len(key) == cache.HASH_LENGTH and all(c in "0123456789abcdef" for c in key) else None


def remember(digest: str, key: str) -> None:
    """Remember that the inputs of ``digest`` give the structure ``key`` (atomically)."""
    _write(cache.default_cache_dir() / MEMO_FOLDER / digest, key)


def _environment() -> dict:
    """What numba's machine code depends on besides the module: numba, Python, the machine."""
    return {"numba": importlib.metadata.version("numba"), "python": sys.version, "machine": platform.machine()}


def _ready_path(key: str) -> Path:
    return cache.default_cache_dir() / f"{cache.PREFIX}{key}{READY_SUFFIX}"


def _index_files(key: str) -> list[str]:
    """The names of numba's index files of structure ``key``'s functions in the cache."""
    return sorted(path.name for path in (cache.default_cache_dir() / "__pycache__").glob(f"{cache.PREFIX}{key}.*.nbi"))


def mark_compiled(key: str) -> None:
    """Note that this process ran the stepper of structure ``key`` from the cache."""
    _write(_ready_path(key), json.dumps(_environment() | {"index": _index_files(key)}))


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


def _write(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically, in a folder of the private cache."""
    path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    cache.check_private(cache.default_cache_dir())
    descriptor, temporary = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    try:
        with os.fdopen(descriptor, "w") as file:
            file.write(text)
        os.replace(temporary, path)
    finally:
        Path(temporary).unlink(missing_ok=True)
