"""The closed-form contact-force LCP of one contact (mbds.kernel.one_contact) against Lemke's
method: where it answers, the answer is Lemke's (to the last bit for a sliding contact, to
round-off for a stick candidate, whose LCP then has one solution: docs/theory.md), and it leaves
problems without that guarantee (Painlevé's paradox, mu = 0, an open contact) to Lemke."""

from __future__ import annotations

import numpy as np

from mbds.kernel.lcp import SOLVED, lcp_workspace, lemke
from mbds.kernel.one_contact import solve_one_contact

TOL_LEX = 1e-8


def lemke_solution(A, q):
    fwork, iwork = lcp_workspace(len(q))
    z, w = np.zeros(len(q)), np.zeros(len(q))
    status, _ = lemke(A, q, z, w, 1e-14, 1e-10, TOL_LEX, 10000, fwork, iwork)
    return status, z, w


def closed_form(A, q, nh):
    z, w = np.full(len(q), np.nan), np.full(len(q), np.nan)
    ok = solve_one_contact(A, q, z, w, nh, TOL_LEX, np.zeros(3, dtype=np.int64), np.zeros(3))
    return ok, z, w


def stick_candidate(D, mu, q_n, q_t):
    """A and q of one stick candidate (contact_problem.build_matrix with na = nh = 1)."""
    A = np.array([[D[0, 0] - mu * D[0, 1], D[0, 1], 0.0],
                  [D[1, 0] - mu * D[1, 1], D[1, 1], 1.0],
                  [2.0 * mu, -1.0, 0.0]])
    return A, np.array([q_n, q_t, 0.0])


def delassus(rng):
    """w_N, w_T of one contact on a random body: D = W M^-1 W^T (symmetric positive definite)."""
    W = rng.normal(size=(2, 3))
    M = np.diag(rng.uniform(0.5, 2.0, 3))
    return W @ np.linalg.solve(M, W.T)


def test_a_sliding_contact_gets_lemkes_answer_to_the_last_bit():
    rng = np.random.default_rng(1)
    for _ in range(200):
        A = np.array([[rng.uniform(1e-3, 10.0)]])
        q = np.array([-rng.uniform(1e-6, 10.0)])
        ok, z, w = closed_form(A, q, 0)
        status, z_l, w_l = lemke_solution(A, q)
        assert ok and status == SOLVED
        np.testing.assert_array_equal(z, z_l)
        np.testing.assert_array_equal(w, w_l)


def test_a_stick_candidate_gets_the_solution_lemke_finds():
    """Random contacts with the three slopes of docs/theory.md positive: stick, slide forwards
    and slide backwards all occur, and every answer equals Lemke's within round-off."""
    rng = np.random.default_rng(2)
    kinds = set()
    answered = 0
    for _ in range(400):
        D = delassus(rng)
        mu = rng.uniform(0.05, 1.0)
        if D[0, 0] - mu * abs(D[0, 1]) <= 0.1 * D[0, 0]:
            continue  # near Painlevé's paradox: not this test's case
        A, q = stick_candidate(D, mu, -rng.uniform(0.1, 10.0), rng.normal(0.0, 5.0))
        ok, z, w = closed_form(A, q, 1)
        status, z_l, w_l = lemke_solution(A, q)
        assert status == SOLVED
        if not ok:
            continue
        answered += 1
        np.testing.assert_allclose(z, z_l, rtol=1e-9, atol=1e-12 * np.abs(z_l).max())
        np.testing.assert_allclose(w, w_l, rtol=1e-9, atol=1e-12 * np.abs(q).max())
        kinds.add("stick" if z[1] > 0.0 and z[2] == 0.0 and w[2] > 0.0 else
                  "forwards" if z[1] == 0.0 else "backwards")
    assert answered >= 250
    assert kinds == {"stick", "forwards", "backwards"}


def test_problems_without_a_unique_solution_go_to_lemke():
    D = np.array([[1.0, 0.9], [0.9, 1.0]])
    # Painlevé: D_nn - mu D_nt < 0 (slope of g_N'' negative while sliding forwards)
    A, q = stick_candidate(D, 1.5, -1.0, 2.0)
    assert not closed_form(A, q, 1)[0]
    # frictionless stick candidate: the cone is a point, the tangential rows are degenerate
    A, q = stick_candidate(D, 0.0, -1.0, 0.5)
    assert not closed_form(A, q, 1)[0]
    # singular D (normal and tangential directions dependent)
    A, q = stick_candidate(np.array([[1.0, 1.0], [1.0, 1.0]]), 0.3, -1.0, 0.5)
    assert not closed_form(A, q, 1)[0]
    # an open contact (b_N >= 0) and a sliding contact that would have to pull
    A, q = stick_candidate(np.eye(2), 0.3, 0.5, -1.0)
    assert not closed_form(A, q, 1)[0]
    assert not closed_form(np.array([[-1.0]]), np.array([-1.0]), 0)[0]
