"""Compiling a user force function with numba (the module generated from a user force calls it)."""

from __future__ import annotations

import numba

from mbds.kernel.jit import jit


def jitted(function):
    """``function`` as a numba dispatcher with the kernel's settings (unchanged when it is one
    already).  No disk cache: the function may come from source run with ``exec``."""
    if isinstance(function, numba.core.registry.CPUDispatcher):
        return function
    return jit(function, cache=False)
