"""Lemke's complementary pivot algorithm with a lexicographic ratio test.

Solves LCP(M, q): find z >= 0 with w = M z + q >= 0 and z.w = 0, for a dense M of shape (n, n)
(neither symmetry nor the P-property is assumed) and q of shape (n,). The module is unit-free:
M and q carry whatever units the caller's problem has.

Method. The system w - M z - e z0 = q (covering vector e = ones) is pivoted from the basis
{w}: z0 enters first, replacing the row of the smallest q_i; then the complement of the
variable that just left enters, until z0 leaves (solved) or the entering column has no
positive entry (secondary ray). The basis inverse B^-1 is kept explicitly but compactly: a
column j of B^-1 whose w_j is basic is the unit vector of w_j's row, so only the k columns
with w_j non-basic are stored, transposed (``G[s, :]`` is column ``slot_col[s]`` of B^-1).
A pivot updates them (2 n k flops) and forms the next entering column from them (2 n k),
in contiguous loops, without allocation. q >= 0 is answered with z = 0 and no pivot.

Ratio test. Rows i with d_i > tol_piv * max|d| (d: the entering column) are candidates. The
chosen row is the lexicographic minimum of (qbar_i, B^-1[i, 0], ..., B^-1[i, n-1]) / d_i over
the candidates, compared column by column: in column c, rows whose ratio exceeds the column's
minimum ratio by at most tol_lex * max_i |c_i| / max|d| (max over all rows) tie and go on to
the next column. If the row of z0 ties on qbar, z0 leaves: the step ends on a solution. The
rule keeps every row of [qbar, B^-1] lexicographically positive, so no basis repeats and the
method cannot cycle (in exact arithmetic; tol_lex must exceed the rounding noise, see
docs/lcp.md).

Tolerances (arguments, never globals):

- ``tol_piv_min``, ``tol_piv_max`` (``.wld`` keys ``LCPPivotToleranceMin``, ``Max``): the
  smallest entering-column entry, relative to max|d|, accepted as positive in the ratio test.
  The first attempt uses ``tol_piv_min``, so small but genuine pivots are taken (exact Lemke).
  If the attempt does not end on a verified solution (ray, pivot limit, failure), the problem
  is solved again from scratch with the tolerance raised by decades (capped at
  ``tol_piv_max``) to the first value at or above rho, the smallest relative candidate entry
  the attempt met: a smaller raise would exclude no candidate and repeat the same path. When
  rho exceeds ``tol_piv_max`` the status is final.
- ``tol_lex`` (``LCPLexicoZeroTolerance``): the relative size below which a difference counts
  as zero: ties in the ratio test (above) and the acceptance of the end point. With
  s_i = max|q| + max(z) sum_{j: z_j basic} |M_ij|, the basic point is a solution iff
  |min(z_i / max(z), w_i / s_i)| <= tol_lex for every i (w recomputed as M z + q).

Statuses: SOLVED (also for a ray or pivot limit met on a point that passes the check, e.g.
a ray with z0 = 0), RAY, MAX_PIVOTS, PIVOT_FAILURE. Pivot count: every basis change, the
first (z0 enters) and the last (z0 leaves) included, summed over the tolerance attempts.
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
    """Workspace of LCPs of size <= n: (float64 array of n*n + 5n, int64 array of 7n + 1)."""
    return np.empty(n * n + 5 * n), np.empty(7 * n + 1, dtype=np.int64)


@jit(refcount=False)
def lemke(M, q, z, w, tol_piv_min, tol_piv_max, tol_lex, max_pivots, fwork, iwork):
    """Solve LCP(M, q) into z, w (both (n,), overwritten); return (status, pivots).

    M: (n, n) float64 (any strides, C order is fastest); q: (n,) float64; max_pivots: limit
    per tolerance attempt; fwork, iwork: from :func:`lcp_workspace` of any size >= n. z, w are
    the basic point of the last basis (z clipped at 0, w = M z + q) whatever the status.
    """
    n = q.shape[0]
    if n == 0 or _min(q) >= 0.0:
        for i in range(n):
            z[i] = 0.0
            w[i] = q[i]
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
            M, q, tol_piv, tol_lex, max_pivots,
            G, qbar, d, dnext, col, ratio, basis, where, slot_col, slot_of, rows,
        )
        total += pivots
        status = _end_point(M, q, tol_lex, qbar, basis, z, w, zlist, col, status)
        if status == SOLVED or rho > tol_piv_max:
            return status, total
        while tol_piv < rho:  # smaller raises would repeat the same path
            tol_piv = min(10.0 * tol_piv, tol_piv_max)


@jit(refcount=False)
def _attempt(
    M, q, tol_piv, tol_lex, max_pivots, G, qbar, d, dnext, col, ratio, basis, where, slot_col, slot_of, rows
):
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
    limit = _min(q) + tol_lex * absmax(q)
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
        dmax = absmax(d)
        if not dmax < np.inf:
            return PIVOT_FAILURE, pivots, rho
        threshold = tol_piv * dmax
        ncand = 0
        vmin = np.inf
        dmin = dmax
        scale = 0.0
        for i in range(n):  # branch-free: rows that are not candidates get ratio inf
            candidate = d[i] > threshold
            ncand += candidate
            ratio[i] = qbar[i] / d[i] if candidate else np.inf
            vmin = min(vmin, ratio[i])
            dmin = min(dmin, d[i] if candidate else dmax)
            scale = max(scale, abs(qbar[i]))
        if ncand == 0:
            return RAY, pivots, rho
        rho = min(rho, dmin / dmax)
        if not np.isfinite(vmin):
            return PIVOT_FAILURE, pivots, rho
        limit = vmin + tol_lex * (scale if scale > 0.0 else 1.0) / dmax
        r = where[z0]
        if ratio[r] > limit:  # z0 is not among the tied rows
            ntied = 0
            for i in range(n):
                if ratio[i] <= limit:
                    rows[ntied] = i
                    ntied += 1
            r = rows[0] if ntied == 1 else _lexbreak(rows, ntied, ratio, d, dmax, G, where, slot_of, tol_lex)
            if r < 0:
                return PIVOT_FAILURE, pivots, rho


@jit(refcount=False)
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
        scale = absmax(G[s]) if s >= 0 else 1.0
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


@jit(refcount=False)
def _min(x):
    """min_i x_i of a non-empty 1-d array; NaN if an entry is NaN (as np.min, which allocates)."""
    m = x[0]
    for v in x:
        if v < m:
            m = v
        elif not v >= m:
            return np.nan
    return m


@jit(refcount=False)
def absmax(x):
    """max_i |x_i| of a 1-d array; NaN if an entry is NaN."""
    m = 0.0
    for v in x:
        a = abs(v)
        if a > m:
            m = a
        elif not a <= m:
            return np.nan
    return m


@jit(refcount=False)
def _end_point(M, q, tol_lex, qbar, basis, z, w, zlist, msum, status):
    """Write the basic point of the last basis (z clipped at 0, z0 dropped; w = M z + q).

    msum: (n,) scratch.
    Return SOLVED if it passes the solution check of the module doc (whatever the path's
    status: a ray or a pivot limit met at z0 = 0 still carries a solution); otherwise the
    path's status, or PIVOT_FAILURE if the path claimed a solution.
    """
    n = q.shape[0]
    for i in range(n):
        z[i] = 0.0
    nz = 0
    for i in range(n):
        b = basis[i]
        if n <= b < 2 * n:
            z[b - n] = qbar[i] if qbar[i] > 0.0 else 0.0
            zlist[nz] = b - n
            nz += 1
    if check_solution(M, q, tol_lex, z, w, zlist, nz, msum) == 0:
        return SOLVED
    return PIVOT_FAILURE if status == SOLVED else status


@jit(refcount=False)
def check_solution(M, q, tol_lex, z, w, zlist, nz, msum):
    """w = M z + q for z >= 0 with nonzeros only at zlist[:nz]; return the number of rows that
    fail the solution check of the module doc (0: z, w solve the LCP). msum: (n,) scratch."""
    for i in range(q.shape[0]):
        w[i] = q[i]
        msum[i] = 0.0
    add_columns(M, z, w, zlist, 0, nz, msum)
    return failed_rows(q, tol_lex, z, w, zlist, nz, msum)


@jit(inline="always")
def add_columns(M, z, w, zlist, start, nz, msum):
    """w += M[:, j] z[j] and msum += |M[:, j]| for the columns j in zlist[start:nz], column by
    column (independent sums over the rows): after the columns zlist[:start], the same sums as
    over zlist[:nz] at once."""
    for a in range(start, nz):
        j = zlist[a]
        for i in range(M.shape[0]):
            w[i] += M[i, j] * z[j]
            msum[i] += abs(M[i, j])


@jit(inline="always")
def failed_rows(q, tol_lex, z, w, zlist, nz, msum):
    """The number of rows of w = M z + q (z nonzero only at zlist[:nz], msum the sums of |M| over
    those columns) that fail the solution check of the module doc."""
    n = q.shape[0]
    znorm = 0.0
    for a in range(nz):
        znorm = max(znorm, z[zlist[a]])
    qnorm = absmax(q)
    failed = 0
    for i in range(n):
        zi = z[i] / znorm if znorm > 0.0 else 0.0
        if not abs(min(zi, w[i] / (qnorm + znorm * msum[i]))) <= tol_lex:
            failed += 1
    return failed
