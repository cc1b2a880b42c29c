"""Lemke's method (mbds.kernel.lcp via mbds.lcp.solve) on peer problems and generated ones."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mbds.io.lcpfile import read_lcp
from mbds.kernel.jit import jit
from mbds.kernel.lcp import lcp_workspace, lemke
from mbds.lcp import LEXICO_ZERO_TOLERANCE, Status, solve

DATA = Path(__file__).resolve().parents[2].parent / "shared" / "testdata" / "lcp"
needs_data = pytest.mark.skipif(not DATA.is_dir(), reason=f"peer LCP collection not found at {DATA}")
PEER_FILES = sorted(DATA.glob("siconos*/*.dat")) if DATA.is_dir() else []
RAY_FILES = {"lcp_CPS_3.dat", "lcp_Pang_isolated_sol_perturbed.dat"}
# pivot counts of exact lexicographic Lemke (first pivot, z0 entering, included)
EXACT_PIVOTS = {"lcp_tobenna.dat": 127, "lcp_exp_murty2.dat": 64}
# allowed range of the lexicographic zero tolerance (docs/lcp.md)
LEXICO_RANGE = (1e-10, 1e-6)


def residual(M, q, z, w):
    """Relative residual of an LCP solution: negativity of z and w and complementarity."""
    znorm = max(np.abs(z).max(), 1.0)
    wscale = np.abs(q).max() + np.abs(M).max(axis=1).sum() * znorm
    assert np.allclose(w, M @ z + q, rtol=0, atol=1e-12 * wscale)
    return max(-z.min() / znorm, -w.min() / wscale, np.abs(z * w).max() / (znorm * wscale), 0.0)


def assert_solved(M, q, result, tol=1e-10):
    assert result.status == Status.SOLVED
    assert residual(M, q, result.z, result.w) <= tol


def murty(n):
    """Murty's exponential example: Lemke needs 2^n pivots."""
    M = np.triu(np.full((n, n), 2.0), 1) + np.eye(n)
    q = -np.array([sum(2.0**j for j in range(i, n + 1)) for i in range(1, n + 1)])
    return M, q


def friction_lcp(rng, contacts, duplicates, bodies):
    """2D frictional contact LCP (unknowns: normal force, tangential reserve, slip per contact).

    D = W^T Mass^-1 W for random W and SPD mass matrix; duplicated contacts make D singular;
    the third block of q is zero and some normal rows of q are zero: highly degenerate.
    """
    ndof = 3 * bodies
    A = rng.standard_normal((ndof, ndof))
    mass = A @ A.T + ndof * np.eye(ndof)
    WN, WT = rng.standard_normal((2, ndof, contacts))
    copies = rng.integers(0, contacts, duplicates)
    WN, WT = np.hstack([WN, WN[:, copies]]), np.hstack([WT, WT[:, copies]])
    c = WN.shape[1]
    W = np.hstack([WN, WT])
    D = W.T @ np.linalg.solve(mass, W)
    NN, NT, TN, TT = D[:c, :c], D[:c, c:], D[c:, :c], D[c:, c:]
    mu = np.diag(rng.uniform(0.0, 1.0, c))
    I, O = np.eye(c), np.zeros((c, c))
    M = np.block([[NN - NT @ mu, NT, O], [TN - TT @ mu, TT, I], [2 * mu, -I, O]])
    v = rng.standard_normal(ndof)
    qN = WN.T @ v
    qN[rng.random(c) < 0.3] = 0.0
    return M, np.concatenate([qN, WT.T @ v, np.zeros(c)])


# ---------------------------------------------------------------- peer collection


@needs_data
@pytest.mark.parametrize("path", PEER_FILES, ids=lambda p: p.name)
def test_peer_problem(path):
    M, q = read_lcp(path)
    result = solve(M, q)
    if path.name in RAY_FILES:
        assert result.status == Status.RAY
    else:
        assert_solved(M, q, result)
    if path.name in EXACT_PIVOTS:
        assert result.pivots == EXACT_PIVOTS[path.name]


@needs_data
def test_randomised_lexico_tolerance_keeps_status():
    rng = np.random.default_rng(20240611)
    for path in PEER_FILES:
        M, q = read_lcp(path)
        reference = solve(M, q).status
        for tol in np.exp(rng.uniform(*np.log(LEXICO_RANGE), size=4)):
            result = solve(M, q, lexico_zero_tolerance=tol)
            assert result.status == reference, (path.name, tol)


@needs_data
def test_pivot_tolerance_raised_after_failure():
    """A path through a tiny pivot ends inaccurate; the raised tolerance avoids it."""
    M, q = read_lcp(DATA / "siconos_fc2d" / "lcp_from_FC2D_SliderCrankLagrangian00001.dat")
    small = solve(M, q, pivot_tolerance_min=1e-14, pivot_tolerance_max=1e-14)
    assert small.status == Status.PIVOT_FAILURE
    direct = solve(M, q, pivot_tolerance_min=1e-11, pivot_tolerance_max=1e-11)
    assert_solved(M, q, direct)
    retried = solve(M, q)
    assert_solved(M, q, retried)
    np.testing.assert_array_equal(retried.z, direct.z)
    assert retried.pivots > small.pivots + direct.pivots  # 1e-14 and 1e-13 failed, then 1e-11


@needs_data
def test_no_retry_when_it_cannot_change_the_path():
    M, q = read_lcp(DATA / "siconos" / "lcp_CPS_3.dat")
    once = solve(M, q, pivot_tolerance_max=1e-14)
    assert once.status == solve(M, q).status == Status.RAY
    assert solve(M, q).pivots == once.pivots


# ---------------------------------------------------------------- generated problems


def test_trivial_case_needs_no_pivot():
    M = np.array([[0.0, -1.0], [3.0, 2.0]])
    q = np.array([1.0, 0.0])
    result = solve(M, q)
    assert result.status == Status.SOLVED and result.pivots == 0
    np.testing.assert_array_equal(result.z, 0.0)
    np.testing.assert_array_equal(result.w, q)


@pytest.mark.parametrize("n", range(1, 13))
def test_murty_exponential_example(n):
    M, q = murty(n)
    result = solve(M, q, max_pivots=2**n + 1)
    assert_solved(M, q, result)
    assert result.pivots == 2**n
    expected = np.zeros(n)
    expected[-1] = 2.0**n  # the unique solution (M is a P-matrix)
    np.testing.assert_array_equal(result.z, expected)


@pytest.mark.parametrize("n", range(1, 14))
def test_murty_solved_with_default_pivot_limit(n):
    """Murty (1978): Lemke needs 2^n pivots; the default limit (10,000) covers n <= 13."""
    M, q = murty(n)
    result = solve(M, q)
    assert_solved(M, q, result)
    assert result.pivots == 2**n


def test_murty_fourteen_exceeds_default_pivot_limit():
    M, q = murty(14)
    assert solve(M, q).status == Status.MAX_PIVOTS


def test_murty_hits_pivot_limit():
    M, q = murty(6)
    assert solve(M, q, max_pivots=63).status == Status.MAX_PIVOTS


def brute_force(M, q):
    """All solutions of a small LCP by enumeration of complementary bases."""
    n = len(q)
    found = []
    for k in range(n + 1):
        for a in map(list, itertools.combinations(range(n), k)):
            z = np.zeros(n)
            z[a] = np.linalg.solve(M[np.ix_(a, a)], -q[a]) if a else []
            w = M @ z + q
            if z.min() >= -1e-9 and w.min() >= -1e-9:
                found.append(z)
    return found


@st.composite
def p_matrix_problems(draw):
    """M = S + K with S symmetric positive definite and K skew: a (nonsymmetric) P-matrix."""
    seed = draw(st.integers(0, 2**32 - 1))
    n = draw(st.integers(1, 7))
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    K = rng.standard_normal((n, n)) * draw(st.sampled_from([0.0, 1.0, 10.0]))
    M = A @ A.T + 0.1 * np.eye(n) + K - K.T
    return M, rng.standard_normal(n) * 10.0 ** draw(st.integers(-3, 3))


@settings(max_examples=60, deadline=None)
@given(p_matrix_problems())
def test_p_matrix_unique_solution(problem):
    M, q = problem
    result = solve(M, q)
    assert_solved(M, q, result)
    (unique,) = brute_force(M, q)
    np.testing.assert_allclose(result.z, unique, rtol=1e-8, atol=1e-8 * max(1.0, np.abs(unique).max()))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 20), st.floats(0.0, 0.9))
def test_psd_feasible_problem_solved(seed, n, rank_deficit):
    """M positive semidefinite (copositive-plus) and q feasible: Lemke must solve it."""
    rng = np.random.default_rng(seed)
    rank = max(1, round(n * (1 - rank_deficit)))
    A = rng.standard_normal((n, rank))
    K = rng.standard_normal((n, n))
    M = A @ A.T + K - K.T
    z, w = np.zeros(n), np.zeros(n)
    active = rng.random(n) < 0.5
    z[active] = rng.uniform(0.0, 2.0, active.sum())
    w[~active] = rng.uniform(0.0, 2.0, (~active).sum())
    q = w - M @ z  # (z, w) solves LCP(M, q)
    assert_solved(M, q, solve(M, q))


@settings(max_examples=80, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 6), st.integers(0, 4), st.integers(1, 3))
def test_degenerate_friction_problems_terminate(seed, contacts, duplicates, bodies):
    M, q = friction_lcp(np.random.default_rng(seed), contacts, duplicates, bodies)
    limit = 50 * len(q)
    result = solve(M, q, max_pivots=limit)
    assert result.status in (Status.SOLVED, Status.RAY)
    assert result.pivots < limit
    if result.status == Status.SOLVED:
        assert residual(M, q, result.z, result.w) <= 1e-10


def test_friction_problems_mostly_solved():
    """Without duplicated contacts a ray is rare: the test of termination is not vacuous."""
    rng = np.random.default_rng(7)
    statuses = [solve(*friction_lcp(rng, 4, 0, 3)).status for _ in range(100)]
    assert statuses.count(Status.SOLVED) >= 90


# ---------------------------------------------------------------- kernel contract


@jit
def _solve_many(M, Q, Z, W, fwork, iwork):
    """Solve LCP(M, Q[i]) for each row of Q with one workspace."""
    status = np.empty(Q.shape[0], dtype=np.int64)
    for i in range(Q.shape[0]):
        status[i], _ = lemke(M, Q[i], Z[i], W[i], 1e-14, 1e-10, LEXICO_ZERO_TOLERANCE, 1000, fwork, iwork)
    return status


def test_numba_callers_share_a_workspace_and_results_are_bit_identical():
    rng = np.random.default_rng(3)
    n = 12
    A = rng.standard_normal((n, n))
    M = A @ A.T + np.eye(n)
    Q = rng.standard_normal((5, n))
    Z, W = np.empty((5, n)), np.empty((5, n))
    status = _solve_many(M, Q, Z, W, *lcp_workspace(n + 5))  # a larger workspace serves too
    assert (status == Status.SOLVED).all()
    for i in range(5):
        result = solve(M, Q[i])
        np.testing.assert_array_equal(result.z, Z[i])
        np.testing.assert_array_equal(result.w, W[i])


@pytest.mark.parametrize(
    "M, q, kwargs",
    [
        (np.eye(2), np.ones(3), {}),
        (np.eye(2), np.array([np.nan, 1.0]), {}),
        (np.eye(2), np.ones(2), {"pivot_tolerance_min": 1e-8, "pivot_tolerance_max": 1e-10}),
        (np.eye(2), np.ones(2), {"lexico_zero_tolerance": 0.0}),
        (np.eye(2), np.ones(2), {"max_pivots": 0}),
    ],
)
def test_bad_input_rejected(M, q, kwargs):
    with pytest.raises(ValueError):
        solve(M, q, **kwargs)
