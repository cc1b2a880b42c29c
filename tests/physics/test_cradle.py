"""Newton's cradle: a row of equal polygon balls on a line (no gravity, no friction, e = 1), the
first moving into the others.

mbds resolves all closed contacts of an impact at once: Poisson's law as a compression LCP
(impulses Lambda_C >= 0 until no contact approaches) and an expansion LCP (Lambda_E = e Lambda_C
plus what keeps the contacts from closing again) (Glocker & Pfeiffer 1992, "Dynamical systems with
unilateral contacts", Nonlinear Dynamics 3; Pfeiffer & Glocker 1996, ch. 7). For N touching equal
balls hit by the first at v, compression ends with all balls at v/N and e = 1 doubles every
impulse: the first ball recoils at (2/N - 1) v and the N - 1 others leave together at 2v/N. That
keeps momentum and energy ((2/N - 1)² + 4(N - 1)/N² = 1) but is not the "one ball out" of a real
cradle, which needs the impacts to travel through the row one after the other (wave effects the
rigid LCP does not have). Balls set a little apart do collide one pair at a time, each pair
exchanging velocities, and the last ball leaves alone at v.

The prediction is computed here independently: both LCPs solved by enumerating active sets.
"""

import itertools

import numpy as np
import pytest

from tests.physics.models import FreeBody, run_folder, write_free_bodies

pytestmark = pytest.mark.physics

BALLS = 4
SIDES = 31  # odd: a vertex at +x faces the next ball's flat edge at -x
RADIUS, MASS = 0.05, 0.2  # m, kg
SPEED = 1.0  # m/s of the first ball
SPACING = RADIUS * (1.0 + np.cos(np.pi / SIDES))  # m, centres of touching balls


def lcp_by_enumeration(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z >= 0 with w = A z + b >= 0 and z.w = 0, by trying every active set (small A only)."""
    m = len(b)
    for size in range(m + 1):
        for active in itertools.combinations(range(m), size):
            z = np.zeros(m)
            if active:
                idx = list(active)
                z[idx] = np.linalg.solve(A[np.ix_(idx, idx)], -b[idx])
            w = A @ z + b
            if (z >= -1e-14).all() and (w >= -1e-14).all():
                return z
    raise AssertionError("no solution")


def poisson_impact(v: np.ndarray, contacts: list[int], e: float) -> np.ndarray:
    """Velocities (m/s) along the line after a Poisson impact of equal balls over the closed
    contacts (contact k between balls k and k + 1)."""
    W = np.zeros((len(contacts), len(v)))
    for row, k in enumerate(contacts):
        W[row, k], W[row, k + 1] = -1.0, 1.0  # gN' = v_{k+1} - v_k
    G = W @ W.T / MASS
    compression = lcp_by_enumeration(G, W @ v)
    after_compression = v + W.T @ compression / MASS
    expansion = e * compression + lcp_by_enumeration(G, W @ after_compression + G @ (e * compression))
    return after_compression + W.T @ expansion / MASS


def cradle(folder, gap: float):
    """The row with ``gap`` (m) between neighbouring balls, the first moving at SPEED."""
    angles = 2.0 * np.pi * np.arange(SIDES) / SIDES  # a vertex at +x, an edge at -x
    shape = RADIUS * np.column_stack([np.cos(angles), np.sin(angles)])
    inertia = MASS * RADIUS**2 / 6.0 * (1.0 + 2.0 * np.cos(np.pi / SIDES) ** 2)  # regular polygon, centroidal
    bodies = [FreeBody(f"ball{k}", shape, MASS, inertia, position=(k * (SPACING + gap), 0.0, 0.0),
                       velocity=(SPEED if k == 0 else 0.0, 0.0, 0.0)) for k in range(BALLS)]
    pairs = [(f"ball{k}", f"ball{k + 1}") for k in range(BALLS - 1)]
    return write_free_bodies(folder, bodies, pairs, floor=False, gravity=0.0, friction=0.0, restitution=1.0,
                             dt_max=1e-4, max_penetration=1e-8, break_time=0.02)


def line_velocities(result) -> np.ndarray:
    return result.u[-1, 0::3]


def test_touching_balls_follow_the_simultaneous_impact_lcp(tmp_path):
    result = run_folder(cradle(tmp_path, 0.0))
    start = np.r_[SPEED, np.zeros(BALLS - 1)]
    predicted = poisson_impact(start, list(range(BALLS - 1)), 1.0)
    np.testing.assert_allclose(predicted, np.r_[2.0 / BALLS - 1.0, np.full(BALLS - 1, 2.0 / BALLS)] * SPEED,
                               atol=1e-14)
    np.testing.assert_allclose(line_velocities(result), predicted, rtol=0.0, atol=1e-9)
    assert np.abs(result.u[-1, 1::3]).max() < 1e-12  # nothing off the line, no spin
    assert result.energy[-1] == pytest.approx(result.energy[0], rel=1e-9)
    assert abs(result.lost[-1]) < 1e-9 * result.energy[0]


def test_balls_set_apart_pass_the_momentum_to_the_last_ball(tmp_path):
    result = run_folder(cradle(tmp_path, 1e-3))
    predicted = np.r_[SPEED, np.zeros(BALLS - 1)]
    for k in range(BALLS - 1):  # one pair at a time, through the same impact law
        predicted = poisson_impact(predicted, [k], 1.0)
    np.testing.assert_allclose(predicted, np.r_[np.zeros(BALLS - 1), SPEED], atol=1e-14)
    np.testing.assert_allclose(line_velocities(result), predicted, rtol=0.0, atol=1e-9)
    assert result.energy[-1] == pytest.approx(result.energy[0], rel=1e-9)
