"""Bounds on how far the points of a body can move over a step.

Over a step of length dt from a state with body velocity V = B q' + bhat and acceleration
A = B q'' + beta, Heun's method moves a body's pose by dt V + dt^2/2 A (exactly so for poses
that are generalized coordinates). A point at distance r from the body's origin then moves by at
most

    reach(dt) = (|v| + |omega| r) dt + (|a| + |alpha| r) dt^2 / 2

(translation plus rotation times radius: a rotation by phi moves it by 2 r sin(phi/2) <= r phi).
Two bodies' points move relative to each other by at most the sum of their reaches.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit
from mbds.kernel.layout import DT_MAX, MAX_PEN

SPEED, SPIN, ACCEL, SPIN_ACCEL = range(4)
"""Columns of the motion array: |v| (m/s), |omega| (rad/s), |a| (m/s^2), |alpha| (rad/s^2)."""


@jit(refcount=False)
def body_motion(carrier, B, bhat, beta, u, acc, other, speeds, motion):
    """Fill motion (nb, 4) with the speeds of every body at velocities u (only when ``speeds``:
    else those already there are kept) and the larger of its accelerations at q'' = acc and
    q'' = other (an acceleration that is not finite counts as zero; pass acc again as ``other``
    for one). Rows of virtual bodies (carrier >= 0) are not written: their bounds are their
    carrier's (see :func:`_pair_rates`)."""
    nb, _, n = B.shape
    known = _finite(acc)
    known_other = _finite(other)
    for b in range(nb):
        if carrier[b] >= 0:
            continue
        if speeds:
            vx, vy, w = bhat[b, 0], bhat[b, 1], bhat[b, 2]
            for k in range(n):
                vx += B[b, 0, k] * u[k]
                vy += B[b, 1, k] * u[k]
                w += B[b, 2, k] * u[k]
            motion[b, SPEED] = np.sqrt(vx * vx + vy * vy)
            motion[b, SPIN] = abs(w)
        linear, angular = _acceleration(B, beta, b, acc, known)
        second, second_angular = _acceleration(B, beta, b, other, known_other)
        motion[b, ACCEL] = max(second, linear)
        motion[b, SPIN_ACCEL] = max(second_angular, angular)


@jit(inline="always")
def _finite(x):
    """Whether every entry of x is finite."""
    for k in range(x.shape[0]):
        if not np.isfinite(x[k]):
            return False
    return True


@jit(inline="always")
def _acceleration(B, beta, b, acc, known):
    """(|a|, |alpha|) of body b at q'' = acc (m/s^2, rad/s^2); beta alone when not known."""
    ax, ay, al = beta[b, 0], beta[b, 1], beta[b, 2]
    if known:
        for k in range(acc.shape[0]):
            ax += B[b, 0, k] * acc[k]
            ay += B[b, 1, k] * acc[k]
            al += B[b, 2, k] * acc[k]
    return np.sqrt(ax * ax + ay * ay), abs(al)


@jit(inline="always")
def _pair_rates(model, motion, k):
    """(speed, acceleration) bounds (m/s, m/s^2) of the relative motion of any point of one body
    of pair k against the other."""
    speed = 0.0
    accel = 0.0
    for side in range(2):
        b = model.pair_bodies[k, side]
        c = model.carrier[b]
        r = model.radius[b]
        if c >= 0:
            r += np.sqrt(model.offset[b, 0] ** 2 + model.offset[b, 1] ** 2)
        else:
            c = b
        speed += motion[c, SPEED] + motion[c, SPIN] * r
        accel += motion[c, ACCEL] + motion[c, SPIN_ACCEL] * r
    return speed, accel


@jit(refcount=False)
def detection_margins(model, motion, settings, margin):
    """Detection margin of each pair (m): maxPen + (1 + f) * (relative reach over a maximum
    step), f the larger ``maximumDisplacementFactor`` of the two bodies. A vertex farther than
    this from the other body cannot reach it within a maximum step."""
    dt = settings[DT_MAX]
    for k in range(model.pair_bodies.shape[0]):
        speed, accel = _pair_rates(model, motion, k)
        factor = max(model.factor[model.pair_bodies[k, 0]], model.factor[model.pair_bodies[k, 1]])
        margin[k] = settings[MAX_PEN] + (1.0 + factor) * (speed * dt + 0.5 * accel * dt * dt)


@jit(refcount=False)
def reach_limit(model, motion, settings, margin, dt):
    """The longest step (s), at most dt, over which no point of any pair moves relative to the
    other body by more than the pair's margin less maxPen: vertices that detection did not
    report (farther than the margin) cannot penetrate within it."""
    for k in range(model.pair_bodies.shape[0]):
        speed, accel = _pair_rates(model, motion, k)
        room = margin[k] - settings[MAX_PEN]
        if speed * dt + 0.5 * accel * dt * dt > room:
            dt = 2.0 * room / (speed + np.sqrt(speed * speed + 2.0 * accel * room))
    return dt
