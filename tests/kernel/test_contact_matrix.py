"""The matrix of a contact LCP (mbds.kernel.contact_problem.build_matrix): its entries are
products of a W row with a Y = M^-1 W row taken only where both rows can be nonzero, and must
equal the full loops over all coordinates bit for bit, and the block formula of the module doc."""

from __future__ import annotations

import numpy as np
import pytest

from mbds.kernel.contact_problem import build_matrix
from mbds.kernel.linalg import cholesky, cholesky_solve_row, envelope
from tests.kernel.test_active_set import block_mass, couple_bodies
from tests.kernel.test_components import contacts_between

PAIRS = [(0, -1), (0, 1), (1, -1), (1, 2), (2, -1), (2, 3), (3, -1), (3, 4), (4, -1), (0, -1)]
"""Ten contacts of five bodies in a row on the ground (-1), the first one twice: wedged balls."""


def problem(mass, seed):
    """(WN, WT, YN, YT, stick, sign, laws) of the contacts PAIRS with a block mass matrix
    (free bodies), or one that couples bodies 1 and 3."""
    rng = np.random.default_rng(seed)
    M = block_mass(rng, 5)
    if mass == "coupled":
        M = couple_bodies(rng, M)
    WN, WT = contacts_between(rng, 5, PAIRS)
    L, profile = np.zeros_like(M), np.zeros((2, 15), np.int64)
    assert cholesky(M, L)
    envelope(L, profile)
    YN, YT = np.zeros_like(WN), np.zeros_like(WT)
    for i in range(len(PAIRS)):
        cholesky_solve_row(L, profile, WN, i, YN)
        cholesky_solve_row(L, profile, WT, i, YT)
    stick = rng.random(len(PAIRS)) < 0.6
    sign = np.where(rng.random(len(PAIRS)) < 0.5, -1.0, 1.0)
    laws = np.zeros((len(PAIRS), 4))
    laws[:, 0] = rng.uniform(0.0, 1.0, len(PAIRS))
    return M, WN, WT, YN, YT, stick, sign, laws


def kernel_matrix(WN, WT, YN, YT, stick, sign, laws, active):
    cap, n = WN.shape
    active = np.asarray(active, np.int64)
    A_flat = np.full(9 * cap * cap, np.nan)
    hrow, span = np.zeros(cap, np.int64), np.zeros((cap, 4), np.int64)
    nh = build_matrix(active, len(active), stick, sign, laws, WN, WT, YN, YT, np.zeros((cap, n)), hrow, span, A_flat)
    m = len(active) + 2 * nh
    return A_flat[: m * m].reshape(m, m), nh


def full_loops(WN, WT, YN, YT, stick, sign, laws, active):
    """The matrix with every product over all coordinates, in the kernel's order."""
    na = len(active)
    held = [a for a in range(na) if stick[active[a]]]
    nh = len(held)
    f = [laws[c, 0] * (1.0 if stick[c] else sign[c]) for c in active]
    columns = [YN[c] - f[a] * YT[c] for a, c in enumerate(active)]
    rows = [WN[c] for c in active] + [WT[active[a]] for a in held]
    right = columns + [YT[active[a]] for a in held]
    m = na + 2 * nh
    A = np.zeros((m, m))
    for i, w in enumerate(rows):
        for j, y in enumerate(right):
            s = 0.0
            for k in range(len(w)):
                s += w[k] * y[k]
            A[i, j] = s
    for g, a in enumerate(held):
        A[na + g, na + nh + g] = 1.0
        A[na + nh + g, a] = 2.0 * laws[active[a], 0]
        A[na + nh + g, na + g] = -1.0
    return A


@pytest.mark.parametrize("mass", ["blocks", "coupled"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_matrix_equals_the_full_loops_and_the_block_formula(mass, seed):
    M, WN, WT, YN, YT, stick, sign, laws = problem(mass, seed)
    active = np.random.default_rng(seed).permutation(len(PAIRS))[:8]
    A, nh = kernel_matrix(WN, WT, YN, YT, stick, sign, laws, active)
    assert np.array_equal(A, full_loops(WN, WT, YN, YT, stick, sign, laws, active))
    # the block formula of mbds.kernel.contact_problem's doc (N_G - W_H mu_H), with numpy's products
    held = active[stick[active]]
    mu = laws[:, 0]
    NG = (WN[active] - (mu[active] * np.where(stick[active], 1.0, sign[active]))[:, None] * WT[active]).T
    Minv = np.linalg.inv(M)
    na = len(active)
    assert np.allclose(A[:na, :na], WN[active] @ Minv @ NG, atol=1e-12)
    assert np.allclose(A[na : na + nh, na : na + nh], WT[held] @ Minv @ WT[held].T, atol=1e-12)


def test_contacts_no_mass_couples_have_exact_zeros():
    """Free bodies: an entry between contacts of different bodies is an exact zero, so the
    groups of mbds.kernel.components stay apart."""
    _, WN, WT, YN, YT, stick, sign, laws = problem("blocks", 4)
    active = np.array([0, 4, 8])  # bodies 0, 2 and 4 on the ground
    A, _ = kernel_matrix(WN, WT, YN, YT, stick, sign, laws, active)
    assert A[0, 1] == A[1, 2] == A[2, 0] == 0.0
    assert np.all(np.diag(A)[:3] != 0.0)
