"""The linear complementarity problems of contacts: between impacts and at impacts.

Contacts are rows of WN, WT (force directions, (cap, n)); ``Y = M^-1 W^T`` is kept per row
(YN, YT). Of the ``na`` contacts in ``active``, those flagged in ``stick`` (``nh`` of them)
are stick candidates; the others slide with ``sign`` = sgn(gT'). The unknowns of one LCP are
x = (lambda_N [na], lambda_0R [nh], gT''^- [nh]) with y = (gN'' [na], gT''^+ [nh], lambda_0L [nh]):

    A = [ WN^T M^-1 (N_G - W_H mu_H)   WN^T M^-1 W_H   0 ]
        [ W_H^T M^-1 (N_G - W_H mu_H)  W_H^T M^-1 W_H  I ]
        [ 2 mu_H                        -I              0 ]

where N_G column j is w_N,j - mu_j sign_j w_T,j (sliding) or w_N,j (stick candidate), and
lambda_T = lambda_0R - mu lambda_N at stick candidates, -mu sign lambda_N at sliding contacts.
At impacts every contact is a stick candidate and the same matrix (with impulses in place of
forces, velocities in place of accelerations) serves the compression and expansion phases.
"""

from __future__ import annotations

from mbds.kernel.jit import jit
from mbds.kernel.linalg import cholesky_solve_row


@jit
def inverse_mass_rows(L, rows, count, Y):
    """Y[i] = M^-1 rows[i] for the first ``count`` rows (L: Cholesky factor of M)."""
    for i in range(count):
        cholesky_solve_row(L, rows, i, Y)


@jit(inline="always")
def rows_dot(A, i, B, j):
    """sum_k A[i, k] B[j, k] (row i of A with row j of B, no array views)."""
    s = 0.0
    for k in range(A.shape[1]):
        s += A[i, k] * B[j, k]
    return s


@jit(inline="always")
def row_dot(A, i, v):
    """sum_k A[i, k] v[k]."""
    s = 0.0
    for k in range(A.shape[1]):
        s += A[i, k] * v[k]
    return s


@jit
def build_matrix(active, na, stick, sign, laws, WN, WT, YN, YT, column, hrow, A_flat):
    """Fill the matrix A (size m = na + 2 nh, row-major in A_flat[:m * m]) for the contacts
    active[:na]; return nh.

    column: (cap, n) scratch for M^-1 times the effective normal column of each contact;
    hrow: (cap,) int64 scratch, the index in ``active`` of each stick candidate.
    """
    n = WN.shape[1]
    nh = 0
    for a in range(na):
        c = active[a]
        if stick[c]:
            hrow[nh] = a
            nh += 1
        f = laws[c, 0] * (1.0 if stick[c] else sign[c])
        for k in range(n):
            column[a, k] = YN[c, k] - f * YT[c, k]
    m = na + 2 * nh
    A = A_flat[: m * m].reshape((m, m))
    for i in range(m):
        for j in range(m):
            A[i, j] = 0.0
    for i in range(na):
        ci = active[i]
        for j in range(na):
            A[i, j] = rows_dot(WN, ci, column, j)
        for h in range(nh):
            A[i, na + h] = rows_dot(WN, ci, YT, active[hrow[h]])
    for g in range(nh):
        cg = active[hrow[g]]
        r = na + g
        for j in range(na):
            A[r, j] = rows_dot(WT, cg, column, j)
        for h in range(nh):
            A[r, na + h] = rows_dot(WT, cg, YT, active[hrow[h]])
        A[r, na + nh + g] = 1.0
        r2 = na + nh + g
        A[r2, hrow[g]] = 2.0 * laws[cg, 0]
        A[r2, na + g] = -1.0
    return nh


@jit
def tangential_forces(active, na, stick, sign, laws, z, lam_n, lam_t):
    """Normal and tangential forces (or impulses) of the active contacts from an LCP solution z."""
    h = 0
    for a in range(na):
        c = active[a]
        lam_n[c] = z[a]
        if stick[c]:
            lam_t[c] = z[na + h] - laws[c, 0] * z[a]
            h += 1
        else:
            lam_t[c] = -laws[c, 0] * sign[c] * z[a]
