"""Small dense linear algebra without allocation: Cholesky factorisation and solves."""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit


@jit
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


@jit
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
