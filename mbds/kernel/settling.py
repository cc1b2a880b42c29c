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

import numpy as np

from mbds.kernel.contact_problem import settling_speed
from mbds.kernel.jit import jit

SETTLE_RANK = 1e-9
"""A pivot of the normal block below this fraction of its largest diagonal entry ends the
factorisation: the rows left are dependent on the others."""


@jit(refcount=False)
def settle_positions(active, na, gap0, WN, YN, settings, dt, q, fwork, iwork):
    """q += dt M^-1 W_N^T x for the contacts active[:na] at rest over a step of dt (s), with their
    gaps gap0 (m) at the step's start (see the module doc). WN, YN: (cap, n) rows W_N and
    M^-1 W_N^T; fwork: float scratch of at least na * (na + 2); iwork: int scratch of at least na."""
    n = q.shape[0]
    N = fwork  # the normal block, row-major na x na (lower triangle), then x and y
    x = na * na
    y = x + na
    for a in range(na):
        iwork[a] = a
        fwork[x + a] = dt * settling_speed(gap0[active[a]], settings)
        for b in range(a + 1):
            s = 0.0
            for k in range(n):
                s += WN[active[a], k] * YN[active[b], k]
            N[a * na + b] = s
    top = 0.0
    for a in range(na):
        top = max(top, N[a * na + a])
    rank = na
    for j in range(na):
        p = j
        for i in range(j + 1, na):
            if N[i * na + i] > N[p * na + p]:
                p = i
        if not N[p * na + p] > SETTLE_RANK * top:
            rank = j
            break
        if p != j:
            _swap(N, na, iwork, j, p)
        pivot = np.sqrt(N[j * na + j])
        N[j * na + j] = pivot
        for i in range(j + 1, na):
            N[i * na + j] /= pivot
        for i in range(j + 1, na):
            for c in range(j + 1, i + 1):
                N[i * na + c] -= N[i * na + j] * N[c * na + j]
    for j in range(rank):  # L z = P^T b, then L^T y = z, on the factorised rows
        s = fwork[x + iwork[j]]
        for k in range(j):
            s -= N[j * na + k] * fwork[y + k]
        fwork[y + j] = s / N[j * na + j]
    for j in range(rank - 1, -1, -1):
        s = fwork[y + j]
        for k in range(j + 1, rank):
            s -= N[k * na + j] * fwork[y + k]
        fwork[y + j] = s / N[j * na + j]
    for j in range(rank):
        c = active[iwork[j]]
        for k in range(n):
            q[k] += fwork[y + j] * YN[c, k]


@jit(inline="always")
def _swap(N, na, perm, j, p):
    """Swap rows and columns j < p of the symmetric na x na matrix whose lower triangle N holds
    (the factor's columns left of j move with their rows) and entries j, p of perm."""
    perm[j], perm[p] = perm[p], perm[j]
    for c in range(j):
        N[j * na + c], N[p * na + c] = N[p * na + c], N[j * na + c]
    N[j * na + j], N[p * na + p] = N[p * na + p], N[j * na + j]
    for i in range(j + 1, p):
        N[i * na + j], N[p * na + i] = N[p * na + i], N[i * na + j]
    for i in range(p + 1, na):
        N[i * na + j], N[i * na + p] = N[i * na + p], N[i * na + j]
