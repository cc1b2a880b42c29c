"""The disk cache of generated model modules.

A module is stored as ``<cache dir>/mbds_model_<hash>.py`` where the hash is that of its text;
numba keeps the machine code of its functions beside it (``__pycache__``), keyed on the file's
modification time, so an existing file is never rewritten.

Importing a module runs it, and numba's index files beside it are unpickled: a cache another user
can write to would run that user's code. So the cache folder is created private (0700), and
before use the folder and its ``__pycache__`` must belong to the user and be writable by no one
else, and a module file must belong to the user; otherwise :class:`~mbds.errors.ModelError`
says what to fix.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import sys
import tempfile
from pathlib import Path
from types import ModuleType

from mbds._version import version as mbds_version
from mbds.errors import ModelError

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
    cache_dir.mkdir(mode=0o700, parents=True, exist_ok=True)
    (cache_dir / "__pycache__").mkdir(mode=0o700, exist_ok=True)  # before numba makes it with the umask's mode
    check_private(cache_dir)
    if path.is_file() and path.read_bytes() == data:
        check_owned(path)
        return path
    descriptor, temporary = tempfile.mkstemp(dir=cache_dir, prefix=path.stem, suffix=".tmp")
    try:
        with os.fdopen(descriptor, "wb") as file:
            file.write(data)
        os.chmod(temporary, 0o600)
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


def check_private(folder: Path) -> None:
    """``folder`` (and its ``__pycache__``, if there) belongs to this user and no one else may
    write to it; ModelError otherwise (not checked where the system has no user ids)."""
    for each in (folder, folder / "__pycache__"):
        if not each.exists():
            continue
        check_owned(each)
        if each.stat().st_mode & 0o022:
            raise ModelError(f"the compiled-model cache is writable by other users, who could make mbds run their "
                             f"code: chmod go-w {each}, or set MBDS_CACHE_DIR to a private folder", each)


def check_owned(path: Path) -> None:
    """``path`` belongs to this user; ModelError otherwise."""
    if hasattr(os, "getuid") and path.stat().st_uid != os.getuid():
        raise ModelError("belongs to another user: mbds does not run compiled models that others left in its "
                         "cache; set MBDS_CACHE_DIR to a folder of your own", path)


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


@functools.cache
def code_digest() -> str:
    """sha256 of the versions of mbds, sympy (which writes the code) and Python, and of every
    source file of the package (names and bytes): what any input digest of the cache starts from."""
    import importlib.metadata  # reading a distribution's metadata costs 40-60 ms at first: only when asked

    package = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256(f"{mbds_version()} {importlib.metadata.version('sympy')} {sys.version}".encode())
    for path in sorted(package.rglob("*.py")):
        digest.update(str(path.relative_to(package)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def write_private(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically, in a folder of the private cache (the default one)."""
    path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    check_private(default_cache_dir())
    descriptor, temporary = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    try:
        with os.fdopen(descriptor, "w") as file:
            file.write(text)
        os.replace(temporary, path)
    finally:
        Path(temporary).unlink(missing_ok=True)
