"""Time stepping of a model with unilateral contacts, impacts and friction.

One call of :func:`advance` integrates from the current state until a given time, or until a
buffer is full, and returns a status; the caller empties buffers and calls again. All state
lives in arrays the caller owns, so a run can be interrupted and resumed exactly.

Each step, at (q, u, t):

1. body kinematics from q (generalized, dependent and fixed coordinates; virtual bodies);
2. contact detection with a margin per pair of ``maxPen + (1 + f) * v * dt_max`` (f the
   larger ``maximumDisplacementFactor`` of the two bodies, v their largest vertex speed);
3. the step is checked: if penetration grew beyond ``maximumPenetration`` since the last accepted
   state and the step was longer than ``minimumTimestep``, it is rejected and retried from its
   start with half the step;
4. closed contacts (gap <= 0) approaching faster than ``ZeroVelocityTolerance`` start an impact:
   a compression and an expansion LCP over all closed contacts change the velocities;
5. closed contacts that do not separate faster than the rest velocity (``maximumPenetration /
   maximumTimestep``) form the acceleration LCP with Coulomb friction; contacts slower than the
   rest velocity tangentially are stick candidates, the others slide;
6. the step size: grown by 1.5 up to ``maximumTimestep``, limited so that no approaching contact
   penetrates by more than ``maximumPenetration``, at least ``minimumTimestep``, and cut to land on
   history sample times;
7. Heun's method (explicit trapezoidal rule) over the step, with the contact set of step 5 and
   the LCP solved again at the end point; lost work is integrated by the trapezoidal rule.

Contributions of a step (lost work, impulses, energy counters) stay pending until the next
step accepts it; ``TryToSolveByGoingBack`` can then return to the start of the previous step.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.contact_problem import (
    build_matrix,
    inverse_mass_rows,
    row_dot,
    rows_dot,
    tangential_forces,
)
from mbds.kernel.detection import (
    bounding_boxes,
    contact_geometry,
    detect_contacts,
    world_points,
)
from mbds.kernel.jit import jit
from mbds.kernel.kinematics import body_states, contact_kinematics
from mbds.kernel.lcp import SOLVED, lemke
from mbds.kernel.linalg import cholesky, cholesky_solve
from mbds.kernel.random import uniform

# settings array
DT_MIN, DT_MAX, MAX_PEN, ZERO_VELOCITY, PIVOT_MIN, PIVOT_MAX, LEXICO, LEXICO_LOW, LEXICO_HIGH = range(9)
GO_BACK, SAMPLE_EVERY, SAMPLE_AT_COLLISION, SAMPLE_EACH_STEP, MAX_PIVOTS, SETTINGS = range(9, 15)

# clock array
T, DT, NEXT_SAMPLE, STEPS, IMPACTS, REJECTED, LOST, DRIVE_WORK, MAX_PENETRATION = range(9)
LCP_FAILURES, OVER_PENETRATIONS, LAST_PENETRATION, CLOCK = range(9, 13)

# statuses of advance
REACHED, HISTORY_FULL, EVENTS_FULL, CAPACITY, NOT_FINITE = range(5)

# event codes (events array rows: time, code, value, value)
EVENT_LCP_RAY, EVENT_LCP_MAX_PIVOTS, EVENT_LCP_FAILURE, EVENT_OVER_PENETRATION, EVENT_BAD_LAW, EVENT_SINGULAR_MASS = range(6)

# columns of per-point accumulators
IMP_N, IMP_T, IMP_X, IMP_Y, WORK, ANGLE, POINT_COLUMNS = range(7)

# float columns of the per-contact records kept for going back (integer columns: vertex,
# edge start and edge end points; the closing point of a shape is never used: see _edge_end)
R_XI, R_IMP_N, R_IMP_T, R_IMP_X, R_IMP_Y, R_LOSS, R_ANGLE, RECORD_COLUMNS = range(8)

REST_FRACTION = 0.01
"""A closed contact whose normal speed is below the rest velocity REST_FRACTION * maxPen /
dt_max is at rest: within a maximum step it moves by at most 1 % of the allowed penetration."""
STICK_FRACTION = 1e-3
"""A contact at rest whose sliding speed is below STICK_FRACTION times the rest velocity is a
stick candidate; a faster one slides, and the step ends where its sliding speed reaches zero."""
CLOSED_FRACTION = 0.01
"""A contact whose gap is below CLOSED_FRACTION * maxPen is closed (touching)."""


@jit(inline="always")
def advance(
    mass_matrix, h_vector, dependent_state, dependent_jacobian, mechanical_energy, contact_law,
    model, settings, until, clock, q, u, rng, point_loss, point_interval, history, events, ws,
):
    """Integrate until time ``until`` (s) or until a buffer fills; return a status.

    model: tuple of the kernel arrays (see mbds.run.buffers); settings (SETTINGS,); clock
    (CLOCK,) time, step and counters; q, u (n,); rng: uint64 (1,); point_loss (P,) lost work
    accumulated per shape point (J); point_interval (P, POINT_COLUMNS) impulses (N s), lost work
    (J) and contact angle (rad) per point since the last history sample; history, events, ws:
    output buffers and workspace.
    """
    (binding, binding_index, start_pose, carrier, offset, points, point_start, skin, factor,
     radius, pair_bodies, pair_law, pair_resisting, pair_temperature, watch_start, watch_points, p) = model
    h_count = history[-1]
    (world, boxes, pose, vel, B, bhat, beta, dpos, dvel, dacc, djac, dsc, zero, margin,
     c_pair, c_vb, c_vertex, c_eb, c_edge, c_xi, c_gap, c_normal, c_point, det_work,
     WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t, laws,
     M, L, hv, minv_h, YN, YT, column, hrow, active, stick, sign, A_flat, bvec, z, w, fwork, iwork,
     lam_n, lam_t, lam_n1, lam_t1, imp_n, imp_t, gam_n, gam_t, compression_loss, a1, a2, q_star, u_star,
     backup_q, backup_u, backup_clock, records_int, records_float, record_count, last_sample, law_out) = ws
    n = q.shape[0]
    while True:
        t = clock[T]
        for k in range(n):
            if not (np.isfinite(q[k]) and np.isfinite(u[k])):
                return NOT_FINITE
        # --- 1, 2: kinematics and contacts at the current state
        _kinematics(dependent_state, dependent_jacobian, binding, binding_index, start_pose, carrier, offset,
                    q, u, t, p, zero, pose, vel, B, bhat, beta, dpos, dvel, dacc, djac, dsc)
        world_points(pose, points, point_start, world)
        bounding_boxes(world, point_start, boxes)
        _margins(pair_bodies, carrier, vel, radius, factor, settings, margin)
        nc = detect_contacts(world, point_start, boxes, pair_bodies, pair_resisting, skin, margin,
                             c_pair, c_vb, c_vertex, c_eb, c_edge, c_xi, c_gap, c_normal, c_point, det_work)
        if nc < 0:
            return CAPACITY
        # --- 3: accept the step that led here, or go back to its start with half the step
        penetration = 0.0
        for i in range(nc):
            penetration = max(penetration, -c_gap[i])
        if penetration > max(settings[MAX_PEN], clock[LAST_PENETRATION]) and record_count[1] >= 0:
            if backup_clock[1, DT] > settings[DT_MIN] * 1.000001:
                _go_back(1, q, u, clock, point_loss, point_interval, backup_q, backup_u, backup_clock,
                         records_int, records_float, record_count)
                clock[DT] = max(0.5 * clock[DT], settings[DT_MIN])
                clock[REJECTED] += 1.0
                continue
            _event(events, t, EVENT_OVER_PENETRATION, penetration, settings[MAX_PEN])
            clock[OVER_PENETRATIONS] += 1.0
        clock[LAST_PENETRATION] = penetration
        clock[MAX_PENETRATION] = max(clock[MAX_PENETRATION], penetration)
        # --- the state at t is final: history, end, buffers
        due = t >= clock[NEXT_SAMPLE] - 1e-12 * max(1.0, abs(t)) or settings[SAMPLE_EACH_STEP] > 0.0
        if due and t > last_sample[0]:  # (after going back, the start time is not sampled twice)
            if h_count[0] >= history[0].shape[0]:
                return HISTORY_FULL
            if n > 0 and np.isnan(a2[0]):  # no step has computed the accelerations at t yet
                contact_kinematics(nc, c_vb, c_eb, c_normal, c_point, carrier, pose, vel, B, bhat, beta,
                                   WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t)
                _laws(contact_law, nc, c_pair, pair_law, pair_temperature, gd_t, p, law_out, laws, events, t)
                if not _dynamics(mass_matrix, h_vector, q, u, t, p, M, L, hv, minv_h, WN, WT, YN, YT, nc):
                    return NOT_FINITE
                _contact_forces(nc, c_gap, gd_n, gd_t, settings, settings[LEXICO], active, stick, sign, laws,
                                WN, WT, YN, YT, minv_h, wbar_n, wbar_t, column, hrow, A_flat, bvec, z, w,
                                fwork, iwork, lam_n, lam_t, a2, events, t)
            _sample(mechanical_energy, q, u, a2, t, p, clock, point_interval, watch_start, watch_points, history)
            last_sample[0] = t
            record_count[0] = -1  # no going back past a sample
            record_count[1] = -1
            # the next sample time as a multiple of the interval (no drift from repeated sums)
            clock[NEXT_SAMPLE] = (np.floor(t / settings[SAMPLE_EVERY] + 1e-9) + 1.0) * settings[SAMPLE_EVERY]
        if t >= until - 1e-12 * max(1.0, abs(until)):
            return REACHED
        if events[1][0] + 8 > events[0].shape[0]:
            return EVENTS_FULL
        _begin_step(q, u, clock, backup_q, backup_u, backup_clock, records_int, records_float, record_count)
        if settings[LEXICO_HIGH] > 0.0:
            tol_lex = uniform(rng, settings[LEXICO_LOW], settings[LEXICO_HIGH])
        else:
            tol_lex = settings[LEXICO]
        contact_kinematics(nc, c_vb, c_eb, c_normal, c_point, carrier, pose, vel, B, bhat, beta,
                           WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t)
        _laws(contact_law, nc, c_pair, pair_law, pair_temperature, gd_t, p, law_out, laws, events, t)
        if not _dynamics(mass_matrix, h_vector, q, u, t, p, M, L, hv, minv_h, WN, WT, YN, YT, nc):
            _event(events, t, EVENT_SINGULAR_MASS, 0.0, 0.0)
            return NOT_FINITE
        # --- 4: impact
        impacting = False
        for i in range(nc):
            if c_gap[i] <= CLOSED_FRACTION * settings[MAX_PEN] and gd_n[i] < -settings[ZERO_VELOCITY]:
                impacting = True
        solved = True
        if impacting:
            solved = _impact(nc, c_gap, gd_n, gd_t, what_n, what_t, WN, WT, YN, YT, laws, u, settings, tol_lex,
                             active, stick, sign, column, hrow, A_flat, bvec, z, w, fwork, iwork,
                             imp_n, imp_t, lam_n, lam_t, gam_n, gam_t, compression_loss, events, t, clock,
                             c_vertex, c_edge, c_eb, point_start, c_xi, c_normal, point_loss, point_interval,
                             records_int, records_float, record_count)
            clock[IMPACTS] += 1.0
        # --- 5: forces between impacts
        na, forces_ok = _contact_forces(nc, c_gap, gd_n, gd_t, settings, tol_lex, active, stick, sign, laws,
                                        WN, WT, YN, YT, minv_h, wbar_n, wbar_t, column, hrow, A_flat, bvec, z, w,
                                        fwork, iwork, lam_n1, lam_t1, a1, events, t)
        solved = solved and forces_ok
        if not solved:
            clock[LCP_FAILURES] += 1.0
            if settings[GO_BACK] > 0.0 and record_count[0] >= 0 and backup_clock[0, DT] > settings[DT_MIN] * 1.000001:
                _go_back(0, q, u, clock, point_loss, point_interval, backup_q, backup_u, backup_clock,
                         records_int, records_float, record_count)
                clock[DT] = max(0.5 * clock[DT], settings[DT_MIN])
                continue
        # --- 6: step size
        dt = min(1.5 * clock[DT], settings[DT_MAX])
        for i in range(nc):
            if c_gap[i] > CLOSED_FRACTION * settings[MAX_PEN]:  # open: reach at most half maxPen
                accel = row_dot(WN, i, a1) + wbar_n[i]
                dt = min(dt, _time_to_reach(c_gap[i] + 0.5 * settings[MAX_PEN], gd_n[i], accel))
        for a in range(na):  # a sliding contact stops at the end of the step, not beyond
            i = active[a]
            if not stick[i]:
                accel = row_dot(WT, i, a1) + wbar_t[i]
                if gd_t[i] * accel < 0.0:
                    dt = min(dt, -gd_t[i] / accel)
        dt = max(dt, settings[DT_MIN])
        clock[DT] = dt
        t2 = t + dt
        target = min(clock[NEXT_SAMPLE], until)
        if t2 >= target:  # land exactly on the sample time or the end
            dt = target - t
            t2 = target
        # --- 7: Heun step with the contact set of step 5
        power = 0.0
        drive = 0.0
        for a in range(na):
            i = active[a]
            power += lam_n1[i] * gd_n[i] + lam_t1[i] * gd_t[i]
            drive -= lam_n1[i] * what_n[i] + lam_t1[i] * what_t[i]
            gam_n[i] = gd_n[i]
            gam_t[i] = gd_t[i]
        for k in range(n):
            q_star[k] = q[k] + dt * u[k]
            u_star[k] = u[k] + dt * a1[k]
        _kinematics(dependent_state, dependent_jacobian, binding, binding_index, start_pose, carrier, offset,
                    q_star, u_star, t2, p, zero, pose, vel, B, bhat, beta, dpos, dvel, dacc, djac, dsc)
        world_points(pose, points, point_start, world)
        contact_geometry(world, c_vertex, c_edge, nc, c_xi, c_gap, c_normal, c_point)
        contact_kinematics(nc, c_vb, c_eb, c_normal, c_point, carrier, pose, vel, B, bhat, beta,
                           WN, WT, what_n, what_t, wbar_n, wbar_t, gd_n, gd_t)
        end_ok = _dynamics(mass_matrix, h_vector, q_star, u_star, t2, p, M, L, hv, minv_h, WN, WT, YN, YT, nc)
        end_ok = end_ok and _accelerations(na, active, stick, sign, laws, WN, WT, YN, YT, minv_h, wbar_n, wbar_t,
                                           settings, tol_lex, column, hrow, A_flat, bvec, z, w, fwork, iwork,
                                           lam_n, lam_t, a2, events, t2)
        if not end_ok:
            for k in range(n):
                a2[k] = a1[k]
            for a in range(na):
                lam_n[active[a]] = lam_n1[active[a]]
                lam_t[active[a]] = lam_t1[active[a]]
        for a in range(na):
            i = active[a]
            power += lam_n[i] * gd_n[i] + lam_t[i] * gd_t[i]
            drive -= lam_n[i] * what_n[i] + lam_t[i] * what_t[i]
            _record(c_vertex[i], c_edge[i], _edge_end(c_edge[i], c_eb[i], point_start), c_xi[i],
                    c_normal[i, 0], c_normal[i, 1],
                    0.5 * dt * (lam_n1[i] + lam_n[i]), 0.5 * dt * (lam_t1[i] + lam_t[i]),
                    -0.5 * dt * (lam_n1[i] * gam_n[i] + lam_t1[i] * gam_t[i] + lam_n[i] * gd_n[i] + lam_t[i] * gd_t[i]),
                    point_loss, point_interval, records_int, records_float, record_count)
        for k in range(n):
            q[k] += 0.5 * dt * (u[k] + u_star[k])
            u[k] += 0.5 * dt * (a1[k] + a2[k])
        clock[LOST] -= 0.5 * dt * power
        clock[DRIVE_WORK] += 0.5 * dt * drive
        clock[T] = t2
        clock[STEPS] += 1.0
        if impacting and settings[SAMPLE_AT_COLLISION] > 0.0:
            clock[NEXT_SAMPLE] = min(clock[NEXT_SAMPLE], t2)


@jit(inline="always")
def _laws(contact_law, nc, c_pair, pair_law, pair_temperature, gd_t, p, law_out, laws, events, t):
    """Friction and restitution coefficients of every contact at its current sliding speed."""
    for i in range(nc):
        if not _contact_law(contact_law, pair_law[c_pair[i]], abs(gd_t[i]), pair_temperature[c_pair[i]], p, law_out):
            _event(events, t, EVENT_BAD_LAW, float(c_pair[i]), abs(gd_t[i]))
        for j in range(4):
            laws[i, j] = law_out[j]


@jit
def _contact_forces(nc, c_gap, gd_n, gd_t, settings, tol_lex, active, stick, sign, laws, WN, WT, YN, YT, minv_h,
                    wbar_n, wbar_t, column, hrow, A_flat, bvec, z, w, fwork, iwork, lam_n, lam_t, acc, events, t):
    """The contacts at rest (closed, not separating faster than the rest velocity), their forces
    and the accelerations; returns (number of contacts at rest, solved)."""
    rest = REST_FRACTION * settings[MAX_PEN] / settings[DT_MAX]
    na = 0
    for i in range(nc):
        if c_gap[i] <= CLOSED_FRACTION * settings[MAX_PEN] and gd_n[i] <= rest:
            active[na] = i
            na += 1
            stick[i] = abs(gd_t[i]) <= STICK_FRACTION * rest
            sign[i] = 1.0 if gd_t[i] > 0.0 else -1.0
    ok = _accelerations(na, active, stick, sign, laws, WN, WT, YN, YT, minv_h, wbar_n, wbar_t, settings, tol_lex,
                        column, hrow, A_flat, bvec, z, w, fwork, iwork, lam_n, lam_t, acc, events, t)
    return na, ok


@jit(inline="always")
def _dynamics(mass_matrix, h_vector, q, u, t, p, M, L, hv, minv_h, WN, WT, YN, YT, nc):
    """M, its Cholesky factor, h, M^-1 h and M^-1 W of the contacts; False if M is not SPD."""
    mass_matrix(q, t, p, M)
    if not cholesky(M, L):
        return False
    h_vector(q, u, t, p, hv)
    cholesky_solve(L, hv, minv_h)
    inverse_mass_rows(L, WN, nc, YN)
    inverse_mass_rows(L, WT, nc, YT)
    return True


@jit(inline="always")
def _kinematics(dependent_state, dependent_jacobian, binding, binding_index, start_pose, carrier, offset,
                q, u, t, p, zero, pose, vel, B, bhat, beta, dpos, dvel, dacc, djac, dsc):
    if dpos.shape[0] > 0:
        dependent_state(q, u, zero, t, p, dpos, dvel, dacc)
        dependent_jacobian(q, u, t, p, djac, dsc)
    body_states(binding, binding_index, start_pose, carrier, offset, q, u, dpos, dvel, djac, dsc,
                pose, vel, B, bhat, beta)


@jit
def _time_to_reach(distance, rate, accel):
    """The first time (s) at which a gap that is ``distance`` (m) above a target, changing at
    ``rate`` (m/s) with ``accel`` (m/s^2), reaches it; inf if it never does."""
    if accel == 0.0:
        return distance / -rate if rate < 0.0 else np.inf
    disc = rate * rate - 2.0 * accel * distance
    if disc < 0.0:
        return np.inf
    root = np.sqrt(disc)
    first = (-rate - root) / accel if accel > 0.0 else 2.0 * distance / (-rate + root)
    if first > 0.0:
        return first
    second = (-rate + root) / accel
    return second if second > 0.0 else np.inf


@jit
def _margins(pair_bodies, carrier, vel, radius, factor, settings, margin):
    """Detection margin of each pair (m): maxPen + (1 + f) v dt_max (see the module
    documentation): at least one maximum step of travel, so no vertex can pass from beyond
    the margin to beyond the skin in one step."""
    for k in range(pair_bodies.shape[0]):
        extent = 0.0
        for side in range(2):
            b = pair_bodies[k, side]
            c = carrier[b] if carrier[b] >= 0 else b
            speed = np.sqrt(vel[c, 0] ** 2 + vel[c, 1] ** 2) + abs(vel[c, 2]) * (radius[b] + radius[c])
            extent = max(extent, (1.0 + factor[b]) * speed * settings[DT_MAX])
        margin[k] = settings[MAX_PEN] + extent


@jit(inline="always")
def _contact_law(contact_law, k, vrel, temperature, p, out):
    """Evaluate law k into out (mu, eN, eT, nu); non-finite or negative values become 0 and
    restitutions are clipped to [0, 1]; return False when anything had to be corrected."""
    contact_law(k, vrel, temperature, p, out)
    ok = True
    for j in range(4):
        if not np.isfinite(out[j]) or out[j] < 0.0:
            out[j] = 0.0
            ok = False
    for j in range(1, 3):
        if out[j] > 1.0:
            out[j] = 1.0
            ok = False
    return ok


@jit
def _solve(m, A_flat, bvec, z, w, fwork, iwork, settings, tol_lex, events, t):
    """Solve the LCP of size m held in A_flat/bvec; log failures; return True when solved."""
    if m == 0:
        return True
    A = A_flat[: m * m].reshape((m, m))
    status, pivots = lemke(A, bvec[:m], z[:m], w[:m], settings[PIVOT_MIN], settings[PIVOT_MAX], tol_lex,
                           int(settings[MAX_PIVOTS]), fwork, iwork)
    if status == SOLVED:
        return True
    _event(events, t, EVENT_LCP_RAY + status - 1, float(m), float(pivots))
    return False


@jit
def _accelerations(na, active, stick, sign, laws, WN, WT, YN, YT, minv_h, wbar_n, wbar_t, settings, tol_lex,
                   column, hrow, A_flat, bvec, z, w, fwork, iwork, lam_n, lam_t, acc, events, t):
    """Contact forces of the active contacts and the accelerations acc = M^-1 (h + W lambda)."""
    n = acc.shape[0]
    nh = build_matrix(active, na, stick, sign, laws, WN, WT, YN, YT, column, hrow, A_flat)
    m = na + 2 * nh
    for a in range(na):
        bvec[a] = row_dot(WN, active[a], minv_h) + wbar_n[active[a]]
    for g in range(nh):
        c = active[hrow[g]]
        bvec[na + g] = row_dot(WT, c, minv_h) + wbar_t[c]
        bvec[na + nh + g] = 0.0
    ok = _solve(m, A_flat, bvec, z, w, fwork, iwork, settings, tol_lex, events, t)
    for a in range(na):
        lam_n[active[a]] = 0.0
        lam_t[active[a]] = 0.0
    if ok:
        tangential_forces(active, na, stick, sign, laws, z, lam_n, lam_t)
    for k in range(n):
        acc[k] = minv_h[k]
    for a in range(na):
        c = active[a]
        for k in range(n):
            acc[k] += lam_n[c] * YN[c, k] + lam_t[c] * YT[c, k]
    return ok


@jit
def _impact(nc, c_gap, gd_n, gd_t, what_n, what_t, WN, WT, YN, YT, laws, u, settings, tol_lex,
            active, stick, sign, column, hrow, A_flat, bvec, z, w, fwork, iwork,
            imp_n, imp_t, lam_ne, lam_te, gam_n, gam_t, compression_loss, events, t, clock,
            c_vertex, c_edge, c_eb, point_start, c_xi, c_normal, point_loss, point_interval,
            records_int, records_float, record_count):
    """Compression and expansion LCPs over all closed contacts (Poisson's law, see
    docs/theory.md); updates u, gd_n and gd_t, records impulses and losses. Returns False when
    an LCP failed: velocities are then left unchanged (compression failed) or those after
    compression are kept (expansion failed)."""
    na = 0
    for i in range(nc):
        if c_gap[i] <= CLOSED_FRACTION * settings[MAX_PEN]:
            active[na] = i
            na += 1
            stick[i] = True
            sign[i] = 0.0
            gam_n[i] = gd_n[i]  # gamma_A
            gam_t[i] = gd_t[i]
    nh = build_matrix(active, na, stick, sign, laws, WN, WT, YN, YT, column, hrow, A_flat)
    m = na + 2 * nh
    for a in range(na):  # compression: b = (gamma_NA, gamma_TA, 0)
        c = active[a]
        bvec[a] = gd_n[c]
        bvec[na + a] = gd_t[c]
        bvec[2 * na + a] = 0.0
    if not _solve(m, A_flat, bvec, z, w, fwork, iwork, settings, tol_lex, events, t):
        return False
    tangential_forces(active, na, stick, sign, laws, z, imp_n, imp_t)
    _apply_impulses(active, na, imp_n, imp_t, YN, YT, u)
    _relative_velocities(active, na, WN, WT, what_n, what_t, u, gd_n, gd_t)
    # expansion: start from eN Lambda_NC (with its -mu tangential partner) and eT Lambda_TC;
    # the LCP adds the increments that keep contacts from closing, within Coulomb's cone
    for a in range(na):
        c = active[a]
        lam_ne[c] = laws[c, 1] * imp_n[c]
        lam_te[c] = laws[c, 2] * imp_t[c] - laws[c, 0] * lam_ne[c]
    for a in range(na):
        c = active[a]
        sn = gd_n[c]
        st = gd_t[c]
        for b in range(na):
            e = active[b]
            sn += rows_dot(WN, c, YN, e) * lam_ne[e] + rows_dot(WN, c, YT, e) * lam_te[e]
            st += rows_dot(WT, c, YN, e) * lam_ne[e] + rows_dot(WT, c, YT, e) * lam_te[e]
        bvec[a] = sn
        bvec[na + a] = st
        bvec[2 * na + a] = 2.0 * laws[c, 0] * lam_ne[c]
    expanded = _solve(m, A_flat, bvec, z, w, fwork, iwork, settings, tol_lex, events, t)
    for a in range(na):
        c = active[a]
        if expanded:
            lam_ne[c] += z[a]
            lam_te[c] = laws[c, 2] * imp_t[c] + z[na + a] - laws[c, 0] * lam_ne[c]
        else:  # keep the compression result: a plastic impact
            lam_ne[c] = 0.0
            lam_te[c] = 0.0
    lost = 0.0
    drive = 0.0
    for a in range(na):  # loss of the compression phase; then gam_* <- gamma_C
        c = active[a]
        compression_loss[c] = -0.5 * (imp_n[c] * (gam_n[c] + gd_n[c]) + imp_t[c] * (gam_t[c] + gd_t[c]))
        gam_n[c] = gd_n[c]
        gam_t[c] = gd_t[c]
    _apply_impulses(active, na, lam_ne, lam_te, YN, YT, u)
    _relative_velocities(active, na, WN, WT, what_n, what_t, u, gd_n, gd_t)
    for a in range(na):
        c = active[a]
        loss = compression_loss[c] - 0.5 * (lam_ne[c] * (gam_n[c] + gd_n[c]) + lam_te[c] * (gam_t[c] + gd_t[c]))
        lost += loss
        drive -= (imp_n[c] + lam_ne[c]) * what_n[c] + (imp_t[c] + lam_te[c]) * what_t[c]
        _record(c_vertex[c], c_edge[c], _edge_end(c_edge[c], c_eb[c], point_start), c_xi[c],
                c_normal[c, 0], c_normal[c, 1], imp_n[c] + lam_ne[c],
                imp_t[c] + lam_te[c], loss, point_loss, point_interval, records_int, records_float, record_count)
    clock[LOST] += lost
    clock[DRIVE_WORK] += drive
    return expanded


@jit
def _apply_impulses(active, na, imp_n, imp_t, YN, YT, u):
    for a in range(na):
        c = active[a]
        for k in range(u.shape[0]):
            u[k] += imp_n[c] * YN[c, k] + imp_t[c] * YT[c, k]


@jit
def _relative_velocities(active, na, WN, WT, what_n, what_t, u, gd_n, gd_t):
    for a in range(na):
        c = active[a]
        gd_n[c] = row_dot(WN, c, u) + what_n[c]
        gd_t[c] = row_dot(WT, c, u) + what_t[c]


@jit
def _event(events, t, code, a, b):
    data, count = events
    k = count[0]
    if k < data.shape[0]:
        data[k, 0] = t
        data[k, 1] = code
        data[k, 2] = a
        data[k, 3] = b
        count[0] = k + 1


@jit(inline="always")
def _record(vertex, edge, edge_end, xi, nx, ny, imp_n, imp_t, loss, point_loss, point_interval,
            records_int, records_float, record_count):
    """Add a contact's impulses (N s) and lost work (J) of this step to its points, and keep
    the record so that going back can take it out again.

    The vertex point gets all of it; the edge's two points share it as (1 - xi, xi), with the
    impulse reversed (the reaction). Impulses are normal-tangential (n out of the edge body,
    t = (-n_y, n_x)) and x-y, as acting on the watched point's body.
    """
    imp_x = imp_n * nx - imp_t * ny
    imp_y = imp_n * ny + imp_t * nx
    angle = np.arctan2(ny, nx)
    _add_contact(vertex, edge, edge_end, xi, imp_n, imp_t, imp_x, imp_y, loss, angle, 1.0, point_loss, point_interval)
    k = max(record_count[1], 0)
    if k < records_int.shape[1]:
        records_int[1, k, 0] = vertex
        records_int[1, k, 1] = edge
        records_int[1, k, 2] = edge_end
        records_float[1, k, R_XI] = xi
        records_float[1, k, R_IMP_N] = imp_n
        records_float[1, k, R_IMP_T] = imp_t
        records_float[1, k, R_IMP_X] = imp_x
        records_float[1, k, R_IMP_Y] = imp_y
        records_float[1, k, R_LOSS] = loss
        records_float[1, k, R_ANGLE] = angle
        record_count[1] = k + 1
    else:  # no room to keep it: this step becomes final
        record_count[1] = -1
        record_count[0] = -1


@jit(inline="always")
def _edge_end(edge, body, point_start):
    """The point an edge ends at: the next point, or the body's first for its closing edge."""
    end = edge + 1
    return point_start[body] if end == point_start[body + 1] - 1 else end


@jit(inline="always")
def _take_out(records_int, records_float, slot, k, point_loss, point_interval):
    """Take record k of ``slot`` out of the per-point accumulators."""
    r = records_float
    _add_contact(records_int[slot, k, 0], records_int[slot, k, 1], records_int[slot, k, 2], r[slot, k, R_XI],
                 r[slot, k, R_IMP_N], r[slot, k, R_IMP_T], r[slot, k, R_IMP_X], r[slot, k, R_IMP_Y],
                 r[slot, k, R_LOSS], r[slot, k, R_ANGLE], -1.0, point_loss, point_interval)


@jit(inline="always")
def _add_contact(vertex, edge, edge_end, xi, imp_n, imp_t, imp_x, imp_y, loss, angle, scale, point_loss, point_interval):
    """Add (scale 1) or take out (scale -1) a contact's share at its vertex and edge points."""
    _add_point(vertex, scale, 1.0, imp_n, imp_t, imp_x, imp_y, loss, angle, point_loss, point_interval)
    _add_point(edge, (1.0 - xi) * scale, -1.0, imp_n, imp_t, imp_x, imp_y, loss, angle, point_loss, point_interval)
    _add_point(edge_end, xi * scale, -1.0, imp_n, imp_t, imp_x, imp_y, loss, angle, point_loss, point_interval)


@jit(inline="always")
def _add_point(point, share, direction, imp_n, imp_t, imp_x, imp_y, loss, angle, point_loss, point_interval):
    point_loss[point] += share * loss
    point_interval[point, IMP_N] += share * imp_n
    point_interval[point, IMP_T] += share * direction * imp_t
    point_interval[point, IMP_X] += share * direction * imp_x
    point_interval[point, IMP_Y] += share * direction * imp_y
    point_interval[point, WORK] += share * loss
    if share > 0.0:
        point_interval[point, ANGLE] = angle if direction > 0.0 else angle + np.pi


@jit
def _begin_step(q, u, clock, backup_q, backup_u, backup_clock, records_int, records_float, record_count):
    """Keep the start of this step (slot 1) and of the previous one (slot 0) for going back."""
    if record_count[1] >= 0:
        for k in range(record_count[1]):
            for j in range(records_int.shape[2]):
                records_int[0, k, j] = records_int[1, k, j]
            for j in range(records_float.shape[2]):
                records_float[0, k, j] = records_float[1, k, j]
        for k in range(q.shape[0]):
            backup_q[0, k] = backup_q[1, k]
            backup_u[0, k] = backup_u[1, k]
        for k in range(clock.shape[0]):
            backup_clock[0, k] = backup_clock[1, k]
    record_count[0] = record_count[1]
    for k in range(q.shape[0]):
        backup_q[1, k] = q[k]
        backup_u[1, k] = u[k]
    for k in range(clock.shape[0]):
        backup_clock[1, k] = clock[k]
    record_count[1] = 0


@jit
def _go_back(slot, q, u, clock, point_loss, point_interval, backup_q, backup_u, backup_clock,
             records_int, records_float, record_count):
    """Return to the start of the step kept in ``slot`` (1: the last step, 0: the one before),
    taking the records of the steps undone out of the accumulators; counters keep counting."""
    for s in range(1, slot - 1, -1):
        for k in range(max(record_count[s], 0)):
            _take_out(records_int, records_float, s, k, point_loss, point_interval)
    keep = np.empty(6)
    for j, c in enumerate((STEPS, IMPACTS, REJECTED, LCP_FAILURES, OVER_PENETRATIONS, MAX_PENETRATION)):
        keep[j] = clock[c]
    for k in range(q.shape[0]):
        q[k] = backup_q[slot, k]
        u[k] = backup_u[slot, k]
    for k in range(clock.shape[0]):
        clock[k] = backup_clock[slot, k]
    for j, c in enumerate((STEPS, IMPACTS, REJECTED, LCP_FAILURES, OVER_PENETRATIONS, MAX_PENETRATION)):
        clock[c] = keep[j]
    record_count[0] = -1
    record_count[1] = -1


@jit(inline="always")
def _sample(mechanical_energy, q, u, a, t, p, clock, point_interval, watch_start, watch_points, history):
    """Write a history sample and start a new interval of the per-point accumulators."""
    h_time, h_q, h_u, h_a, h_energy, h_lost, h_drive, h_watch, h_count = history
    k = h_count[0]
    h_time[k] = t
    for j in range(q.shape[0]):
        h_q[k, j] = q[j]
        h_u[k, j] = u[j]
        h_a[k, j] = a[j]
    h_energy[k] = mechanical_energy(q, u, t, p)
    h_lost[k] = clock[LOST]
    h_drive[k] = clock[DRIVE_WORK]
    for wi in range(watch_start.shape[0] - 1):
        for c in range(POINT_COLUMNS):
            h_watch[k, wi, c] = 0.0
        for m in range(watch_start[wi], watch_start[wi + 1]):
            pt = watch_points[m]
            for c in range(ANGLE):
                h_watch[k, wi, c] += point_interval[pt, c]
            h_watch[k, wi, ANGLE] = point_interval[pt, ANGLE]
    for pt in range(point_interval.shape[0]):
        for c in range(ANGLE):
            point_interval[pt, c] = 0.0
    h_count[0] = k + 1
