"""The small-angle woodpecker model of Leine, Glocker and van Campen, side by side with mbds.

Run from the repository root: ``.venv/bin/python benchmarks/woodpecker_reference.py [seconds]``.

The reference model (docs/THEORY.md §8) has q = (y, phi_M, phi_S), a constant mass matrix, an
h-vector linear in q and three contacts with linear gaps and constant force directions:
beak on pole (g_N1 = l_M + l_G - l_S - r_0 - h_S phi_S) and the upper and lower sleeve edges
(g_N2,3 = r_M - r_0 -/+ h_M phi_M). It is integrated here independently of the mbds kernel:

- contacts with g_N <= GAP_TOL are closed; a closed contact approaching faster than SPEED_TOL
  starts an impact, solved with Poisson's law and Coulomb friction over all closed contacts
  (a compression and an expansion LCP, THEORY.md §4);
- between impacts the contact forces come from the acceleration LCP (THEORY.md §3) of the
  closed contacts that are not separating; a contact slower than SPEED_TOL tangentially is a
  stick candidate, the others slide;
- each step (at most STEP) ends early at the next event it can predict: an open gap closing
  (quadratic in time) or a sliding velocity reaching zero (linear); the state is advanced by
  Heun's rule with the LCP solved again at the end of the step in the same contact mode.

All LCPs are solved with ``mbds.lcp.solve``. mbds runs ``campaigns/woodpecker`` (exact polygon
contact geometry, same M and h). Both trajectories are measured by
``tests.physics.limit_cycle.cycle_figures`` after SKIP seconds.
"""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from mbds.lcp import solve  # noqa: E402
from tests.physics.limit_cycle import cycle_figures, velocity_jumps  # noqa: E402

# data set (THEORY.md §8): kg, kg m², m, N m/rad, m/s²
M_M, J_M, M_S, J_S, G = 3e-4, 5e-9, 4.5e-3, 7e-7, 9.81
R_0, R_M, H_M, L_M, L_G, H_S, L_S = 2.5e-3, 3.1e-3, 5.8e-3, 0.010, 0.015, 0.020, 0.0201
C_PHI, MU, EPS = 0.0056, np.array([0.3, 0.3, 0.3]), np.array([0.5, 0.0, 0.0])
Q0, U0 = np.array([0.0, -0.1036, -0.2788]), np.array([-0.3411, 0.0, -7.4583])

MASS = np.array([
    [M_S + M_M, M_S * L_M, M_S * L_G],
    [M_S * L_M, J_M + M_S * L_M**2, M_S * L_M * L_G],
    [M_S * L_G, M_S * L_M * L_G, J_S + M_S * L_G**2],
])
MINV = np.linalg.inv(MASS)
WN = np.array([[0.0, 0.0, -H_S], [0.0, -H_M, 0.0], [0.0, H_M, 0.0]]).T  # columns: contacts 1, 2 (upper), 3 (lower)
WT = np.array([[1.0, L_M, L_G - L_S], [1.0, R_M, 0.0], [1.0, R_M, 0.0]]).T
GAP0 = np.array([L_M + L_G - L_S - R_0, R_M - R_0, R_M - R_0])

STEP = 1e-5  # s
GAP_TOL = 1e-9  # m
SPEED_TOL = 1e-6  # m/s
SKIP = 1.0  # s of transient left out


def h_vector(q: np.ndarray) -> np.ndarray:
    spring = C_PHI * (q[1] - q[2])
    return np.array([-(M_S + M_M) * G, -spring - M_S * G * L_M, spring - M_S * G * L_G])


def _lcp(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    result = solve(A, b)
    if result.status != 0:
        raise RuntimeError(f"LCP not solved: {result.status!r}")
    return result.z


def _impact_matrix(c: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A of the impact LCPs over contacts c (all stick candidates), and M^-1 W_N, M^-1 W_T."""
    k = len(c)
    yn, yt, mu = MINV @ WN[:, c], MINV @ WT[:, c], np.diag(MU[c])
    dnn, dnt, dtn, dtt = WN[:, c].T @ yn, WN[:, c].T @ yt, WT[:, c].T @ yn, WT[:, c].T @ yt
    A = np.block([
        [dnn - dnt @ mu, dnt, np.zeros((k, k))],
        [dtn - dtt @ mu, dtt, np.eye(k)],
        [2.0 * mu, -np.eye(k), np.zeros((k, k))],
    ])
    return A, yn, yt


def impact(u: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Velocities after a Poisson impact with Coulomb friction over the closed contacts c."""
    k = len(c)
    A, yn, yt = _impact_matrix(c)
    mu = MU[c]
    z = _lcp(A, np.concatenate([WN[:, c].T @ u, WT[:, c].T @ u, np.zeros(k)]))
    nc, tc = z[:k], z[k:2 * k] - mu * z[:k]
    uc = u + yn @ nc + yt @ tc
    base = EPS[c] * nc  # Poisson: the expansion starts from eps Lambda_NC ...
    b = np.concatenate([WN[:, c].T @ uc, WT[:, c].T @ uc, 2.0 * mu * base])
    b[: 2 * k] += A[: 2 * k, :k] @ base  # ... with its -mu partner in the tangential direction
    z = _lcp(A, b)
    ne = base + z[:k]
    te = z[k:2 * k] - mu * ne
    return uc + yn @ ne + yt @ te


def accelerations(q: np.ndarray, u: np.ndarray, c: np.ndarray, stick: np.ndarray, sign: np.ndarray) -> np.ndarray:
    """q'' with the acceleration LCP over the active contacts c (stick candidates where
    ``stick``; the others slide with ``sign`` = sgn(gT'))."""
    minv_h = MINV @ h_vector(q)
    if len(c) == 0:
        return minv_h
    mu = MU[c]
    ng = WN[:, c] - WT[:, c] * np.where(stick, 0.0, mu * sign)
    wh = WT[:, c[stick]]
    muh = np.zeros((len(wh.T), len(c)))
    muh[np.arange(len(wh.T)), np.flatnonzero(stick)] = mu[stick]
    left = MINV @ (ng - wh @ muh)
    k, s = len(c), len(wh.T)
    A = np.block([
        [WN[:, c].T @ left, WN[:, c].T @ MINV @ wh, np.zeros((k, s))],
        [wh.T @ left, wh.T @ MINV @ wh, np.eye(s)],
        [2.0 * muh, -np.eye(s), np.zeros((s, s))],
    ])
    z = _lcp(A, np.concatenate([WN[:, c].T @ minv_h, wh.T @ minv_h, np.zeros(s)]))
    lam_n, lam_h = z[:k], z[k:k + s] - muh @ z[:k]
    return minv_h + MINV @ (ng @ lam_n + wh @ lam_h)


def simulate_reference(duration: float, sample: float = 1e-5):
    """Integrate the reference model; return sample times, q, u (samples every ``sample`` s)
    and the times of impacts (s)."""
    q, u, t = Q0.copy(), U0.copy(), 0.0
    times, qs, us, impacts = [0.0], [q.copy()], [u.copy()], []
    next_sample = sample
    while t < duration:
        gap = GAP0 + WN.T @ q
        closed = np.flatnonzero(gap <= GAP_TOL)
        if np.any(WN[:, closed].T @ u < -SPEED_TOL):
            u = impact(u, closed)
            impacts.append(t)
        gd_n, gd_t = WN.T @ u, WT.T @ u
        active = closed[gd_n[closed] <= SPEED_TOL]
        stick = np.abs(gd_t[active]) <= SPEED_TOL
        sign = np.sign(gd_t[active])
        a1 = accelerations(q, u, active, stick, sign)
        dt = min(STEP, next_sample - t, duration - t)
        for i in np.flatnonzero(gap > GAP_TOL):  # an open gap closing within the step
            g2, g1, g0 = 0.5 * WN[:, i] @ a1, gd_n[i], gap[i]
            roots = np.roots([g2, g1, g0]) if abs(g2) > 0 else np.array([-g0 / g1 if g1 else -1.0])
            roots = roots[np.isreal(roots)].real
            roots = roots[roots > 0]
            if len(roots):
                dt = min(dt, roots.min())
        for j, i in enumerate(active):  # a sliding velocity reaching zero within the step
            if not stick[j]:
                rate = WT[:, i] @ a1
                if rate * gd_t[i] < 0:
                    dt = min(dt, -gd_t[i] / rate)
        dt = max(dt, 1e-12)
        q1, u1 = q + dt * u, u + dt * a1
        a2 = accelerations(q1, u1, active, stick, sign)
        q, u, t = q + 0.5 * dt * (u + u1), u + 0.5 * dt * (a1 + a2), t + dt
        if t >= next_sample - 1e-13:
            times.append(t)
            qs.append(q.copy())
            us.append(u.copy())
            next_sample += sample
    return np.array(times), np.array(qs), np.array(us), np.array(impacts)


def run_mbds(duration: float):
    """mbds' run of campaigns/woodpecker: history times, q, u, q'' and the wall time (s)."""
    from mbds.model.load import load_model
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(ROOT / "campaigns" / "woodpecker")
    result = simulate(model, RunSettings(break_time=duration))
    return result.time, result.q, result.u, result.a


def main() -> None:
    duration = float(sys.argv[1]) if len(sys.argv) > 1 else 2.0
    start = time.perf_counter()
    t, q, u, impacts = simulate_reference(duration)
    print(f"reference: {len(impacts)} impacts in {duration} s ({time.perf_counter() - start:.1f} s wall)")
    reference = cycle_figures(t, q, impacts, SKIP)
    start = time.perf_counter()
    t2, q2, u2, a2 = run_mbds(duration)
    print(f"mbds: {time.perf_counter() - start:.1f} s wall (compile included)")
    jumps = velocity_jumps(t2, u2, a2, (1.0, L_M, L_G), 1e-3)
    ours = cycle_figures(t2, q2, jumps, SKIP)
    print(f"\nafter {SKIP} s of {duration} s:")
    print(f"{'':>4}{'reference (small-angle, linear gaps)':<60}mbds (campaigns/woodpecker)")
    for left, right in zip(reference.lines(), ours.lines()):
        print(f"{'':>4}{left:<60}{right}")


if __name__ == "__main__":
    main()
