"""DAP_BC's equations of motion in body coordinates, and the analyses built on them (numba).

The model's generated functions come in as arguments: ``constraints(q, t, par, fv, out)`` Phi,
``jacobian(q, t, par, fv, D)``, ``velocity_rhs(q, t, par, fv, out)`` nu (D q' = nu),
``acceleration_rhs(q, qd, t, par, fv, out)`` gamma (D q'' = gamma), ``forces_before`` and
``forces_after(q, qd, t, par, fv, h)`` (the force elements before and after the user element,
added into h) and ``user_force`` (mbds.io.dapbc.user_force's signature).  The equations are
DAP_BC's (its analysis.m): [M -D^T; D 0] [q''; lam] = [h; gamma], with no stabilisation.
Units: SI; arrays float64, C-contiguous.

The functions that take the model's functions as arguments are inlined (numba IR) into the
analyses of mbds.kernel.dapbc_analyses, which are compiled once for all models and receive them
through a table of their addresses (mbds.kernel.function_table).
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.dapbc_functions import funct_values
from mbds.kernel.dapbc_layout import BodyArrays
from mbds.kernel.jit import jit
from mbds.kernel.linalg import gram, lu_solve, min_norm_solve

NEWTON_ITERATIONS = 50


@jit
def body_arrays(q, qd, point_body, point_local):
    """The BodyArrays of state (q, qd)."""
    nb = q.shape[0] // 3
    r, r_d = np.empty((nb, 2)), np.empty((nb, 2))
    p, p_d = np.empty(nb), np.empty(nb)
    A = np.empty((nb, 2, 2))
    for b in range(nb):
        r[b, 0], r[b, 1], p[b] = q[3 * b], q[3 * b + 1], q[3 * b + 2]
        r_d[b, 0], r_d[b, 1], p_d[b] = qd[3 * b], qd[3 * b + 1], qd[3 * b + 2]
        c, s = np.cos(p[b]), np.sin(p[b])
        A[b, 0, 0], A[b, 0, 1], A[b, 1, 0], A[b, 1, 1] = c, -s, s, c
    n_points = point_body.shape[0]
    rP, rP_d, sP = np.empty((n_points, 2)), np.zeros((n_points, 2)), np.empty((n_points, 2))
    for k in range(n_points):
        b = point_body[k]
        x, y = point_local[k, 0], point_local[k, 1]
        if b < 0:
            sP[k, 0], sP[k, 1] = x, y
            rP[k, 0], rP[k, 1] = x, y
            continue
        sP[k, 0] = A[b, 0, 0] * x + A[b, 0, 1] * y
        sP[k, 1] = A[b, 1, 0] * x + A[b, 1, 1] * y
        rP[k, 0], rP[k, 1] = r[b, 0] + sP[k, 0], r[b, 1] + sP[k, 1]
        rP_d[k, 0] = r_d[b, 0] - p_d[b] * sP[k, 1]
        rP_d[k, 1] = r_d[b, 1] + p_d[b] * sP[k, 0]
    return BodyArrays(r, p, r_d, p_d, A, rP, rP_d, sP)


@jit(inline="always")
def applied_forces(forces_before, forces_after, user_force, t, q, qd, data, state, fv, h):
    """h = the generalised applied forces (N, N m) of every force element, in list order."""
    h[:] = 0.0
    forces_before(q, qd, t, data.par, fv, h)
    if data.has_user:
        nb = q.shape[0] // 3
        a = body_arrays(q, qd, data.point_body, data.point_local)
        f, n = np.empty((nb, 2)), np.empty(nb)
        for b in range(nb):
            f[b, 0], f[b, 1], n[b] = h[3 * b], h[3 * b + 1], h[3 * b + 2]
        user_force(t, a.r, a.p, a.r_d, a.p_d, a.A, a.rP, a.rP_d, a.sP, data.force_fields, state, f, n)
        for b in range(nb):
            h[3 * b], h[3 * b + 1], h[3 * b + 2] = f[b, 0], f[b, 1], n[b]
    forces_after(q, qd, t, data.par, fv, h)


@jit(inline="always")
def accelerations(jacobian, acceleration_rhs, forces_before, forces_after, user_force,
                  t, y, data, state, yd, lam, D):
    """yd = (q', q'') of y = (q, q') at time t, the multipliers lam and the Jacobian D."""
    n = data.mass.shape[0]
    nc = lam.shape[0]
    q, qd = y[:n], y[n:]
    fv = np.empty((data.functs.shape[0], 3))
    funct_values(data.functs, t, fv)
    h = np.empty(n)
    applied_forces(forces_before, forces_after, user_force, t, q, qd, data, state, fv, h)
    yd[:n] = qd
    if nc == 0:
        yd[n:] = h / data.mass
        return
    jacobian(q, t, data.par, fv, D)
    gamma = np.empty(nc)
    acceleration_rhs(q, qd, t, data.par, fv, gamma)
    system = np.zeros((n + nc, n + nc))
    rhs = np.empty(n + nc)
    for i in range(n):
        system[i, i] = data.mass[i]
        rhs[i] = h[i]
    for k in range(nc):
        rhs[n + k] = gamma[k]
        for i in range(n):
            system[i, n + k] = -D[k, i]
            system[n + k, i] = D[k, i]
    solution, ok = lu_solve(system, rhs)
    if not ok:
        solution[:] = np.nan  # redundant constraints: the integrator stops on a state that is not finite
    yd[n:] = solution[:n]
    lam[:] = solution[n:]


@jit
def newton_step(x, solved):
    """x -= step for solved = (step, ok) from a linear solve; returns ok (x unchanged if not)."""
    step, ok = solved
    if ok:
        x -= step
    return ok


@jit(inline="always")
def correct_positions(constraints, jacobian, nc, q, t, par, functs, tolerance):
    """DAP_BC's correction of coordinates: minimum-norm Newton steps q -= D^+ Phi until
    max |Phi| <= tolerance (m, rad); returns the iterations taken (-1: no convergence)."""
    if nc == 0:
        return 0
    fv = np.empty((functs.shape[0], 3))
    funct_values(functs, t, fv)
    phi, D = np.empty(nc), np.empty((nc, q.shape[0]))
    for iteration in range(NEWTON_ITERATIONS):
        constraints(q, t, par, fv, phi)
        if np.max(np.abs(phi)) <= tolerance:
            return iteration
        jacobian(q, t, par, fv, D)
        if not newton_step(q, min_norm_solve(D, phi)):
            return -1
    return -1


@jit(inline="always")
def correct_velocities(jacobian, velocity_rhs, nc, q, qd, t, par, functs):
    """DAP_BC's correction of velocities: the minimum-norm change of qd that gives D qd = nu."""
    if nc == 0:
        return
    fv = np.empty((functs.shape[0], 3))
    funct_values(functs, t, fv)
    D, nu = np.empty((nc, q.shape[0])), np.empty(nc)
    jacobian(q, t, par, fv, D)
    velocity_rhs(q, t, par, fv, nu)
    residual = -nu
    for k in range(nc):
        for i in range(q.shape[0]):
            residual[k] += D[k, i] * qd[i]
    qd -= min_norm_solve(D, residual)[0]


@jit(inline="always")
def kinematic_state(constraints, jacobian, velocity_rhs, acceleration_rhs, nc, q, qd, qdd, t, par,
                    functs, tolerance):
    """Kinematic analysis at time t of a system with as many independent constraints as
    coordinates: q from Phi(q, t) = 0 by Newton from the given q, then D qd = nu and
    D qdd = gamma.  Returns the Newton iterations (-1: no convergence)."""
    iterations = correct_positions(constraints, jacobian, nc, q, t, par, functs, tolerance)
    fv = np.empty((functs.shape[0], 3))
    funct_values(functs, t, fv)
    D, rhs = np.empty((nc, q.shape[0])), np.empty(nc)
    jacobian(q, t, par, fv, D)
    velocity_rhs(q, t, par, fv, rhs)
    velocity, ok = lu_solve(D, rhs)
    qd[:] = velocity
    acceleration_rhs(q, qd, t, par, fv, rhs)
    acceleration, ok2 = lu_solve(D, rhs)
    qdd[:] = acceleration
    return iterations if ok and ok2 else -1


@jit(inline="always")
def inverse_multipliers(jacobian, forces_before, forces_after, user_force, t, q, qd, qdd, data, state, lam, D):
    """Inverse dynamics of a fully driven system (D square): lam from D^T lam = M qdd - h."""
    n = q.shape[0]
    fv = np.empty((data.functs.shape[0], 3))
    funct_values(data.functs, t, fv)
    h = np.empty(n)
    applied_forces(forces_before, forces_after, user_force, t, q, qd, data, state, fv, h)
    if lam.shape[0] == 0:
        return
    jacobian(q, t, data.par, fv, D)
    lam[:] = lu_solve(D.T.copy(), data.mass * qdd - h)[0]


@jit(inline="always")
def static_residual(constraints, jacobian, forces_before, forces_after, user_force, t, x, data, state, out):
    """F(q, lam) = (h(q, 0) + D^T lam, Phi(q)) for x = (q, lam): zero at static equilibrium."""
    n = data.mass.shape[0]
    nc = x.shape[0] - n
    q = x[:n].copy()
    fv = np.empty((data.functs.shape[0], 3))
    funct_values(data.functs, t, fv)
    h = np.empty(n)
    applied_forces(forces_before, forces_after, user_force, t, q, np.zeros(n), data, state, fv, h)
    out[:n] = h
    if nc > 0:
        D, phi = np.empty((nc, n)), np.empty(nc)
        jacobian(q, t, data.par, fv, D)
        constraints(q, t, data.par, fv, phi)
        for k in range(nc):
            for i in range(n):
                out[i] += D[k, i] * x[n + k]
        out[n:] = phi


@jit(inline="always")
def initial_multipliers(jacobian, forces_before, forces_after, user_force, t, x, data, state):
    """lam (x[n:]) = the least-squares solution of D^T lam = -h at q = x[:n]: the joints' share
    of the applied forces.  At lam = 0 the Newton matrix of the static equations would lack the
    joints' geometric stiffness (d(D^T lam)/dq) and may be singular."""
    n = data.mass.shape[0]
    nc = x.shape[0] - n
    if nc == 0:
        return
    q = x[:n].copy()
    fv = np.empty((data.functs.shape[0], 3))
    funct_values(data.functs, t, fv)
    h, D = np.empty(n), np.empty((nc, n))
    applied_forces(forces_before, forces_after, user_force, t, q, np.zeros(n), data, state, fv, h)
    jacobian(q, t, data.par, fv, D)
    Dh = np.zeros(nc)
    for k in range(nc):
        for i in range(n):
            Dh[k] -= D[k, i] * h[i]
    lam, ok = lu_solve(gram(D), Dh)
    if ok:
        x[n:] = lam


@jit(inline="always")
def static_equilibrium(constraints, jacobian, forces_before, forces_after, user_force, t, x, data, state, tolerance):
    """Newton's method on static_residual from x = (q, lam) with lam first set by
    initial_multipliers, with a forward-difference Jacobian; returns the iterations taken
    (-1: no convergence).  Stops when max |F| <= tolerance (N)."""
    size = x.shape[0]
    residual, shifted, matrix = np.empty(size), np.empty(size), np.empty((size, size))
    saved = state.copy()
    initial_multipliers(jacobian, forces_before, forces_after, user_force, t, x, data, state)
    state[:] = saved
    for iteration in range(NEWTON_ITERATIONS):
        static_residual(constraints, jacobian, forces_before, forces_after, user_force, t, x, data, state, residual)
        if np.max(np.abs(residual)) <= tolerance:
            return iteration
        for j in range(size):
            delta = 1e-7 * max(abs(x[j]), 1.0)
            keep = x[j]
            x[j] = keep + delta
            state[:] = saved
            static_residual(constraints, jacobian, forces_before, forces_after, user_force, t, x, data, state, shifted)
            x[j] = keep
            matrix[:, j] = (shifted - residual) / delta
        state[:] = saved
        if not newton_step(x, lu_solve(matrix, residual)):
            return -1
    return -1


@jit(inline="always")
def post(jacobian, acceleration_rhs, forces_before, forces_after, user_force, potential_energy,
         times, Y, states, data, out):
    """DAP_BC's post at every report k: accelerations, multipliers, Jacobian, points and energy
    from y = Y[k] with the model memory states[k] (a copy, so nothing leaks between reports).
    ``out`` is a DapbcPost bundle of preallocated arrays."""
    n = data.mass.shape[0]
    yd = np.empty(2 * n)
    for k in range(times.shape[0]):
        y = Y[k]
        state = states[k].copy()
        accelerations(jacobian, acceleration_rhs, forces_before, forces_after, user_force,
                      times[k], y, data, state, yd, out.lam[k], out.jac[k])
        out.qdd[k] = yd[n:]
        points(y, data, out.rP[k], out.rPd[k])
        kinetic = 0.5 * np.sum(data.mass * y[n:] ** 2)
        potential = potential_energy(y[:n], data.par)
        out.eng[k, 0], out.eng[k, 1], out.eng[k, 2] = kinetic, potential, kinetic + potential


@jit
def points(y, data, rP, rPd):
    """World positions and velocities of the model's points at y = (q, qd)."""
    n = data.mass.shape[0]
    a = body_arrays(y[:n], y[n:], data.point_body, data.point_local)
    rP[:] = a.rP
    rPd[:] = a.rP_d
