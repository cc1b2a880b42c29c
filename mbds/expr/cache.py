"""The disk cache of generated model modules.

A module is stored as ``<cache dir>/mbds_model_<hash>.py`` where the hash is that of its text;
numba keeps the machine code of its functions beside it (``__pycache__``), keyed on the file's
modification time, so an existing file is never rewritten.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import tempfile
from pathlib import Path
from types import ModuleType

PREFIX = "mbds_model_"
HASH_LENGTH = 20  # hexadecimal digits of sha256 kept in the file name


def default_cache_dir() -> Path:
    """``$MBDS_CACHE_DIR``, else ``mbds/models`` in the platform's user cache directory."""
    explicit = os.environ.get("MBDS_CACHE_DIR")
    if explicit:
        return Path(explicit).expanduser()
    if os.environ.get("XDG_CACHE_HOME"):
        base = Path(os.environ["XDG_CACHE_HOME"]).expanduser()
    elif sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA") or Path.home() / "AppData" / "Local")
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Caches"
    else:
        base = Path.home() / ".cache"
    return base / "mbds" / "models"


def source_hash(source: str) -> str:
    """Leading hexadecimal digits of the sha256 of ``source``."""
    return hashlib.sha256(source.encode("utf-8")).hexdigest()[:HASH_LENGTH]


def store(source: str, cache_dir: Path) -> Path:
    """Write ``source`` to its file in ``cache_dir`` unless an identical file is already there.

    The file appears atomically: concurrent writers (ranks of one campaign) never expose a
    partial file, and the first complete one is kept.
    """
    data = source.encode("utf-8")
    path = cache_dir / f"{PREFIX}{source_hash(source)}.py"
    if path.is_file() and path.read_bytes() == data:
        return path
    cache_dir.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(dir=cache_dir, prefix=path.stem, suffix=".tmp")
    try:
        with os.fdopen(descriptor, "wb") as file:
            file.write(data)
        os.chmod(temporary, 0o644)  # mkstemp makes it private; the cache may be shared by a group
        try:
            os.link(temporary, path)  # creates path only if it does not exist yet
        except FileExistsError:
            if path.read_bytes() != data:  # a damaged file: replace it
                os.replace(temporary, path)
        except OSError:  # a file system without hard links
            os.replace(temporary, path)
    finally:
        Path(temporary).unlink(missing_ok=True)
    return path


def load(path: Path) -> ModuleType:
    """Import the module at ``path`` once per process, named after its file (which carries its hash)."""
    name = path.stem
    module = sys.modules.get(name)
    if module is not None:
        return module
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module
