"""The contact-state fast path of the contact LCPs (mbds.kernel.active_set) and the sparse
solves it relies on (mbds.kernel.linalg): every answer it accepts solves the same LCP as
Lemke's method, and the sparse solves equal the dense ones."""

from __future__ import annotations

import numpy as np
import pytest

from mbds.kernel.active_set import (
    OPEN,
    OPEN_NEG,
    OPEN_STICK,
    PRESSED,
    SLIDE_NEG,
    SLIDE_POS,
    recall_states,
    remember_states,
    solve_states,
)
from mbds.kernel.lcp import SOLVED, lcp_workspace, lemke
from mbds.kernel.linalg import cholesky, cholesky_solve, cholesky_solve_row, envelope, gauss_solve
from tests.kernel.test_lcp import friction_lcp, residual

TOL_PIV, TOL_LEX = 1e-10, 1e-8


def lemke_states(M, q, c):
    """Lemke's solution of a friction LCP with c contacts (all stick candidates) and its states."""
    fwork, iwork = lcp_workspace(len(q))
    z, w = np.zeros(len(q)), np.zeros(len(q))
    status, _ = lemke(M, q, z, w, 1e-14, TOL_PIV, TOL_LEX, 10000, fwork, iwork)
    memory = np.zeros((c, 3), dtype=np.int64)
    active = np.arange(c)
    remember_states(active, c, c, active, active, active, z, w, memory)
    return status, z, memory[:, 2].copy()


def states_solution(M, q, c, state, rounds=4):
    fwork, iwork = lcp_workspace(len(q))
    z, w = np.zeros(len(q)), np.zeros(len(q))
    ok = solve_states(M, q, z, w, c, c, np.arange(c), state, rounds, TOL_PIV, TOL_LEX, 10000, fwork, iwork)
    return ok, z, w


def test_states_of_the_lemke_solution_give_a_solution_of_the_same_lcp():
    """Started from the states of Lemke's solution, the fast path solves the LCP (whenever it
    accepts an answer, that answer passes the residual test of Lemke's solutions)."""
    accepted = 0
    for seed in range(60):
        rng = np.random.default_rng(seed)
        c = int(rng.integers(1, 6))
        M, q = friction_lcp(rng, c, 0, int(rng.integers(1, 4)))
        status, _, state = lemke_states(M, q, c)
        if status != SOLVED:  # a ray: no state to start from
            continue
        ok, z, w = states_solution(M, q, c, state.copy())
        if ok:
            accepted += 1
            assert residual(M, q, z, w) <= 1e-8
            assert np.allclose(M @ z + q, w, atol=1e-10 * max(1.0, np.abs(w).max()))
    assert accepted >= 30


def test_fast_path_mostly_hits_from_the_lemke_states():
    """On non-degenerate friction problems the states of the solution are a solution (the
    fast path's purpose): at least 80 % are accepted at once, with Lemke's forces."""
    hits = same = tried = 0
    for seed in range(200):
        rng = np.random.default_rng(1000 + seed)
        c = int(rng.integers(1, 5))
        M, q = friction_lcp(rng, c, 0, c)
        q[c:] += 1e-3 * rng.standard_normal(2 * c) * (q[c:] != 0)  # no exact ties
        status, z_lemke, state = lemke_states(M, q, c)
        if status != SOLVED:
            continue
        tried += 1
        ok, z, w = states_solution(M, q, c, state.copy(), rounds=0)
        if ok:
            hits += 1
            assert residual(M, q, z, w) <= 1e-8
            same += np.allclose(z[:c], z_lemke[:c], rtol=1e-6, atol=1e-9 * np.abs(z_lemke).max())
    assert tried >= 150
    assert hits >= 0.8 * tried
    assert same >= 0.9 * hits


def expansion_lcp(rng, c):
    """A friction LCP of the expansion phase of an impact with c contacts: the third block of q
    is the cone 2 mu Lambda_N of the impulses so far (mbds.kernel.impact), positive for most
    contacts, so a contact may take a tangential increment without a normal one."""
    M, q = friction_lcp(rng, c, 0, c)
    q[c:2 * c] += 1e-3 * rng.standard_normal(c)  # no exact ties
    impulses = rng.uniform(0.0, 1.0, c) * (rng.random(c) < 0.8)
    q[2 * c:] = M[2 * c:, :c].diagonal() * impulses  # 2 mu Lambda_N
    return M, q


def test_fast_path_hits_expansion_problems():
    """The expansion LCP of an impact (tangential reserves already in the cone): from the
    states of Lemke's solution the fast path answers at least 80 % at once, with Lemke's
    impulses, and among them contacts that take a tangential increment without a normal one
    (states OPEN_STICK and OPEN_NEG, without which such problems always fell back to Lemke)."""
    hits = same = tried = 0
    seen = set()
    for seed in range(300):
        rng = np.random.default_rng(5000 + seed)
        c = int(rng.integers(1, 5))
        M, q = expansion_lcp(rng, c)
        status, z_lemke, state = lemke_states(M, q, c)
        if status != SOLVED:
            continue
        tried += 1
        seen.update(int(s) for s in state)
        ok, z, w = states_solution(M, q, c, state.copy(), rounds=0)
        if ok:
            hits += 1
            assert residual(M, q, z, w) <= 1e-8
            same += np.allclose(z[:2 * c], z_lemke[:2 * c], rtol=1e-6, atol=1e-9 * np.abs(z_lemke).max())
    assert {OPEN_STICK, OPEN_NEG} <= seen
    assert tried >= 250
    assert hits >= 0.8 * tried
    assert same >= 0.9 * hits


@pytest.mark.parametrize("infeasibility, kept", [(1e-10, True), (1e-6, False)])
def test_a_state_changes_only_where_the_point_fails_lemkes_solution_check(infeasibility, kept):
    """Two frictionless contacts of a light body (Delassus entries 1e4 1/kg), the first pressed
    at -1 m/s, the second open at -0.5 m/s - ``infeasibility``: the first one's impulse
    (1e-4 N s) leaves it approaching at ``infeasibility``. Lemke's check measures that row
    against |q| + |z| sum|A| (about 1.5 m/s), so 1e-10 m/s is within tol_lex = 1e-8 and the
    states stand in round 0; 1e-6 m/s is not, so the open contact is pressed (round 1).
    Measured against |z| alone (1e-4, the units of an impulse), 1e-10 m/s would have changed
    the state of a point Lemke's method accepts, and the fast path would have fallen back to
    Lemke."""
    scale = 1e4
    A = scale * np.array([[1.0, 0.5], [0.5, 1.0]])
    q = np.array([-1.0, -0.5 - infeasibility])
    fwork, iwork = lcp_workspace(2)
    z, w = np.zeros(2), np.zeros(2)
    state = np.array([PRESSED, OPEN], dtype=np.int64)
    ok = solve_states(A, q, z, w, 2, 0, np.zeros(0, dtype=np.int64), state, 0, TOL_PIV, TOL_LEX, 100, fwork, iwork)
    assert ok == kept
    if kept:
        np.testing.assert_allclose(z, [1e-4, 0.0], rtol=1e-12)
        assert w[1] == pytest.approx(-infeasibility, rel=1e-3)
    else:
        assert list(state) == [PRESSED, PRESSED]
        ok = solve_states(A, q, z, w, 2, 0, np.zeros(0, dtype=np.int64), state, 1, TOL_PIV, TOL_LEX, 100, fwork,
                          iwork)
        assert ok and z[1] > 0.0 and np.abs(w).max() <= 1e-12


@pytest.mark.parametrize("seed", range(40))
def test_cold_guesses_never_return_a_wrong_answer(seed):
    """From arbitrary states (wrong ones included) an accepted answer still solves the LCP."""
    rng = np.random.default_rng(seed)
    c = int(rng.integers(1, 7))
    M, q = friction_lcp(rng, c, int(rng.integers(0, 2)), int(rng.integers(1, 4)))
    c = len(q) // 3  # with the duplicated contacts
    if seed % 2:  # an expansion LCP: impulses already in the cone
        q[2 * c:] = rng.uniform(0.0, 1.0, c) * M[2 * c:, :c].diagonal()
    for _ in range(5):
        state = rng.choice([OPEN, PRESSED, SLIDE_POS, SLIDE_NEG, OPEN_STICK, OPEN_NEG], c).astype(np.int64)
        ok, z, w = states_solution(M, q, c, state)
        if ok:
            assert residual(M, q, z, w) <= 1e-8


def test_recall_matches_contacts_by_vertex_and_edge():
    memory = np.array([[7, 3, SLIDE_NEG], [2, 9, OPEN]], dtype=np.int64)
    vertex, edge = np.array([2, 5, 7]), np.array([9, 1, 3])
    active = np.array([2, 0, 1])
    state = np.zeros(3, dtype=np.int64)
    recall_states(active, 3, vertex, edge, memory, 2, np.array([1.0, 1.0, -1.0]), state)
    # contact 2 is (7, 3), contact 0 is (2, 9), contact 1 is new: pressed as it approaches
    assert list(state) == [SLIDE_NEG, OPEN, PRESSED]


def block_mass(rng, blocks):
    """A block-diagonal SPD mass matrix (free bodies, 3 coordinates each)."""
    n = 3 * blocks
    M = np.zeros((n, n))
    for b in range(blocks):
        A = rng.standard_normal((3, 3))
        M[3 * b : 3 * b + 3, 3 * b : 3 * b + 3] = A @ A.T + 3 * np.eye(3)
    return M


def couple_bodies(rng, M):
    """M with bodies 1 and 3 (of a :func:`block_mass`) coupled by a mass block, still SPD: the
    envelope of its Cholesky factor jumps from block 1 to block 3 and back."""
    M[9:12, 3:6] = 0.3 * rng.standard_normal((3, 3))
    M[3:6, 9:12] = M[9:12, 3:6].T
    assert np.all(np.linalg.eigvalsh(M) > 0.0)
    return M


def dense_row_solve(L, b):
    """The full forward and back substitution, in the order of the kernel's loops."""
    n = len(b)
    x = np.zeros(n)
    for r in range(n):
        s = b[r]
        for k in range(r):
            s -= L[r, k] * x[k]
        x[r] = s / L[r, r]
    for r in range(n - 1, -1, -1):
        s = x[r]
        for k in range(r + 1, n):
            s -= L[k, r] * x[k]
        x[r] = s / L[r, r]
    return x


@pytest.mark.parametrize("mass", ["blocks", "coupled", "dense"])
def test_envelope_solves_equal_the_full_loops(mass):
    """Skipping the zeros outside L's envelope and outside a row's nonzeros changes no bit:
    free bodies (block-diagonal M), two bodies coupled across the others (the envelope of L
    jumps from block 1 to block 3 and back), and a full M."""
    rng = np.random.default_rng(3)
    M = block_mass(rng, 5)
    if mass == "coupled":
        M = couple_bodies(rng, M)
    if mass == "dense":
        A = rng.standard_normal((15, 15))
        M = A @ A.T + 15 * np.eye(15)
    L, profile = np.zeros_like(M), np.zeros((2, 15), dtype=np.int64)
    assert cholesky(M, L)
    envelope(L, profile)
    rows = np.zeros((6, 15))
    for i, (a, b) in enumerate([(0, 1), (1, 3), (4, 4), (2, 2), (0, 4), (3, 4)]):
        rows[i, 3 * a : 3 * a + 3] = rng.standard_normal(3)
        rows[i, 3 * b : 3 * b + 3] = rng.standard_normal(3)
    Y = np.zeros_like(rows)
    for i in range(len(rows)):
        cholesky_solve_row(L, profile, rows, i, Y)
        assert np.array_equal(Y[i], dense_row_solve(L, rows[i]))
        assert np.allclose(M @ Y[i], rows[i], atol=1e-12)
    h = rng.standard_normal(15)
    x = np.zeros(15)
    cholesky_solve(L, profile, h, x)
    assert np.array_equal(x, dense_row_solve(L, h))


def test_gauss_solve():
    rng = np.random.default_rng(5)
    A = rng.standard_normal((6, 6))
    b = rng.standard_normal(6)
    x = b.copy()
    assert gauss_solve(A.copy(), x, 6, 1e-12)
    assert np.allclose(A @ x, b)
    A[5] = A[0] + A[1]  # singular
    assert not gauss_solve(A.copy(), b.copy(), 6, 1e-12)
