"""The contact-force LCP of a single contact (mbds.kernel.contact_problem.build_matrix with
na = 1) in closed form, where its solution is provably unique.

A sliding contact (nh = 0) gives LCP(A, q) of size 1: z = -q / A for q < 0 < A. This is the
very division Lemke's method ends with on that problem (its two pivots compute -q and then
-q / A, nothing else), so the answer is Lemke's to the last bit.

A stick candidate (nh = 1) gives size 3, z = (lambda_N, lambda_0R, gT''^-) and
w = (gN'', gT''^+, lambda_0L):

    A = [ Dnn - mu Dnt   Dnt   0 ]        D = [ Dnn  Dnt ]  = [ w_N ] M^-1 [ w_N  w_T ]
        [ Dtn - mu Dtt   Dtt   1 ]            [ Dtn  Dtt ]    [ w_T ]
        [ 2 mu           -1    0 ]

Coulomb's law at one contact: for a given lambda_N the tangential problem (Dtt > 0) has one
solution lambda_T(lambda_N), piecewise linear; gN'' = Dnn lambda_N + Dnt lambda_T + q_N then
rises with lambda_N with slope det(D) / Dtt while sticking and Dnn -+ mu Dnt while sliding
forwards or backwards. Where all three slopes are positive, gN'' is strictly increasing, so
lambda_N >= 0, gN'' >= 0, lambda_N gN'' = 0 has one solution, and with it lambda_T, lambda_0R
and the slip rates: the LCP has exactly one solution, and any method that finds a solution
finds this one (Lemke's within its round-off). The slopes are required to exceed
UNIQUE_MARGIN relative to the sizes of their terms; otherwise (near Painleve's paradox, a
singular D, or mu = 0) the caller uses Lemke's method.

With q_N < 0 the contact is pressed and the solution is one of three: stick (gN'' = gT'' = 0,
0 <= lambda_0R <= 2 mu lambda_N), slide forwards (lambda_0R = 0, gT''^+ >= 0) or slide
backwards (lambda_0L = 0, gT''^- >= 0). Each is solved from its two equations and taken when
its signs hold and it passes Lemke's solution check (mbds.kernel.lcp.check_solution) on the
same data; when none does (a solution on the border between two, in round-off), the caller
uses Lemke's method.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit
from mbds.kernel.lcp import check_solution

UNIQUE_MARGIN = 1e-6
"""The slopes of gN'' over lambda_N (det(D) / Dtt, Dnn - mu Dnt, Dnn + mu Dnt) must exceed
UNIQUE_MARGIN times the sum of the magnitudes of their terms: uniqueness then holds with a
margin far above round-off."""


@jit(refcount=False)
def solve_one_contact(A, q, z, w, nh, tol_lex, zlist, msum):
    """Solve the LCP (A, q) of one contact (nh = 0: size 1, nh = 1: size 3) into z, w where its
    solution is unique and the contact is pressed (q[0] < 0); return False (z, w then hold
    anything) when the caller must use Lemke's method. zlist (int64, >= 3), msum (>= 3): scratch."""
    if not q[0] < 0.0:
        return False
    if nh == 0:
        if not 0.0 < A[0, 0] < np.inf:
            return False
        z[0] = -q[0] / A[0, 0]
        zlist[0] = 0
        return check_solution(A, q, tol_lex, z, w, zlist, 1, msum) == 0
    if not _unique(A):
        return False
    two_mu = A[2, 0]
    # stick: the 2 x 2 system of rows gN'' = 0 and gT''^+ = 0
    det = A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
    lam_n = (A[0, 1] * q[1] - A[1, 1] * q[0]) / det
    reserve = (A[1, 0] * q[0] - A[0, 0] * q[1]) / det
    if lam_n > 0.0 and reserve >= 0.0 and two_mu * lam_n - reserve + q[2] >= 0.0:
        return _accept(A, q, z, w, lam_n, reserve, 0.0, tol_lex, zlist, msum)
    # slide forwards: lambda_0R = 0 (lambda_T = -mu lambda_N), gN'' = 0
    lam_n = -q[0] / A[0, 0]
    if lam_n > 0.0 and A[1, 0] * lam_n + q[1] >= 0.0 and two_mu * lam_n + q[2] >= 0.0:
        return _accept(A, q, z, w, lam_n, 0.0, 0.0, tol_lex, zlist, msum)
    # slide backwards: lambda_0L = 0 (lambda_0R = 2 mu lambda_N + q_L), gN'' = 0
    lam_n = -(q[0] + A[0, 1] * q[2]) / (A[0, 0] + A[0, 1] * two_mu)
    reserve = two_mu * lam_n + q[2]
    slip = -(A[1, 0] * lam_n + A[1, 1] * reserve + q[1])
    if lam_n > 0.0 and reserve >= 0.0 and slip >= 0.0:
        return _accept(A, q, z, w, lam_n, reserve, slip, tol_lex, zlist, msum)
    return False


@jit(inline="always")
def _unique(A):
    """Whether the slopes of gN'' over lambda_N (module doc) are positive with UNIQUE_MARGIN."""
    mu = 0.5 * A[2, 0]
    if not mu > 0.0 or A[2, 1] != -1.0 or A[1, 2] != 1.0:
        return False
    d_nt, d_tt = A[0, 1], A[1, 1]
    d_nn = A[0, 0] + mu * d_nt
    d_tn = A[1, 0] + mu * d_tt
    if not (d_tt > 0.0 and d_nn > 0.0):
        return False
    slope_stick = d_nn * d_tt - d_nt * d_tn
    forwards = d_nn - mu * d_nt
    backwards = d_nn + mu * d_nt
    size = d_nn + mu * abs(d_nt)
    return (slope_stick > UNIQUE_MARGIN * (d_nn * d_tt + abs(d_nt * d_tn))
            and forwards > UNIQUE_MARGIN * size and backwards > UNIQUE_MARGIN * size)


@jit(inline="always")
def _accept(A, q, z, w, lam_n, reserve, slip, tol_lex, zlist, msum):
    """z = (lam_n, reserve, slip) with its nonzeros listed; True when it passes Lemke's check."""
    z[0], z[1], z[2] = lam_n, reserve, slip
    nz = 0
    for i in range(3):
        if z[i] != 0.0:
            zlist[nz] = i
            nz += 1
    return check_solution(A, q, tol_lex, z, w, zlist, nz, msum) == 0
