"""Independent groups of contacts (mbds.kernel.components): contacts that no mass couples are
solved as separate LCPs, and those LCPs together solve the LCP of all contacts.

Source: the contact LCP's matrix is W^T M^-1 W (Pfeiffer and Glocker, "Multibody Dynamics with
Unilateral Contacts", Wiley 1996, ch. 6); with M block diagonal over bodies, its entries between
contacts of bodies that no chain of contacts links are exact zeros, so the LCP splits into one
LCP per group of linked bodies.
"""

from __future__ import annotations

import numpy as np
import pytest

from mbds.kernel.components import split_components
from mbds.kernel.lcp import SOLVED, lcp_workspace, lemke
from mbds.kernel.linalg import cholesky, cholesky_solve_row, envelope
from tests.kernel.test_active_set import block_mass


def contacts_between(rng, bodies, pairs):
    """Rows W_N, W_T of contacts between the bodies of ``pairs`` (a body index, or -1 for the
    fixed ground): random entries on the coordinates (3 per body) of the two bodies only."""
    n = 3 * bodies
    WN, WT = np.zeros((len(pairs), n)), np.zeros((len(pairs), n))
    for row, pair in enumerate(pairs):
        for body in pair:
            if body >= 0:
                WN[row, 3 * body : 3 * body + 3] = rng.standard_normal(3)
                WT[row, 3 * body : 3 * body + 3] = rng.standard_normal(3)
    return WN, WT


def split(WN, WT, M, active):
    """split_components of the contacts ``active`` with mass matrix M: (groups, reordered active)."""
    n = M.shape[0]
    L, profile = np.zeros((n, n)), np.zeros((2, n), np.int64)
    assert cholesky(M, L)
    envelope(L, profile)
    YN, YT = np.zeros_like(WN), np.zeros_like(WT)
    for i in range(len(WN)):  # as the kernel solves them (exact zeros outside a block)
        cholesky_solve_row(L, profile, WN, i, YN)
        cholesky_solve_row(L, profile, WT, i, YT)
    active = np.array(active, dtype=np.int64)
    na = len(active)
    group, root, grouped = np.zeros(na + 1, np.int64), np.zeros(na, np.int64), np.zeros(na, np.int64)
    masks = np.zeros((2, na, (M.shape[0] + 63) // 64), np.uint64)
    ng = split_components(active, na, WN, WT, YN, YT, group, root, grouped, masks)
    return [list(active[group[g] : group[g + 1]]) for g in range(ng)]


def linked_groups(pairs, active):
    """The expected groups: contacts linked through shared bodies (the ground links nothing),
    ordered by their first contact, each in its contacts' order."""
    groups: list[list[int]] = []
    for c in active:
        bodies = {b for b in pairs[c] if b >= 0}
        joined = [g for g in groups if any(bodies & {b for b in pairs[e] if b >= 0} for e in g)]
        merged = sorted((e for g in joined for e in g), key=list(active).index) + [c]
        groups = [g for g in groups if g not in joined]
        groups.append(merged)
        groups.sort(key=lambda g: list(active).index(g[0]))
    return groups


@pytest.mark.parametrize("seed", range(20))
def test_groups_are_the_bodies_linked_by_contacts(seed):
    rng = np.random.default_rng(seed)
    bodies = int(rng.integers(2, 7))
    pairs = [(int(rng.integers(0, bodies)), int(rng.integers(-1, bodies))) for _ in range(int(rng.integers(1, 10)))]
    M = block_mass(rng, bodies)
    WN, WT = contacts_between(rng, bodies, pairs)
    active = list(rng.permutation(len(pairs)))
    assert split(WN, WT, M, active) == linked_groups(pairs, active)


def test_a_mass_matrix_that_couples_the_bodies_makes_one_group():
    """Bodies coupled through M (a joint eliminated into generalized coordinates) are one group
    even when no contact links them."""
    rng = np.random.default_rng(1)
    A = rng.standard_normal((6, 6))
    M = A @ A.T + 6 * np.eye(6)
    WN, WT = contacts_between(rng, 2, [(0, -1), (1, -1), (0, -1)])
    assert split(WN, WT, M, [2, 0, 1]) == [[2, 0, 1]]


def test_the_groups_lcps_solve_the_lcp_of_all_contacts():
    """Solving each group's LCP (normal contacts, A = W M^-1 W^T) gives Lemke's solution of the
    whole LCP, whose matrix has exact zeros between groups."""
    rng = np.random.default_rng(7)
    pairs = [(0, -1), (1, -1), (0, 1), (2, -1), (3, 2), (3, -1)]
    M = block_mass(rng, 4)
    WN, _ = contacts_between(rng, 4, pairs)
    A = WN @ np.linalg.solve(M, WN.T)
    q = rng.standard_normal(len(pairs))

    def lemke_solution(A, q):
        fwork, iwork = lcp_workspace(len(q))
        z, w = np.zeros(len(q)), np.zeros(len(q))
        status, _ = lemke(np.ascontiguousarray(A), q.copy(), z, w, 1e-14, 1e-10, 1e-8, 10000, fwork, iwork)
        assert status == SOLVED
        return z

    whole = lemke_solution(A, q)
    groups = split(WN, np.zeros_like(WN), M, range(len(pairs)))
    assert groups == [[0, 1, 2], [3, 4, 5]]
    parts = np.zeros(len(pairs))
    for g in groups:
        parts[g] = lemke_solution(A[np.ix_(g, g)], q[g])
    assert np.allclose(parts, whole, rtol=1e-10, atol=1e-12)
    assert np.all(A[np.ix_(groups[0], groups[1])] == 0.0)
