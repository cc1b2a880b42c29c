"""Small dense linear algebra without allocation: Cholesky factorisation and solves."""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit


@jit(refcount=False)
def cholesky(A, L):
    """Lower-triangular L with L L^T = A (A symmetric positive definite, (n, n)).

    Returns False (L undefined) when A is not positive definite or not finite.
    """
    n = A.shape[0]
    for j in range(n):
        s = A[j, j]
        for k in range(j):
            s -= L[j, k] * L[j, k]
        if not s > 0.0:
            return False
        d = np.sqrt(s)
        L[j, j] = d
        for i in range(j + 1, n):
            s = A[i, j]
            for k in range(j):
                s -= L[i, k] * L[j, k]
            L[i, j] = s / d
        for i in range(j):
            L[i, j] = 0.0
    return True


@jit(refcount=False)
def envelope(L, profile):
    """The nonzero envelope of a lower-triangular L (n, n) into profile (2, n) int64: profile[0, r]
    the first nonzero column of row r, profile[1, r] the last nonzero row of column r (for a
    block-diagonal M, e.g. free bodies, L is block-diagonal and the solves below skip the zeros
    between the blocks)."""
    n = L.shape[0]
    for r in range(n):
        first = r
        for k in range(r):
            if L[r, k] != 0.0:
                first = k
                break
        profile[0, r] = first
        last = r
        for k in range(n - 1, r, -1):
            if L[k, r] != 0.0:
                last = k
                break
        profile[1, r] = last


@jit(refcount=False)
def cholesky_solve(L, profile, b, x):
    """x = A^-1 b for A = L L^T (b and x (n,); they may be the same array); profile: the
    envelope of L (:func:`envelope`). Only products with entries of L outside the envelope,
    which are exact zeros, are left out: the result equals that of the full loops."""
    n = L.shape[0]
    for i in range(n):
        s = b[i]
        for k in range(profile[0, i], i):
            s -= L[i, k] * x[k]
        x[i] = s / L[i, i]
    for i in range(n - 1, -1, -1):
        s = x[i]
        for k in range(i + 1, profile[1, i] + 1):
            s -= L[k, i] * x[k]
        x[i] = s / L[i, i]


@jit(inline="always")
def cholesky_solve_row(L, profile, B, i, X):
    """X[i] = A^-1 B[i] for A = L L^T (rows i of B and X, without array views); profile: the
    envelope of L (:func:`envelope`).

    The leading zeros of B[i], the rows of the forward and backward solutions that no nonzero
    reaches through the envelope of L (exact zeros) and the entries of L outside its envelope
    are skipped (a contact row touches the coordinates of two bodies only); the terms left out
    are products with exact zeros, so the result equals that of the full loops."""
    n = L.shape[0]
    first = 0
    while first < n and B[i, first] == 0.0:
        X[i, first] = 0.0
        first += 1
    reach = n - 1  # the last row that a nonzero so far can reach: B's last nonzero or a column's envelope
    while reach >= first and B[i, reach] == 0.0:
        reach -= 1
    last = -1
    for r in range(first, n):
        if r > reach:
            break
        s = B[i, r]
        for k in range(max(first, profile[0, r]), r):
            s -= L[r, k] * X[i, k]
        X[i, r] = s / L[r, r]
        if X[i, r] != 0.0:
            last = r
            reach = max(reach, profile[1, r])
    for r in range(n - 1, last, -1):
        X[i, r] = 0.0
    low = first  # the first nonzero of X so far: a row whose column of L ends above it stays 0
    for r in range(last, -1, -1):
        if r < first and profile[1, r] < low:
            continue  # (X[i, r] is already 0)
        s = X[i, r]
        for k in range(r + 1, min(last, profile[1, r]) + 1):
            s -= L[k, r] * X[i, k]
        X[i, r] = s / L[r, r]
        if X[i, r] != 0.0:
            low = r


@jit(refcount=False)
def gauss_solve(A, x, k, tol_piv):
    """x[:k] <- A^-1 x[:k] for A (k, k) by Gaussian elimination with partial pivoting (A is
    overwritten); False when a pivot is not above tol_piv * max|A| (A singular within that
    tolerance) or anything is not finite."""
    amax = 0.0
    for a in range(k):
        for b in range(k):
            amax = max(amax, abs(A[a, b]))
    if not amax < np.inf:
        return False
    for c in range(k):
        p = c
        for r in range(c + 1, k):
            if abs(A[r, c]) > abs(A[p, c]):
                p = r
        if not abs(A[p, c]) > tol_piv * amax:
            return False
        if p != c:
            for b in range(c, k):
                A[c, b], A[p, b] = A[p, b], A[c, b]
            x[c], x[p] = x[p], x[c]
        for r in range(c + 1, k):
            f = A[r, c] / A[c, c]
            if f != 0.0:
                for b in range(c + 1, k):
                    A[r, b] -= f * A[c, b]
                x[r] -= f * x[c]
    for r in range(k - 1, -1, -1):
        s = x[r]
        for b in range(r + 1, k):
            s -= A[r, b] * x[b]
        x[r] = s / A[r, r]
        if not np.isfinite(x[r]):
            return False
    return True


@jit
def lu_solve(A, b):
    """x = A^-1 b by Gaussian elimination with partial pivoting (A (n, n) and b (n,) are not
    changed).  Returns (x, ok); ok is False when a pivot is zero or anything is not finite."""
    x = b.copy()
    return x, gauss_solve(A.copy(), x, A.shape[0], 0.0)


@jit
def gram(D):
    """D D^T of D (m, n), without BLAS (whose addresses would keep numba from caching)."""
    m, n = D.shape
    G = np.zeros((m, m))
    for i in range(m):
        for k in range(m):
            s = 0.0
            for j in range(n):
                s += D[i, j] * D[k, j]
            G[i, k] = s
    return G


@jit
def min_norm_solve(D, b):
    """The least-norm x with D x = b for D (m, n) of full row rank: x = D^T (D D^T)^-1 b.
    Returns (x, ok); ok is False when D D^T is singular (redundant rows)."""
    m, n = D.shape
    y, ok = lu_solve(gram(D), b)
    x = np.zeros(n)
    for i in range(m):
        for j in range(n):
            x[j] += D[i, j] * y[i]
    return x, ok


@jit(inline="always")
def span_dot(A, i, B, j, span, a):
    """sum_k A[i, k] B[j, k] (row i of A with row j of B, no array views), over the columns
    span[a, 0] <= k < span[a, 1] outside which row i of A is zero
    (mbds.kernel.contact_problem.row_spans): the products left out are with exact zeros, so the
    sum is that over all columns."""
    s = 0.0
    for k in range(span[a, 0], span[a, 1]):
        s += A[i, k] * B[j, k]
    return s


@jit(inline="always")
def pivoted_cholesky(G, perm, n, tol):
    """Factorise the symmetric positive semidefinite n x n matrix whose lower triangle G holds, in
    place, by Cholesky with diagonal pivoting (perm: the order of the rows, set here); stop at
    the first pivot not above ``tol`` times the largest diagonal entry. Returns the rank r: the
    rows perm[r:] depend on the others."""
    top = 0.0
    for i in range(n):
        perm[i] = i
        top = max(top, G[i, i])
    for j in range(n):
        p = j
        for i in range(j + 1, n):
            if G[i, i] > G[p, p]:
                p = i
        if not G[p, p] > tol * top:
            return j
        if p != j:
            _swap_symmetric(G, perm, n, j, p)
        pivot = np.sqrt(G[j, j])
        G[j, j] = pivot
        for i in range(j + 1, n):
            G[i, j] /= pivot
        for i in range(j + 1, n):
            for c in range(j + 1, i + 1):
                G[i, c] -= G[i, j] * G[c, j]
    return n


@jit(inline="always")
def pivoted_cholesky_solve(G, perm, r, b, x):
    """x[:r] = the solution of the factorised rows of :func:`pivoted_cholesky` (rank r) for the
    right-hand side b (in the original order): L y = P^T b, then L^T x = y."""
    for j in range(r):
        s = b[perm[j]]
        for k in range(j):
            s -= G[j, k] * x[k]
        x[j] = s / G[j, j]
    for j in range(r - 1, -1, -1):
        s = x[j]
        for k in range(j + 1, r):
            s -= G[k, j] * x[k]
        x[j] = s / G[j, j]


@jit(inline="always")
def _swap_symmetric(G, perm, n, j, p):
    """Swap coordinates j < p of the symmetric n x n matrix whose lower triangle G holds (rows
    and columns alike; the factor's columns left of j move with their rows) and in perm."""
    perm[j], perm[p] = perm[p], perm[j]
    for c in range(j):
        G[j, c], G[p, c] = G[p, c], G[j, c]
    G[j, j], G[p, p] = G[p, p], G[j, j]
    for i in range(j + 1, p):
        G[i, j], G[p, i] = G[p, i], G[i, j]
    for i in range(p + 1, n):
        G[i, j], G[i, p] = G[i, p], G[i, j]
