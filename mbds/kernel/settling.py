"""Settling of contacts at rest towards zero gap, by a shift of the positions alone.

A contact at rest that lies in its surface (an impact ends up to maximumPenetration deep, a
pivoting corner drifts) or just above it (in the held band) moves towards zero gap at its
settling speed v_s (mbds.kernel.contact_problem.settling_speed: -gap / (4 tau), within half the
rest velocity either way). The shift is the smallest in the metric of M that moves each contact
of the step's set by dt v_s along its normal: dq = M^-1 W_N^T x with (W_N M^-1 W_N^T) x = dt v_s.
It changes no velocity, so a body whose contacts open while they settle (it lifts off) takes no
settling speed into its flight. The Delassus matrix's normal block is factorised by Cholesky
with diagonal pivoting; rows dependent within SETTLE_RANK of its largest diagonal entry get
x = 0 (five balls wedged in a row: their gaps settle as far as one shift meets them).
"""

from __future__ import annotations

from mbds.kernel.contact_problem import settling_speed
from mbds.kernel.jit import jit
from mbds.kernel.linalg import pivoted_cholesky, pivoted_cholesky_solve

SETTLE_RANK = 1e-3
"""A pivot of the normal block below this fraction of its largest diagonal entry ends the
factorisation: the rows left are dependent on the others, or so nearly that meeting them would
take a shift up to 1 / SETTLE_RANK times larger than the gaps asked for. (At 1e-9, two nearly
dependent rows of a fast pile of polygons asked for a shift that drove a third vertex into a
body at 4 cm/s, step after step, and the steps fell to minimumTimestep.)"""


@jit(refcount=False)
def settle_positions(active, na, gap0, WN, YN, settings, dt, q, fwork, iwork):
    """q += dt M^-1 W_N^T x for the contacts active[:na] at rest over a step of dt (s), with their
    gaps gap0 (m) at the step's start (see the module doc). WN, YN: (cap, n) rows W_N and
    M^-1 W_N^T; fwork: float scratch of at least na * (na + 2); iwork: int scratch of at least na."""
    n = q.shape[0]
    N = fwork[: na * na].reshape((na, na))  # the normal block's lower triangle, then b and x
    b = fwork[na * na : na * na + na]
    x = fwork[na * na + na : na * na + 2 * na]
    for a in range(na):
        b[a] = dt * settling_speed(gap0[active[a]], settings)
        for c in range(a + 1):
            s = 0.0
            for k in range(n):
                s += WN[active[a], k] * YN[active[c], k]
            N[a, c] = s
    rank = pivoted_cholesky(N, iwork, na, SETTLE_RANK)
    pivoted_cholesky_solve(N, iwork, rank, b, x)
    for j in range(rank):
        c = active[iwork[j]]
        for k in range(n):
            q[k] += x[j] * YN[c, k]
