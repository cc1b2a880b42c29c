"""The one place for numba settings of the kernel.

Environment overrides (read once, at import):

- ``MBDS_JIT_CACHE`` (default ``1``): cache compiled code on disk.
- ``MBDS_FASTMATH`` (default ``0``): allow fast-math; off keeps results bit-reproducible.
- ``MBDS_BOUNDSCHECK`` (default ``0``): check array bounds (slow; for debugging).

numba keys a cached function by the text of its own file, but a kernel function's machine code
also holds the functions it calls from other kernel files. The kernel's cached functions are
therefore keyed by all of its files together (:func:`kernel_source_hash`): after any change to the
kernel (an upgrade, an edit) each of them compiles again instead of running stale callees.
"""

from __future__ import annotations

import functools
import hashlib
import os
from pathlib import Path

import numba
from numba.core import caching

KERNEL_FOLDER = Path(__file__).resolve().parent


def _flag(name: str, default: bool) -> bool:
    value = os.environ.get(name)
    if value is None:
        return default
    return value.strip().lower() not in ("0", "false", "no", "off", "")


CACHE = _flag("MBDS_JIT_CACHE", True)
FASTMATH = _flag("MBDS_FASTMATH", False)
BOUNDSCHECK = _flag("MBDS_BOUNDSCHECK", False)


def jit(*args, refcount=True, **kwargs):
    """``numba.njit`` with the project's settings; keyword arguments override them.

    ``refcount=False`` compiles without numba's reference counting of arrays: no atomic
    increment and decrement of every array argument, namedtuple field and view a function
    touches (the larger part of the stepper's cost per step when it had them). Only for
    functions that work on arrays their caller owns: they may not create an array or return
    one (numba then refuses to compile them).
    """
    options = {"cache": CACHE, "fastmath": FASTMATH, "boundscheck": BOUNDSCHECK, "nogil": True}
    if not refcount:
        options["_nrt"] = False
    options.update(kwargs)
    if args and callable(args[0]) and len(args) == 1:
        return numba.njit(**options)(args[0])
    return numba.njit(*args, **options)


@functools.cache
def kernel_source_hash() -> str:
    """Hash of the source files of mbds.kernel (names and bytes), 20 hex digits."""
    digest = hashlib.sha256()
    for path in sorted(KERNEL_FOLDER.glob("*.py")):
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:20]


class _WholeKernelStamp:
    """A numba cache locator for functions defined in the kernel's files, stamped with the hash of
    all of them; it declines every other file (numba's own locators then take it)."""

    def get_source_stamp(self):
        return kernel_source_hash()

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent != KERNEL_FOLDER:
            return None
        return super().from_function(py_func, py_file)


def _kernel_locators() -> list[type]:
    """numba's file-backed locators (in their order), each stamped by the whole kernel."""
    return [type(f"Kernel{base.__name__}", (_WholeKernelStamp, base), {})
            for base in (caching.UserProvidedCacheLocator, caching.InTreeCacheLocator, caching.UserWideCacheLocator)]


if not any(issubclass(c, _WholeKernelStamp) for c in caching.CacheImpl._locator_classes):
    caching.CacheImpl._locator_classes[:0] = _kernel_locators()
