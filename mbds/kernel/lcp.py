"""Lemke's complementary pivot algorithm with a lexicographic ratio test.

Solves LCP(M, q): find z >= 0 with w = M z + q >= 0 and z.w = 0, for a dense M of shape (n, n)
(neither symmetry nor the P-property is assumed) and q of shape (n,). Quantities are
dimensionless to this module: M and q carry whatever units the caller's problem has.

Method. The system w - M z - e z0 = q (covering vector e = ones) is pivoted from the basis
{w}: z0 enters first, then each step the complement of the variable that just left enters,
until z0 leaves (solved) or the entering column has no positive entry (ray). The explicit
basis inverse B^-1 is stored compactly: a column j of B^-1 whose w_j is basic is the unit
vector of w_j's row, so only the k columns with w_j non-basic are kept, transposed
(``G[s, :]`` is column ``slot_col[s]`` of B^-1). Computing the entering column and updating
B^-1 both cost 2 n k flops per pivot, in contiguous loops, with no allocation.

Ratio test. Rows i with d_i > tol_piv * max|d| (d: the entering column) are candidates. Among
them the lexicographic minimum of the rows (qbar_i, B^-1[i, 0], ..., B^-1[i, n-1]) / d_i is
chosen, column by column: each column c is scaled by max_i |c_i| (over all rows) and d by
max|d|; rows whose scaled ratio exceeds the column minimum by at most ``tol_lex`` tie and go
on to the next column. When the row of z0 is among the rows tied on qbar, z0 leaves (the step
ends on a solution). This rule keeps every row of [qbar, B^-1] lexicographically positive, so
no basis repeats: the method cannot cycle.

Tolerances (arguments, never globals):

- ``tol_piv_min`` / ``tol_piv_max`` (the ``LCPPivotToleranceMin`` / ``Max`` keys): an entry
  d_i of the entering column takes part in the ratio test only if d_i > tol_piv * max|d|.
  The first attempt uses ``tol_piv_min``. If it does not end solved, the tolerance is raised
  tenfold (capped at ``tol_piv_max``) and the problem is solved again from scratch, but only
  while the raise can change the path: when every candidate entry ever met exceeded the
  raised tolerance, the new attempt would repeat the old one exactly, and the old status is
  final. Small pivots are thus accepted first (exact Lemke) and excluded only when the
  result is not a verified solution.
- ``tol_lex`` (the ``LCPLexicoZeroTolerance`` key): the relative size below which a number
  counts as zero. It decides ties in the lexicographic ratio test (above), and it is the
  acceptance threshold of the final check: with s_i = |q_i| + sum_j |M_ij| z_j, the end point
  is a solution only if w_i >= -tol_lex s_i for all i and |w_i| <= tol_lex s_i where z_i > 0.

Pivot count: every basis change, including the first pivot (z0 enters) and the last (z0
leaves), summed over all tolerance attempts; 0 when q >= 0 (then z = 0, w = q).
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit

SOLVED = 0
"""Status: z, w solve the LCP (verified on the original data)."""
RAY = 1
"""Status: the path ended on a secondary ray with z0 > 0; no solution was found."""
MAX_PIVOTS = 2
"""Status: the pivot limit was reached."""
PIVOT_FAILURE = 3
"""Status: numerical breakdown: non-finite numbers, ties that no column breaks, or an end
point that fails the solution check."""


@jit
def lcp_workspace(n):
    """Workspace of an LCP of size n: (float64 array of n*n + 5n, int64 array of 7n + 1)."""
    return np.empty(n * n + 5 * n), np.empty(7 * n + 1, dtype=np.int64)


@jit
def lemke(M, q, z, w, tol_piv_min, tol_piv_max, tol_lex, max_pivots, fwork, iwork):
    """Solve LCP(M, q) into z, w (both (n,), overwritten); return (status, pivots).

    M: (n, n) float64, C-contiguous; q: (n,) float64; max_pivots: limit per tolerance
    attempt; fwork, iwork: from :func:`lcp_workspace`. z, w are the basic point of the last
    basis (z clipped at 0, w = M z + q) whatever the status.
    """
    n = q.shape[0]
    if n == 0 or np.min(q) >= 0.0:
        z[:] = 0.0
        w[:] = q
        return SOLVED, 0
    G = fwork[: n * n].reshape((n, n))
    qbar = fwork[n * n : n * n + n]
    d = fwork[n * n + n : n * n + 2 * n]
    col = fwork[n * n + 2 * n : n * n + 3 * n]
    ratio = fwork[n * n + 3 * n : n * n + 4 * n]
    dnext = fwork[n * n + 4 * n : n * n + 5 * n]
    basis = iwork[:n]
    where = iwork[n : 3 * n + 1]
    slot_col = iwork[3 * n + 1 : 4 * n + 1]
    slot_of = iwork[4 * n + 1 : 5 * n + 1]
    rows = iwork[5 * n + 1 : 6 * n + 1]
    zlist = iwork[6 * n + 1 : 7 * n + 1]
    tol_piv = tol_piv_min
    total = 0
    while True:
        status, pivots, rho = _attempt(
            M, q, tol_piv, tol_lex, max_pivots, G, qbar, d, dnext, col, ratio, basis, where, slot_col, slot_of, rows
        )
        total += pivots
        status = _end_point(M, q, tol_lex, qbar, basis, z, w, zlist, status)
        if status == SOLVED or rho > tol_piv_max:
            return status, total
        while tol_piv < rho:  # smaller raises would repeat the same path
            tol_piv = min(10.0 * tol_piv, tol_piv_max)


@jit
def _attempt(M, q, tol_piv, tol_lex, max_pivots, G, qbar, d, dnext, col, ratio, basis, where, slot_col, slot_of, rows):
    """One Lemke path at pivot tolerance tol_piv; return (status, pivots, rho).

    rho: the smallest d_i / max|d| of all ratio-test candidates (1 if none). Status SOLVED
    means that z0 left the basis, RAY that no candidate was found; the caller checks both.
    Variables are numbered w_i = i, z_i = n + i, z0 = 2n.
    """
    n = q.shape[0]
    z0 = 2 * n
    for i in range(n):
        basis[i] = i
        where[i] = i
        where[n + i] = -1
        slot_of[i] = -1
        qbar[i] = q[i]
        d[i] = -1.0
    where[z0] = -1
    # First pivot: z0 enters with column d = -e; the leaving row is the lexicographic minimum
    # of [q, I]: the smallest q_i, ties to the largest index.
    limit = np.min(q) + tol_lex * _absmax(q)
    r = 0
    for i in range(n):
        if q[i] <= limit:
            r = i
    entering = z0
    k = 0  # number of stored columns of B^-1 (slots)
    pivots = 0
    rho = 1.0
    while True:
        # Pivot on row r: B^-1 <- E B^-1 and qbar <- E qbar, E the eta matrix of column d.
        # The next entering column is accumulated from each updated row of B^-1 while that row
        # is in cache.
        leaving = basis[r]
        dr = d[r]
        following = -1 if leaving == z0 else (leaving + n if leaving < n else leaving - n)
        if entering < n:  # column `entering` of B^-1 becomes the unit vector of row r
            s = slot_of[entering]
            k -= 1
            if s != k:
                for i in range(n):
                    G[s, i] = G[k, i]
                slot_col[s] = slot_col[k]
                slot_of[slot_col[s]] = s
            slot_of[entering] = -1
        basis[r] = entering
        where[leaving] = -1
        where[entering] = r
        if following >= n:  # z_m enters next: dnext = B^-1 a with a = -M[:, m]
            m = following - n
            for i in range(n):
                col[i] = -M[i, m]
            for i in range(n):
                dnext[i] = col[basis[i]] if basis[i] < n else 0.0
        for s in range(k):
            f = G[s, r] / dr
            if f != 0.0:
                for i in range(n):
                    G[s, i] -= f * d[i]
                G[s, r] = f
            if following >= n and col[slot_col[s]] != 0.0:
                c = col[slot_col[s]]
                for i in range(n):
                    dnext[i] += c * G[s, i]
        f = qbar[r] / dr
        for i in range(n):
            qbar[i] -= f * d[i]
        qbar[r] = f
        if leaving < n:  # column `leaving` of B^-1, the unit vector of row r, gets a slot
            for i in range(n):
                G[k, i] = -d[i] / dr
            G[k, r] = 1.0 / dr
            slot_col[k] = leaving
            slot_of[leaving] = k
            c = col[leaving]
            if c != 0.0:
                for i in range(n):
                    dnext[i] += c * G[k, i]
            k += 1
        pivots += 1
        if leaving == z0:
            return SOLVED, pivots, rho
        if pivots >= max_pivots:
            return MAX_PIVOTS, pivots, rho
        if following < n:  # w_m enters next: its column of B^-1
            s = slot_of[following]
            for i in range(n):
                dnext[i] = G[s, i]
        entering = following
        d, dnext = dnext, d

        # Ratio test on qbar (column -1 of the lexicographic rows); ties go to _lexbreak.
        dmax = _absmax(d)
        if not dmax < np.inf:
            return PIVOT_FAILURE, pivots, rho
        threshold = tol_piv * dmax
        ncand = 0
        vmin = np.inf
        dmin = dmax
        for i in range(n):
            if d[i] > threshold:
                rows[ncand] = i
                ratio[ncand] = qbar[i] / d[i]
                vmin = min(vmin, ratio[ncand])
                dmin = min(dmin, d[i])
                ncand += 1
        if ncand == 0:
            return RAY, pivots, rho
        rho = min(rho, dmin / dmax)
        if not np.isfinite(vmin):
            return PIVOT_FAILURE, pivots, rho
        scale = _absmax(qbar)
        limit = vmin + tol_lex * (scale if scale > 0.0 else 1.0) / dmax
        ntied = 0
        r = -1
        for a in range(ncand):
            if ratio[a] <= limit:
                rows[ntied] = rows[a]
                ntied += 1
                if rows[a] == where[z0]:
                    r = rows[a]
        if r < 0:
            r = rows[0] if ntied == 1 else _lexbreak(rows, ntied, ratio, d, dmax, G, where, slot_of, tol_lex)
            if r < 0:
                return PIVOT_FAILURE, pivots, rho


@jit
def _lexbreak(rows, ntied, ratio, d, dmax, G, where, slot_of, tol_lex):
    """Break a tie among rows[:ntied] on the columns of B^-1 in order (see module doc).

    Returns the row, or -1 if no column breaks the tie.
    """
    n = d.shape[0]
    for c in range(n):
        s = slot_of[c]  # -1: column c of B^-1 is the unit vector of row where[c]
        vmin = np.inf
        for a in range(ntied):
            i = rows[a]
            if s >= 0:
                v = G[s, i]
            else:
                v = 1.0 if where[c] == i else 0.0
            ratio[a] = v / d[i]
            vmin = min(vmin, ratio[a])
        scale = _absmax(G[s]) if s >= 0 else 1.0
        limit = vmin + tol_lex * (scale if scale > 0.0 else 1.0) / dmax
        kept = 0
        for a in range(ntied):
            if ratio[a] <= limit:
                rows[kept] = rows[a]
                kept += 1
        ntied = kept
        if ntied == 1:
            return rows[0]
    return -1


@jit
def _absmax(x):
    """max_i |x_i| of a 1-d array; NaN if an entry is NaN."""
    m = 0.0
    for v in x:
        a = abs(v)
        if a > m:
            m = a
        elif not a <= m:
            return np.nan
    return m


@jit
def _end_point(M, q, tol_lex, qbar, basis, z, w, zlist, status):
    """Write the basic point of the last basis (z clipped at 0, z0 dropped; w = M z + q).

    Return SOLVED if it passes the solution check of the module doc (whatever the path's
    status: a ray or a pivot limit met at z0 = 0 still carries a solution); otherwise the
    path's status, or PIVOT_FAILURE if the path claimed a solution.
    """
    n = q.shape[0]
    z[:] = 0.0
    nz = 0
    znorm = 0.0
    for i in range(n):
        b = basis[i]
        if n <= b < 2 * n:
            z[b - n] = qbar[i] if qbar[i] > 0.0 else 0.0
            zlist[nz] = b - n
            nz += 1
            znorm = max(znorm, z[b - n])
    qnorm = _absmax(q)
    ok = True
    for i in range(n):
        wi = q[i]
        mi = 0.0
        for a in range(nz):
            mij = M[i, zlist[a]]
            wi += mij * z[zlist[a]]
            mi += abs(mij)
        w[i] = wi
        zi = z[i] / znorm if znorm > 0.0 else 0.0
        if not abs(min(zi, wi / (qnorm + znorm * mi))) <= tol_lex:
            ok = False
    if ok:
        return SOLVED
    return PIVOT_FAILURE if status == SOLVED else status
