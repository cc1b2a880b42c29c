"""Linear complementarity problems from Python: ``solve(M, q)`` with Lemke's method.

Find z >= 0 with w = M z + q >= 0 and z.w = 0. The work is done by
:func:`mbds.kernel.lcp.lemke`; this module checks the input, allocates the workspace and
wraps the result. Defaults of the tolerances are those of the ``.wld`` keys
``LCPPivotToleranceMin``, ``LCPPivotToleranceMax`` and ``LCPLexicoZeroTolerance``.
"""

from __future__ import annotations

import enum
from typing import NamedTuple

import numpy as np

from mbds.kernel import lcp as _kernel

PIVOT_TOLERANCE_MIN = 1e-14
PIVOT_TOLERANCE_MAX = 1e-10
LEXICO_ZERO_TOLERANCE = 1e-8
MAX_PIVOTS = 10_000
"""Default pivot limit per tolerance attempt (Siconos' default for its Lemke solvers too)."""


class Status(enum.IntEnum):
    """How the solver ended (values are those returned by the kernel)."""

    SOLVED = _kernel.SOLVED
    RAY = _kernel.RAY
    MAX_PIVOTS = _kernel.MAX_PIVOTS
    PIVOT_FAILURE = _kernel.PIVOT_FAILURE


class LCPResult(NamedTuple):
    """z, w (n,); status; pivots: basis changes over all tolerance attempts."""

    z: np.ndarray
    w: np.ndarray
    status: Status
    pivots: int


def solve(
    M,
    q,
    *,
    pivot_tolerance_min: float = PIVOT_TOLERANCE_MIN,
    pivot_tolerance_max: float = PIVOT_TOLERANCE_MAX,
    lexico_zero_tolerance: float = LEXICO_ZERO_TOLERANCE,
    max_pivots: int | None = None,
) -> LCPResult:
    """Solve LCP(M, q) for M (n, n) and q (n,), any real values (converted to float64).

    max_pivots: limit per tolerance attempt, default the larger of :data:`MAX_PIVOTS` and
    100 (n + 1); Murty's exponential problem (2^n pivots) is solved for n <= 13. See :mod:`mbds.kernel.lcp`
    for the meaning of the tolerances. Raises ValueError on bad shapes, non-finite data or
    inconsistent tolerances.
    """
    M = np.ascontiguousarray(M, dtype=np.float64)
    q = np.ascontiguousarray(q, dtype=np.float64)
    n = q.shape[0] if q.ndim == 1 else -1
    if q.ndim != 1 or M.shape != (n, n):
        raise ValueError(f"M must be (n, n) and q (n,), got {M.shape} and {q.shape}")
    if not (np.isfinite(M).all() and np.isfinite(q).all()):
        raise ValueError("M and q must be finite")
    if not 0.0 < pivot_tolerance_min <= pivot_tolerance_max < 1.0:
        raise ValueError("need 0 < pivot_tolerance_min <= pivot_tolerance_max < 1")
    if not 0.0 < lexico_zero_tolerance < 1.0:
        raise ValueError("need 0 < lexico_zero_tolerance < 1")
    if max_pivots is None:
        max_pivots = max(MAX_PIVOTS, 100 * (n + 1))
    if max_pivots < 1:
        raise ValueError("max_pivots must be at least 1")
    z = np.empty(n)
    w = np.empty(n)
    fwork, iwork = _kernel.lcp_workspace(n)
    status, pivots = _kernel.lemke(
        M, q, z, w, pivot_tolerance_min, pivot_tolerance_max, lexico_zero_tolerance, max_pivots, fwork, iwork
    )
    return LCPResult(z, w, Status(status), int(pivots))
