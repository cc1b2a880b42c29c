"""What the compile cache already holds, known without generating code.

Finding a variant's structure (the hash of its generated model source, :mod:`mbds.campaign.structures`)
means assembling its model and generating the code with sympy; making it ready means loading the
compiled module with numba and running its stepper for no time. For a campaign whose models were
compiled before, the scheduling process needs neither: it asks the cache.

- :func:`input_digest`: a digest of everything the generated code is made from: mbds's own
  code (its version and every source file of the package, :func:`mbds.expr.cache.code_digest`),
  sympy's and Python's versions, the bytes of every model file the world file names (by name
  relative to the world file's folder, absent files listed), and the variant's values. Any change to the inputs changes it.
- :func:`remember` / :func:`remembered`: the cache's memo, ``<cache>/keys/<digest>`` holding the
  structure found for these inputs by code generation. A memo is only ever a hint for
  scheduling: a run finds its module through its own model's record (:mod:`mbds.model.known`)
  or by generating its code, so a stale memo can at worst let a task compile (counted in the
  ledger), never run wrong code.
- :func:`mark_compiled` / :func:`compiled` (:mod:`mbds.expr.compiled`): whether the cache holds a
  structure compiled for this environment.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from mbds.expr import cache
from mbds.expr.compiled import compiled, mark_compiled

__all__ = ["compiled", "input_digest", "mark_compiled", "remember", "remembered"]

MEMO_FOLDER = "keys"


def input_digest(files, variant=None) -> str:
    """The digest of the model of ``files`` (as read from its folder) with ``variant``'s values
    written in (None: as it is)."""
    folder = files.world.path.parent
    digest = hashlib.sha256(cache.code_digest().encode())
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
    cache.write_private(cache.default_cache_dir() / MEMO_FOLDER / digest, key)
