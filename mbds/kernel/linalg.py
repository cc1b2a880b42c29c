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
def cholesky_solve(L, b, x):
    """x = A^-1 b for A = L L^T (b and x (n,); they may be the same array)."""
    n = L.shape[0]
    for i in range(n):
        s = b[i]
        for k in range(i):
            s -= L[i, k] * x[k]
        x[i] = s / L[i, i]
    for i in range(n - 1, -1, -1):
        s = x[i]
        for k in range(i + 1, n):
            s -= L[k, i] * x[k]
        x[i] = s / L[i, i]


@jit(inline="always")
def cholesky_solve_row(L, B, i, X):
    """X[i] = A^-1 B[i] for A = L L^T (rows i of B and X, without array views)."""
    n = L.shape[0]
    for r in range(n):
        s = B[i, r]
        for k in range(r):
            s -= L[r, k] * X[i, k]
        X[i, r] = s / L[r, r]
    for r in range(n - 1, -1, -1):
        s = X[i, r]
        for k in range(r + 1, n):
            s -= L[k, r] * X[i, k]
        X[i, r] = s / L[r, r]


@jit
def lu_solve(A, b):
    """x = A^-1 b by Gaussian elimination with partial pivoting (A (n, n) and b (n,) are not
    changed).  Returns (x, ok); ok is False when a pivot is zero or not finite (A singular)."""
    n = A.shape[0]
    M = A.copy()
    x = b.copy()
    for k in range(n):
        pivot = k
        for i in range(k + 1, n):
            if abs(M[i, k]) > abs(M[pivot, k]):
                pivot = i
        if not (abs(M[pivot, k]) > 0.0 and np.isfinite(M[pivot, k])):
            return x, False
        if pivot != k:
            for j in range(k, n):
                M[k, j], M[pivot, j] = M[pivot, j], M[k, j]
            x[k], x[pivot] = x[pivot], x[k]
        for i in range(k + 1, n):
            factor = M[i, k] / M[k, k]
            if factor != 0.0:
                for j in range(k + 1, n):
                    M[i, j] -= factor * M[k, j]
                x[i] -= factor * x[k]
    for i in range(n - 1, -1, -1):
        s = x[i]
        for j in range(i + 1, n):
            s -= M[i, j] * x[j]
        x[i] = s / M[i, i]
    return x, True


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
