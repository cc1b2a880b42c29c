"""Body and contact kinematics in terms of the generalized coordinates.

Each body's pose (x, y, Rz) in (m, m, rad) moves as V_b = B_b q' + bhat_b and
A_b = B_b q'' + beta_b, where B_b is 3 x n: a generalized coordinate contributes a unit row, a
dependent coordinate its Jacobian vector J (with bhat = c' - J.q' and beta = j), a fixed one a
zero row. A virtual body moves rigidly with its carrier at a constant offset.

For a contact of vertex P (on body A) against an edge of body B with outward normal n and
tangent t = (-n_y, n_x), with d_A = P - p_A, d_B = P - p_B (carrier origins) and the unit force
wrench w(f) = (f_x, f_y, d x f):

- relative velocity v_rel = v_A(P) - v_B(P); gN' = n . v_rel and gT' = t . v_rel (m/s);
- force directions w_N = B_A^T w_A(n) - B_B^T w_B(n) and w_T likewise with t (length n);
- gN'' = w_N . q'' + wbar_N with
  wbar_N = w_A(n).beta_A - w_B(n).beta_B - phi'_A^2 n.d_A + phi'_B^2 n.d_B + 2 phi'_B (n x v_rel),
  wbar_T = w_A(t).beta_A - w_B(t).beta_B - phi'_A^2 t.d_A + phi'_B^2 t.d_B - 2 phi'_B (n . v_rel)
  (the last terms come from the rotation of B's edge).
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit

FIXED = 0
GENERALIZED = 1
DEPENDENT = 2


@jit(refcount=False)
def body_frames(binding, binding_index, start_pose, carrier, pose, vel, B, bhat, beta, trig):
    """The parts of every body's state that do not change: B, bhat and beta of axes that are
    generalized or fixed coordinates, pose and velocity of fixed ones, and (cos, sin) of fixed
    angles in trig (nb, 2). Call it once on the arrays that :func:`body_states` then fills, which
    writes only what changes."""
    n = B.shape[2]
    for b in range(binding.shape[0]):
        if carrier[b] >= 0:
            continue
        if binding[b, 2] == FIXED:
            trig[b, 0], trig[b, 1] = np.cos(start_pose[b, 2]), np.sin(start_pose[b, 2])
        for a in range(3):
            kind = binding[b, a]
            if kind == DEPENDENT:
                continue
            for j in range(n):
                B[b, a, j] = 0.0
            bhat[b, a] = 0.0
            beta[b, a] = 0.0
            if kind == GENERALIZED:
                B[b, a, binding_index[b, a]] = 1.0
            else:
                pose[b, a] = start_pose[b, a]
                vel[b, a] = 0.0


@jit(refcount=False)
def body_states(
    binding, binding_index, carrier, offset, q, qd, dep_pos, dep_vel, dep_jac, dep_scalar, pose, vel, B, bhat, beta,
    trig,
):
    """Pose (nb, 3), velocity (nb, 3), B (nb, 3, n), bhat (nb, 3), beta (nb, 3) and (cos, sin) of
    the angle (trig, nb x 2) of every body, in arrays that :func:`body_frames` prepared. Each
    angle's cosine and sine are computed once: fixed angles by :func:`body_frames`, a virtual
    body's at a zero angle offset are its carrier's.

    dep_pos, dep_vel (m,), dep_jac (m, n), dep_scalar (m,): the dependent coordinates' values,
    velocities, J and j at the current state. Virtual bodies get pose and velocity from their
    carrier; their B, bhat and beta are those of the carrier.
    """
    nb = binding.shape[0]
    n = q.shape[0]
    for b in range(nb):
        if carrier[b] >= 0:
            continue
        for a in range(3):
            kind = binding[b, a]
            k = binding_index[b, a]
            if kind == GENERALIZED:
                pose[b, a] = q[k]
                vel[b, a] = qd[k]
            elif kind == DEPENDENT:
                pose[b, a] = dep_pos[k]
                vel[b, a] = dep_vel[k]
                s = 0.0
                for j in range(n):
                    B[b, a, j] = dep_jac[k, j]
                    s += dep_jac[k, j] * qd[j]
                bhat[b, a] = dep_vel[k] - s
                beta[b, a] = dep_scalar[k]
        if binding[b, 2] != FIXED:
            trig[b, 0], trig[b, 1] = np.cos(pose[b, 2]), np.sin(pose[b, 2])
    for b in range(nb):
        c = carrier[b]
        if c < 0:
            continue
        cs, sn = trig[c, 0], trig[c, 1]
        dx = cs * offset[b, 0] - sn * offset[b, 1]
        dy = sn * offset[b, 0] + cs * offset[b, 1]
        pose[b, 0] = pose[c, 0] + dx
        pose[b, 1] = pose[c, 1] + dy
        pose[b, 2] = pose[c, 2] + offset[b, 2]
        vel[b, 0] = vel[c, 0] - vel[c, 2] * dy
        vel[b, 1] = vel[c, 1] + vel[c, 2] * dx
        vel[b, 2] = vel[c, 2]
        if offset[b, 2] == 0.0:
            trig[b, 0], trig[b, 1] = cs, sn
        else:
            trig[b, 0], trig[b, 1] = np.cos(pose[b, 2]), np.sin(pose[b, 2])
        for a in range(3):
            for j in range(n):
                B[b, a, j] = B[c, a, j]
            bhat[b, a] = bhat[c, a]
            beta[b, a] = beta[c, a]


@jit(refcount=False)
def contact_kinematics(
    index, count, c_vertex_body, c_edge_body, c_normal, c_point, carrier, pose, vel, B, bhat, beta,
    WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t,
):
    """Force directions, velocity offsets and relative velocities of the contacts
    index[:count]: rows of WN, WT (cap, n) and entries of what_n, what_t, wbar_n, wbar_t, gd_n,
    gd_t (cap,)."""
    n = WN.shape[1]
    for c in range(count):
        i = index[c]
        a = c_vertex_body[i]
        b = c_edge_body[i]
        if carrier[a] >= 0:
            a = carrier[a]
        if carrier[b] >= 0:
            b = carrier[b]
        nx, ny = c_normal[i, 0], c_normal[i, 1]
        tx, ty = -ny, nx
        px, py = c_point[i, 0], c_point[i, 1]
        dax, day = px - pose[a, 0], py - pose[a, 1]
        dbx, dby = px - pose[b, 0], py - pose[b, 1]
        wa, wb = vel[a, 2], vel[b, 2]
        vx = (vel[a, 0] - wa * day) - (vel[b, 0] - wb * dby)
        vy = (vel[a, 1] + wa * dax) - (vel[b, 1] + wb * dbx)
        gd_n[i] = nx * vx + ny * vy
        gd_t[i] = tx * vx + ty * vy
        ma_n = dax * ny - day * nx
        mb_n = dbx * ny - dby * nx
        ma_t = dax * ty - day * tx
        mb_t = dbx * ty - dby * tx
        for j in range(n):
            WN[i, j] = (B[a, 0, j] * nx + B[a, 1, j] * ny + B[a, 2, j] * ma_n) - (
                B[b, 0, j] * nx + B[b, 1, j] * ny + B[b, 2, j] * mb_n
            )
            WT[i, j] = (B[a, 0, j] * tx + B[a, 1, j] * ty + B[a, 2, j] * ma_t) - (
                B[b, 0, j] * tx + B[b, 1, j] * ty + B[b, 2, j] * mb_t
            )
        what_n[i] = (bhat[a, 0] * nx + bhat[a, 1] * ny + bhat[a, 2] * ma_n) - (
            bhat[b, 0] * nx + bhat[b, 1] * ny + bhat[b, 2] * mb_n
        )
        what_t[i] = (bhat[a, 0] * tx + bhat[a, 1] * ty + bhat[a, 2] * ma_t) - (
            bhat[b, 0] * tx + bhat[b, 1] * ty + bhat[b, 2] * mb_t
        )
        n_cross_v = nx * vy - ny * vx
        n_dot_v = gd_n[i]
        wbar_n[i] = (
            (beta[a, 0] * nx + beta[a, 1] * ny + beta[a, 2] * ma_n)
            - (beta[b, 0] * nx + beta[b, 1] * ny + beta[b, 2] * mb_n)
            - wa * wa * (nx * dax + ny * day)
            + wb * wb * (nx * dbx + ny * dby)
            + 2.0 * wb * n_cross_v
        )
        wbar_t[i] = (
            (beta[a, 0] * tx + beta[a, 1] * ty + beta[a, 2] * ma_t)
            - (beta[b, 0] * tx + beta[b, 1] * ty + beta[b, 2] * mb_t)
            - wa * wa * (tx * dax + ty * day)
            + wb * wb * (tx * dbx + ty * dby)
            - 2.0 * wb * n_dot_v
        )
