"""The one place for numba settings of the kernel.

Environment overrides (read once, at import):

- ``MBDS_JIT_CACHE`` (default ``1``): cache compiled code on disk.
- ``MBDS_FASTMATH`` (default ``0``): allow fast-math; off keeps results bit-reproducible.
- ``MBDS_BOUNDSCHECK`` (default ``0``): check array bounds (slow; for debugging).
"""

from __future__ import annotations

import os

import numba


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
