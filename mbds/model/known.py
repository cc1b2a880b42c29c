"""A model's numbers remembered by the compile cache, so that a model seen before is assembled
without sympy.

Assembling a model reads its files and builds its bodies, contacts and watches with numpy alone;
sympy is needed for what its expressions give: the generated code (whose hash, the model's
*structure*, names its compiled module), the numbers written in its contact laws (entries of
the parameter array ``p``), the start values of free coordinates, the break time, and the
checks of its contact laws and mass matrix. Once a process has assembled a model that way, its
*record* keeps these in the cache: ``<cache>/models/<digest>``, a JSON file, where the digest
(:func:`model_digest`) covers mbds's code (:func:`mbds.expr.cache.code_digest`) and the bytes of
every model file but the shapes, which a worn version changes and which none of these depend on
(a shape counts by its name; the masses it gives are computed again each time). A later load of
a model with the same digest takes them from the record (``mbds.model.load``), and loads the
compiled module of the structure straight from the cache (:func:`mbds.expr.compiled.cached_module`).

The record also keeps the warnings that these steps gave (their texts, the model's folder left
out), so that a model assembled from it warns as it did.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import os
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mbds.errors import ModelWarning
from mbds.expr import cache
from mbds.io.folder import ModelFiles
from mbds.model.bodies import FIXED, POSE, Body

RECORD_FOLDER = "models"
_IN_FOLDER = "\0folder\0"  # stands for the model's folder in a remembered warning


@dataclass(frozen=True)
class Record:
    """What a model's expressions gave: its ``structure`` (the hash of its generated code), the
    numbers lifted from its contact laws (the end of ``p``), its start state ``q0``, ``qd0``
    (m, rad; m/s, rad/s), its ``break_time`` (s) and the texts of the warnings these gave."""

    structure: str
    law_numbers: tuple[float, ...]
    q0: tuple[float, ...]
    qd0: tuple[float, ...]
    break_time: float
    warnings: tuple[str, ...]


def base_parameters(files: ModelFiles, bodies: list[Body]) -> list[float]:
    """The values of ``p`` before the contact-law numbers: the constants (``.cns`` order), each
    non-virtual body's mass (kg) and Jzz (kg m^2), and the start values of fixed pose
    coordinates (m, rad)."""
    values = list(files.constants.values.values())
    solid = [body for body in bodies if not body.virtual]
    for body in solid:
        values += [body.mass, body.inertia]
    for body in solid:
        values += [body.start_position[axis] for axis in range(len(POSE)) if body.binding[axis] == FIXED]
    return values


def model_digest(files: ModelFiles, texts: dict[str, str] | None = None) -> str:
    """sha256 of mbds's code and the model files of ``files`` (shapes by name only), with
    ``texts`` (by path relative to the world file's folder) standing for the files they name,
    as in a copy that writes them over the folder's (``create_model_copy``)."""
    folder = files.world.path.parent
    shapes = {os.path.relpath(shape.path, folder) for shape in files.shapes}
    contents: dict[str, bytes | Path] = {os.path.relpath(path, folder): path for path in files.paths()}
    contents.update({name: text.encode("utf-8") for name, text in (texts or {}).items()})
    digest = hashlib.sha256(cache.code_digest().encode() + b"\0record\0")
    for name in sorted(contents):
        if name in shapes:
            digest.update(b"\0shape\0" + name.encode())
            continue
        data = contents[name]
        digest.update(b"\0file\0" + name.encode() + b"\0")
        digest.update(data if isinstance(data, bytes) else data.read_bytes())
    for name in sorted(set(files.missing) - set(contents)):
        digest.update(b"\0missing\0" + str(name).encode())
    return digest.hexdigest()


def _record_path(digest: str) -> Path:
    return cache.default_cache_dir() / RECORD_FOLDER / digest


def remembered(files: ModelFiles, texts: dict[str, str] | None = None) -> Record | None:
    """The record of the model of ``files`` (see :func:`model_digest`), if the cache holds one
    (ModelError when the cache is not private, as for its modules)."""
    cache.check_private(cache.default_cache_dir())
    try:
        noted = json.loads(_record_path(model_digest(files, texts)).read_text(encoding="utf-8"))
        record = Record(**{name: tuple(value) if isinstance(value, list) else value for name, value in noted.items()})
    except (OSError, ValueError, TypeError):
        return None
    folder = str(files.world.path.parent)
    return dataclasses.replace(record, warnings=tuple(w.replace(_IN_FOLDER, folder) for w in record.warnings))


def remember(files: ModelFiles, record: Record) -> None:
    """Keep ``record`` as the record of the model of ``files`` (as read from its folder; atomically)."""
    folder = str(files.world.path.parent)
    kept = dataclasses.asdict(record) | {"warnings": [w.replace(folder, _IN_FOLDER) for w in record.warnings]}
    cache.write_private(_record_path(model_digest(files)), json.dumps(kept))


def floats(array: np.ndarray) -> tuple[float, ...]:
    """The values of ``array`` as Python floats (which JSON keeps exactly)."""
    return tuple(float(value) for value in array)


@contextlib.contextmanager
def noting(texts: list[str]):
    """Within the block, collect the texts of the model warnings issued into ``texts``; at its
    end (or error) issue every warning caught again, as it would have been."""
    caught: list = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ModelWarning)
            yield
    finally:
        for each in caught:
            if issubclass(each.category, ModelWarning):
                texts.append(str(each.message))
            warnings.warn_explicit(each.message, each.category, each.filename, each.lineno)


def issue(texts) -> None:
    """Issue the remembered warnings ``texts`` again."""
    for text in texts:
        warnings.warn(text, ModelWarning, stacklevel=2)
