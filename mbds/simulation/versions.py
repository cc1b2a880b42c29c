"""Version folders: a model folder holds the model files, an optional job file and one folder per
version (``000``, ``001``, ...), each with its own copy of the model files and the outputs of
its run."""

from __future__ import annotations

import os
import shutil
import tempfile
import warnings
from pathlib import Path

from mbds.data.history import FILE_NAME as HISTORY
from mbds.errors import ModelError, ModelWarning
from mbds.io.folder import (
    ModelFiles,
    copy_model_files,
    find_world,
    read_model_files,
    version_name,
    version_number,
)
from mbds.io.job import JobSettings, read_job
from mbds.io.text import process_umask, write_atomic
from mbds.model.load import check_model


def existing_versions(model_folder: str | Path) -> list[int]:
    """Numbers of the version folders present, in order."""
    folder = Path(model_folder)
    found = (version_number(p) for p in folder.iterdir() if p.is_dir()) if folder.is_dir() else ()
    return sorted(v for v in found if v is not None)


def ensure_version(model_folder: str | Path, number: int, source: str | Path | None = None) -> Path:
    """The folder of version ``number``; when absent it is created from the files of ``source``
    (default: the model folder), which are read and checked first. The folder appears whole or
    not at all."""
    target = Path(model_folder) / version_name(number)
    if target.is_dir() and any(target.glob("*.wld")):
        return target
    with warnings.catch_warnings():  # the version's own files repeat any warning when they are loaded
        warnings.simplefilter("ignore", ModelWarning)
        files = read_model_files(source or model_folder)
    return create_model_copy(target, files, number)


def create_model_copy(target: str | Path, files: ModelFiles, number: int, texts: dict[str, str] | None = None) -> Path:
    """Create folder ``target`` holding a byte-for-byte copy of the model ``files``, with
    ``texts`` (by path relative to the world file's folder) written over their copies. The model
    is checked first (as version ``number``), and the folder appears whole or not at all; an
    existing copy (a folder with a ``.wld`` file) is left as it is."""
    target = Path(target)
    if target.is_dir() and any(target.glob("*.wld")):
        return target
    if target.exists() and any(target.iterdir()):
        raise ModelError("a folder without a .wld world file is in the way", target)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        check_model(files, number, texts)  # bad input stops here, before anything is written
    target.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent))
    try:
        staging.chmod(0o777 & ~process_umask())  # mkdtemp makes it private
        copy_model_files(files, staging)
        for name, text in (texts or {}).items():
            write_atomic(staging / name, text)
        if target.exists():
            target.rmdir()
        os.rename(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target


def differing_copies(model_folder: str | Path, version: str | Path) -> list[str]:
    """The model files of ``model_folder`` whose copies in the version folder ``version`` are
    missing or differ from them (paths relative to the world file's folder)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        files = read_model_files(model_folder)
    base = files.world.path.parent.resolve()
    differing = []
    for path in files.paths():
        relative = Path(path).resolve().relative_to(base)
        copy = Path(version) / relative
        if not copy.is_file() or copy.read_bytes() != Path(path).read_bytes():
            differing.append(relative.as_posix())
    return differing


def refresh_copies(model_folder: str | Path, version: str | Path) -> None:
    """Copy the model folder's files over their copies in the version folder ``version``."""
    copy_model_files(read_model_files(model_folder), version)


def run_folder(path: str | Path, start_from: int | None = None, force: bool = False) -> Path:
    """The version folder a run of ``path`` uses, created when needed.

    ``path`` is a version folder (created from the model folder's files, or from those of
    version ``start_from`` if given, when absent) or a model folder: then version 000, or the
    version after the highest existing one when the run starts from ``start_from``. When version
    000 exists and the model folder's files differ from its copies, ModelError names them,
    unless ``force``: then the copies are replaced by the model folder's files.
    """
    path = Path(path)
    number = version_number(path)
    if number is not None:
        model_folder = path.parent
    else:
        if not path.is_dir():
            raise ModelError("expected a model folder or a version folder (000, 001, ...)", path)
        find_world(path)  # a model folder, or a clear error
        model_folder = path
        number = 0 if start_from is None else max(existing_versions(path), default=-1) + 1
    source = None
    if start_from is not None:
        if start_from == number:
            raise ModelError(f"version {version_name(number)} cannot start from its own end", path)
        source = model_folder / version_name(start_from)
        if not source.is_dir():
            raise ModelError(f"no version {version_name(start_from)} to start from", model_folder)
        if not (source / HISTORY).is_file():
            raise ModelError(f"no {HISTORY} to start from: run this version first", source)
    target = model_folder / version_name(number)
    if number == 0 and source is None and target.is_dir() and any(target.glob("*.wld")):
        differing = differing_copies(model_folder, target)
        if differing and not force:
            raise ModelError(f"the model folder's {', '.join(differing)} differ from the copies in version 000, "
                             "which a run of 000 uses: run with --force to replace 000's copies (and its run) by "
                             "the model folder's files, or make the next version from 000's run with "
                             f"'mbds next {target}'", model_folder)
        if differing:
            refresh_copies(model_folder, target)
    return ensure_version(model_folder, number, source)


def job_settings(model_folder: str | Path, world_stem: str) -> JobSettings:
    """The ``[main]`` settings of the model folder's job file: ``<world>.job``, else its only
    ``.job`` file; the defaults when there is none."""
    folder = Path(model_folder)
    named = folder / f"{world_stem}.job"
    jobs = sorted(folder.glob("*.job"))
    path = named if named.is_file() else (jobs[0] if len(jobs) == 1 else None)
    return read_job(path).settings if path else JobSettings()
