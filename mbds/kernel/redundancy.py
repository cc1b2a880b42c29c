"""Rest targets that one motion can meet, for groups of contacts with dependent rows.

A contact at rest holds with a target rate that relaxes its residual speed
(mbds.kernel.contact_problem.accelerations): g_N'' = -(g_N' - v_s) / tau normally and, where it
sticks, g_T'' = -g_T' / tau, each from its own row's speed and gap. Where the rows of a group are
linearly dependent (five balls wedged in a row between a wall and the floor: 10 normal and 9
tangential rows on 15 coordinates), the targets of the dependent rows need not agree with the
others: no motion of the bodies meets them all. The contact-force LCP is then solved only with
stick candidates slipping at a bound of Coulomb's cone by about the size of the targets, and
which of them slip changes from one LCP to the next with the residual speeds. The targets d
(m/s^2, one per row) are therefore replaced by their orthogonal projection onto the range of the
rows W_R^T, the nearest targets that one motion meets; targets of independent rows are kept as
they are (no projection is computed).

The projection is W_R^T x with G x = W_R d, G = W_R W_R^T over the group's coordinates. A
Cholesky factorisation of G with diagonal pivoting stops at the first pivot below ``tol`` times
G's largest diagonal entry; its rank is that of the rows. Below full rank, x is solved on the
factorised coordinates with the others 0: G x = W_R d is consistent (W_R d lies in the range of
G = W_R W_R^T), and every solution gives the same W_R^T x.
"""

from __future__ import annotations


from mbds.kernel.jit import jit
from mbds.kernel.linalg import pivoted_cholesky, pivoted_cholesky_solve


@jit(inline="always")
def project_targets(part, k, nh, hrow, WN, WT, span, d, tol, G, v, perm):
    """d[:R] <- its orthogonal projection onto the range of W_R^T, the R = k + nh rows of a group
    (the normal rows of part[:k], then the tangential rows of its stick candidates
    part[hrow[:nh]]; span: the nonzero columns of each contact's rows, from
    mbds.kernel.contact_problem.row_spans), where those rows are dependent within ``tol``; return
    their rank (R: d left as it is). G: (>= n, >= n) scratch, v: (>= 2, >= n) scratch, perm:
    (>= n,) int64 scratch, n the number of coordinates."""
    R = k + nh
    lo = WN.shape[1]
    hi = 0
    for a in range(k):
        lo = min(lo, span[a, 0])
        hi = max(hi, span[a, 1])
    n = hi - lo
    if n <= 0:  # rows without a nonzero entry meet no target but zero
        for i in range(R):
            d[i] = 0.0
        return 0
    for i in range(n):  # G's lower triangle only, here and below
        for j in range(i + 1):
            G[i, j] = 0.0
    for i in range(R):
        a, c, W = _group_row(i, k, hrow, part, WN, WT)
        for p in range(span[a, 0], span[a, 1]):
            wp = W[c, p]
            if wp != 0.0:
                for q in range(span[a, 0], p + 1):
                    G[p - lo, q - lo] += wp * W[c, q]
    r = pivoted_cholesky(G, perm, n, tol)
    if r >= R:
        return R
    b, x = v[0], v[1]
    for p in range(n):
        b[p] = 0.0
    for i in range(R):  # b = W_R d
        a, c, W = _group_row(i, k, hrow, part, WN, WT)
        for p in range(span[a, 0], span[a, 1]):
            b[p - lo] += W[c, p] * d[i]
    pivoted_cholesky_solve(G, perm, r, b, x)  # on the factorised coordinates
    for p in range(n):
        b[p] = 0.0
    for j in range(r):
        b[perm[j]] = x[j]
    for i in range(R):  # d = W_R^T x
        a, c, W = _group_row(i, k, hrow, part, WN, WT)
        s = 0.0
        for p in range(span[a, 0], span[a, 1]):
            s += W[c, p] * b[p - lo]
        d[i] = s
    return r


@jit(inline="always")
def _group_row(i, k, hrow, part, WN, WT):
    """(a, c, W) of row i of W_R (see :func:`project_targets`): the index in part of its contact,
    the contact, and WN (normal rows, i < k) or WT (tangential rows of stick candidates)."""
    a = i if i < k else hrow[i - k]
    return a, part[a], WN if i < k else WT
