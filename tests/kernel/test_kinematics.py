"""Contact kinematics against finite differences of the gap along a trajectory."""

import numpy as np
import pytest

from mbds.kernel.kinematics import (
    DEPENDENT,
    FIXED,
    GENERALIZED,
    body_frames,
    body_states,
    contact_kinematics,
)

# body 0: x, y, Rz = q0, q1, q2; body 1: x fixed, y dependent (rheonomic), Rz = q3;
# body 2: virtual, carried by body 1 at an offset
BINDING = np.array([[GENERALIZED] * 3, [FIXED, DEPENDENT, GENERALIZED], [FIXED] * 3], dtype=np.int64)
INDEX = np.array([[0, 1, 2], [-1, 0, 3], [-1, -1, -1]], dtype=np.int64)
START = np.array([[0.0, 0.0, 0.0], [0.3, 0.0, 0.0], [0.0, 0.0, 0.0]])
CARRIER = np.array([-1, -1, 1], dtype=np.int64)
OFFSET = np.array([[0, 0, 0], [0, 0, 0], [0.05, -0.02, 0.4]], dtype=float)
AMPLITUDE, OMEGA, COUPLING = 0.01, 30.0, 0.2
VERTEX = np.array([0.04, -0.03])  # body-frame point of body 0
EDGE = np.array([[-0.1, 0.01], [0.1, 0.03]])  # body-frame edge of body 2 (virtual)


def dependent(q, qd, t):
    pos = np.array([AMPLITUDE * np.sin(OMEGA * t) + COUPLING * q[0]])
    vel = np.array([AMPLITUDE * OMEGA * np.cos(OMEGA * t) + COUPLING * qd[0]])
    jac = np.array([[COUPLING, 0.0, 0.0, 0.0]])
    scalar = np.array([-AMPLITUDE * OMEGA**2 * np.sin(OMEGA * t)])
    return pos, vel, jac, scalar


def states(q, qd, t):
    nb, n = 3, 4
    pose, vel, B = np.empty((nb, 3)), np.empty((nb, 3)), np.empty((nb, 3, n))
    bhat, beta, trig = np.empty((nb, 3)), np.empty((nb, 3)), np.empty((nb, 2))
    body_frames(BINDING, INDEX, START, CARRIER, pose, vel, B, bhat, beta, trig)
    body_states(BINDING, INDEX, CARRIER, OFFSET, q, qd, *dependent(q, qd, t), pose, vel, B, bhat, beta, trig)
    np.testing.assert_array_equal(trig, np.column_stack([np.cos(pose[:, 2]), np.sin(pose[:, 2])]))
    return pose, vel, B, bhat, beta


def to_world(pose, point):
    c, s = np.cos(pose[2]), np.sin(pose[2])
    return pose[:2] + np.array([c * point[0] - s * point[1], s * point[0] + c * point[1]])


def gap(q, t):
    pose = states(q, np.zeros(4), t)[0]
    p = to_world(pose[0], VERTEX)
    q0, q1 = to_world(pose[2], EDGE[0]), to_world(pose[2], EDGE[1])
    tangent = (q1 - q0) / np.linalg.norm(q1 - q0)
    normal = np.array([tangent[1], -tangent[0]])
    return normal @ (p - q0), normal, p


def contact_state(q, qd, t):
    """WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t of the test contact at (q, qd, t)."""
    pose, vel, B, bhat, beta = states(q, qd, t)
    _, normal, point = gap(q, t)
    out = [np.empty((1, 4)), np.empty((1, 4))] + [np.empty(1) for _ in range(6)]
    contact_kinematics(
        np.array([0]), 1, np.array([0]), np.array([2]), normal[None, :], point[None, :], CARRIER, pose, vel, B, bhat, beta, *out
    )
    return out


def test_gap_rates_match_finite_differences():
    q = np.array([0.02, 0.05, 0.3, -0.2])
    qd = np.array([0.5, -1.0, 4.0, -3.0])
    qdd = np.array([2.0, -9.81, 30.0, 50.0])
    t = 0.013

    def g_along(tau):
        return gap(q + qd * tau + 0.5 * qdd * tau**2, t + tau)[0]

    def first(h):
        return (g_along(h) - g_along(-h)) / (2 * h)

    def second(h):
        return (g_along(h) - 2 * g_along(0.0) + g_along(-h)) / h**2

    rate = (4 * first(5e-4) - first(1e-3)) / 3
    accel = (4 * second(5e-4) - second(1e-3)) / 3
    WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t = contact_state(q, qd, t)
    assert gd_n[0] == pytest.approx(rate, rel=1e-8)
    assert WN[0] @ qd + what_n[0] == pytest.approx(gd_n[0], rel=1e-12)
    assert WN[0] @ qdd + wbar_n[0] == pytest.approx(accel, rel=1e-7)
    assert what_n[0] != 0.0  # the rheonomic ground contributes


def test_tangential_rates_match_finite_differences():
    """gT' = t . v_rel (the vertex's velocity relative to the edge's material point under it,
    along the moving edge tangent); its rate is WT.q'' + wbar_T."""
    q = np.array([0.02, 0.05, 0.3, -0.2])
    qd = np.array([0.5, -1.0, 4.0, -3.0])
    qdd = np.array([2.0, -9.81, 30.0, 50.0])
    t = 0.013
    WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t = contact_state(q, qd, t)
    def relative_tangent_velocity(tau):
        qq, qqd = q + qd * tau + 0.5 * qdd * tau**2, qd + qdd * tau
        pz, vz = states(qq, qqd, t + tau)[:2]
        pa = to_world(pz[0], VERTEX)
        va = vz[0, :2] + vz[0, 2] * np.array([-(pa - pz[0, :2])[1], (pa - pz[0, :2])[0]])
        vb = vz[2, :2] + vz[2, 2] * np.array([-(pa - pz[2, :2])[1], (pa - pz[2, :2])[0]])
        q0, q1 = to_world(pz[2], EDGE[0]), to_world(pz[2], EDGE[1])
        tangent = (q1 - q0) / np.linalg.norm(q1 - q0)
        return tangent @ (va - vb)

    assert relative_tangent_velocity(0.0) == pytest.approx(gd_t[0], rel=1e-12)
    assert WT[0] @ qd + what_t[0] == pytest.approx(gd_t[0], rel=1e-12)
    def first(h):
        return (relative_tangent_velocity(h) - relative_tangent_velocity(-h)) / (2 * h)

    rate = (4 * first(5e-4) - first(1e-3)) / 3
    assert WT[0] @ qdd + wbar_t[0] == pytest.approx(rate, rel=1e-8)
