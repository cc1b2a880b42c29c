"""Compiling a user force function with numba (the module generated from a user force calls it)."""

from __future__ import annotations

import numba


def jitted(function):
    """``function`` as a numba dispatcher (unchanged when it is one already)."""
    if isinstance(function, numba.core.registry.CPUDispatcher):
        return function
    return numba.njit(function)
