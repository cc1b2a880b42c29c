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
   a compression and an expansion LCP over the closed contacts of its group of coupled contacts
   (mbds.kernel.components) change the velocities, and the body velocities, contact rows, laws
   and h(q, u, t) are computed again from the new ones;
5. closed contacts that do not separate faster than the rest velocity (``maximumPenetration /
   maximumTimestep``) form the acceleration LCP with Coulomb friction; contacts slower than the
   rest velocity tangentially are stick candidates, the others slide;
6. the step size: grown by 1.5 up to ``maximumTimestep``, limited so that no approaching contact
   penetrates by more than ``maximumPenetration`` and a closed contact lifting off lands where it
   left, at least ``minimumTimestep``, and cut to land on history sample times;
7. Heun's method (explicit trapezoidal rule) over the step, with the contact set of step 5 and
   the LCP solved again at the end point; lost work is integrated by the trapezoidal rule.

Contributions of a step (lost work, impulses, energy counters) stay pending until the next
step accepts it; ``TryToSolveByGoingBack`` can then return to the start of the previous step.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.contact_problem import (
    accelerations,
    closed,
    held_directions,
    contact_forces,
    contact_laws,
    dynamics,
    free_accelerations,
    free_dynamics,
    impacts,
    resting_contacts,
    rest_velocity,
    row_dot,
)
from mbds.kernel.detection import (
    bounding_boxes,
    contact_geometry,
    contact_points,
    detect_contacts,
    tracked_depth,
    world_points,
)
from mbds.kernel.events import log_event
from mbds.kernel.function_table import function_at
from mbds.kernel.heat import cool
from mbds.kernel.impact import impact
from mbds.kernel.jit import jit
from mbds.kernel.kinematics import body_frames, body_states, contact_kinematics
from mbds.kernel.layout import (
    CAPACITY,
    DRIVE_WORK,
    DT,
    DT_MAX,
    DT_MIN,
    EVENT_OVER_PENETRATION,
    EVENT_SINGULAR_MASS,
    EVENTS_FULL,
    GO_BACK,
    HISTORY_FULL,
    IMPACTS,
    LAST_PENETRATION,
    LAST_SLOT,
    LCP_FAILURES,
    LEXICO,
    LEXICO_HIGH,
    LEXICO_LOW,
    LOST,
    MAX_PEN,
    MODEL_FUNCTIONS,
    MAX_PENETRATION,
    NEXT_SAMPLE,
    NOT_FINITE,
    OVER_PENETRATIONS,
    PASSES_DONE,
    PASSES_PER_CALL,
    REACHED,
    REJECTED,
    SAMPLE_AT_COLLISION,
    SAMPLE_EACH_STEP,
    SAMPLE_EVERY,
    STEPS,
    T,
)
from mbds.kernel.motion import body_motion, detection_margins, reach_limit
from mbds.kernel.random import uniform
from mbds.kernel.rollback import begin_step, forget_steps, go_back, kept_slot, record
from mbds.kernel.sampling import sample
from mbds.kernel.settling import settle_positions

_MASS_MATRIX, _H_VECTOR, _DEPENDENT_STATE, _DEPENDENT_JACOBIAN, _MECHANICAL_ENERGY, _CONTACT_LAW = (
    function_at(signature) for signature in MODEL_FUNCTIONS.values())


@jit(refcount=False, entry=True)
def advance(functions, model, settings, until, clock, q, u, rng, point_loss, point_interval, history, events, ws):
    """Integrate until time ``until`` (s) or until a buffer fills; return a status.

    functions: the table of the model's functions (rows: MODEL_FUNCTIONS), so that the stepper,
    compiled once, serves every model;
    model: ModelArrays; settings (SETTINGS,); clock (CLOCK,) time, step and counters; q, u (n,);
    rng: uint64 (1,); point_loss (P,) lost work accumulated per shape point (J); point_interval
    (P, POINT_COLUMNS) impulses (N s), lost work (J) and contact angle (rad) per point since the
    last history sample; history: History; events: Events; ws: Workspace (all in
    mbds.kernel.layout).
    """
    mass_matrix, h_vector = _MASS_MATRIX(functions, 0), _H_VECTOR(functions, 1)
    dependent_state, dependent_jacobian = _DEPENDENT_STATE(functions, 2), _DEPENDENT_JACOBIAN(functions, 3)
    mechanical_energy, contact_law = _MECHANICAL_ENERGY(functions, 4), _CONTACT_LAW(functions, 5)
    bodies, contacts, rows, dyn, pb, forces, back = ws
    a1, a2 = forces.a1, forces.a2
    n = q.shape[0]
    heated = model.pair_heated.any()
    body_frames(model.binding, model.binding_index, model.start_pose, model.carrier, bodies.pose, bodies.vel,
                bodies.B, bodies.bhat, bodies.beta, bodies.trig)
    passes = 0.0
    while True:
        passes += 1.0
        if passes > settings[PASSES_PER_CALL]:  # the loop resumes here on the next call, unchanged
            return PASSES_DONE
        t = clock[T]
        for k in range(n):
            if not (np.isfinite(q[k]) and np.isfinite(u[k])):
                return NOT_FINITE
        # --- 1, 2: kinematics and contacts at the current state
        _body_kinematics(dependent_state, dependent_jacobian, model, q, u, t, bodies)
        world_points(bodies.pose, bodies.trig, model.points, model.point_start, bodies.world)
        # (before detection replaces them: the margins are still those of their detection)
        if np.isnan(back.pending[0]):
            tracked = tracked_depth(bodies.world, model.point_start, model.point_reflex, model.skin, bodies.margin,
                                    contacts, back.tracked[0])
        else:  # the rerun of a pass that ran out of contact capacity, whose detection replaced them
            tracked = back.pending[0]
            back.pending[0] = np.nan
        if not free_dynamics(mass_matrix, h_vector, q, u, t, model.p, dyn):
            log_event(events, t, EVENT_SINGULAR_MASS, 0.0, 0.0)
            return NOT_FINITE
        body_motion(model.carrier, bodies.B, bodies.bhat, bodies.beta, u, a2, dyn.minv_h, True, bodies.motion)
        bounding_boxes(bodies.world, model.point_start, bodies.boxes)
        detection_margins(model, bodies.motion, settings, bodies.margin)
        nc = detect_contacts(bodies.world, model.point_start, model.point_reflex, model.concave, bodies.boxes,
                             model.pair_bodies, model.pair_resisting, model.skin, bodies.margin, settings[MAX_PEN],
                             contacts.pair, contacts.vb, contacts.vertex, contacts.eb, contacts.edge, contacts.xi,
                             contacts.gap, contacts.normal, contacts.point, contacts.work, contacts.frames)
        if nc < 0:  # the caller moves everything into a larger workspace and calls again
            back.pending[0] = tracked
            return CAPACITY
        # --- 3: accept the step that led here, or go back to its start with half the step
        penetration = tracked
        for i in range(nc):
            penetration = max(penetration, -contacts.gap[i])
        if penetration > max(settings[MAX_PEN], clock[LAST_PENETRATION]) and back.record_count[LAST_SLOT] >= 0:
            taken = t - back.clock[LAST_SLOT, T]
            if taken > settings[DT_MIN] * 1.000001:  # the start of the last step
                go_back(LAST_SLOT, q, u, clock, model, point_loss, point_interval, back)
                clock[DT] = max(0.5 * clock[DT], settings[DT_MIN])
                back.cap[0] = 0.5 * taken
                back.tracked[0] = 0
                clock[REJECTED] += 1.0
                continue
            log_event(events, t, EVENT_OVER_PENETRATION, penetration, settings[MAX_PEN])
            clock[OVER_PENETRATIONS] += 1.0
        clock[LAST_PENETRATION] = penetration
        clock[MAX_PENETRATION] = max(clock[MAX_PENETRATION], penetration)
        # --- the state at t is final: history, end, buffers
        due = t >= clock[NEXT_SAMPLE] - 1e-12 * max(1.0, abs(t)) or settings[SAMPLE_EACH_STEP] > 0.0
        if due and t > back.last_sample[0]:  # (after going back, the start time is not sampled twice)
            if history.count[0] >= history.time.shape[0]:
                return HISTORY_FULL
            if n > 0 and np.isnan(a2[0]):  # no step has computed the accelerations at t yet
                _contact_rows(nc, contacts, model, bodies, rows)
                contact_laws(contact_law, nc, contacts, model, point_interval, rows, events, t)
                held_directions(nc, contacts, rows, dyn, settings, pb.active)
                contact_forces(nc, contacts, rows, dyn, pb, settings, settings[LEXICO], forces.lam_n,
                               forces.lam_t, a2, events, t)
            sample(mechanical_energy, q, u, a2, t, model.p, clock, point_interval, model.watch_start,
                   model.watch_points, history)
            back.last_sample[0] = t
            forget_steps(back)  # no going back past a sample
            # the next sample time as a multiple of the interval (no drift from repeated sums)
            clock[NEXT_SAMPLE] = (np.floor(t / settings[SAMPLE_EVERY] + 1e-9) + 1.0) * settings[SAMPLE_EVERY]
        if t >= until - 1e-12 * max(1.0, abs(until)):
            return REACHED
        if events.count[0] + 8 > events.data.shape[0]:
            return EVENTS_FULL
        begin_step(q, u, clock, point_interval, heated, back)
        if settings[LEXICO_HIGH] > 0.0:
            tol_lex = uniform(rng, settings[LEXICO_LOW], settings[LEXICO_HIGH])
        else:
            tol_lex = settings[LEXICO]
        _contact_rows(nc, contacts, model, bodies, rows)
        contact_laws(contact_law, nc, contacts, model, point_interval, rows, events, t)
        held_directions(nc, contacts, rows, dyn, settings, pb.active)
        # --- 4: impact (see contact_problem.impacts)
        impacting = False
        counted = False
        rest = rest_velocity(settings)
        for i in range(nc):
            if impacts(contacts.gap[i], rows.gd_n[i], settings):
                impacting = True
                counted = counted or rows.gd_n[i] < -rest
        if counted:
            clock[IMPACTS] += 1.0
        solved = True
        if impacting:
            solved = impact(nc, contacts, rows, dyn, pb, forces, u, settings, tol_lex, clock, model,
                            point_loss, point_interval, back, events, t, False, False)
            _after_impulses(dependent_state, dependent_jacobian, mass_matrix, h_vector, contact_law, model, q, u, t,
                            nc, point_interval, events, bodies, contacts, rows, dyn)
        # --- 5: forces between impacts
        # (the stepper calls the LCP set-up only where there are contacts: passing it the bundles costs
        # more than a step in flight)
        na, forces_ok = _resting_forces(nc, contacts, rows, dyn, pb, forces, settings, tol_lex, events, t)
        solved = solved and forces_ok
        if not solved:
            clock[LCP_FAILURES] += 1.0
            # TryToSolveByGoingBack: two steps back (slot LAST_SLOT holds this step's start), or one
            # where only one step is kept
            slot = kept_slot(back, LAST_SLOT - 2, LAST_SLOT - 1, settings[DT_MIN]) if settings[GO_BACK] > 0.0 else -1
            if slot >= 0:
                go_back(slot, q, u, clock, model, point_loss, point_interval, back)
                clock[DT] = max(0.5 * clock[DT], settings[DT_MIN])
                back.tracked[0] = 0
                continue
            # no contact forces continue the motion: an impact without collision that stops the present rates,
            # and where forces still fail after it, one that stops the approach of a maximum step
            for present in (True, False):
                if forces_ok:
                    break
                impact(nc, contacts, rows, dyn, pb, forces, u, settings, tol_lex, clock, model, point_loss,
                       point_interval, back, events, t, True, present)
                _after_impulses(dependent_state, dependent_jacobian, mass_matrix, h_vector, contact_law, model, q, u,
                                t, nc, point_interval, events, bodies, contacts, rows, dyn)
                impacting = True
                na, forces_ok = _resting_forces(nc, contacts, rows, dyn, pb, forces, settings, tol_lex, events, t)
        # --- 6: step size
        # (the speeds at u are those of step 2 unless an impact changed u)
        body_motion(model.carrier, bodies.B, bodies.bhat, bodies.beta, u, a1, a1, impacting, bodies.motion)
        dt = _step_size(model, nc, na, contacts.gap, bodies, rows, pb, a1, settings, clock, back)
        clock[DT] = dt
        t2 = t + dt
        target = min(clock[NEXT_SAMPLE], until)
        if t2 >= target:  # land exactly on the sample time or the end
            dt = target - t
            t2 = target
        # --- 7: Heun step with the contact set of step 5
        _heun(mass_matrix, h_vector, dependent_state, dependent_jacobian, mechanical_energy, model, settings, tol_lex,
              clock, q, u, t2, dt, na, point_loss, point_interval, events, bodies, contacts, rows, dyn, pb, forces,
              back)
        back.tracked[0] = nc
        if heated:
            cool(model.point_heat, point_interval, dt)
        clock[STEPS] += 1.0
        if counted and settings[SAMPLE_AT_COLLISION] > 0.0:
            clock[NEXT_SAMPLE] = min(clock[NEXT_SAMPLE], t2)


@jit(refcount=False)
def _step_size(model, nc, na, gap, bodies, rows, pb, a1, settings, clock, back):
    """The next step (s): grown by 1.5 up to maximumTimestep; after a rejected step at most half
    of it; no longer than the reach limit of every pair (no vertex beyond a detection margin can
    penetrate); limited so that no approaching open contact goes deeper than half
    maximumPenetration by its own motion, no closed contact lifting off faster than the rest
    velocity flies on below the gap it left, and no sliding contact passes zero sliding speed;
    at least minimumTimestep."""
    dt = min(1.5 * clock[DT], settings[DT_MAX], back.cap[0])
    back.cap[0] = np.inf
    dt = reach_limit(model, bodies.motion, settings, bodies.margin, dt)
    rest = rest_velocity(settings)
    for i in range(nc):
        touching = closed(gap[i], settings)
        if touching and rows.gd_n[i] <= rest:  # closed and not lifting off: no limit here
            continue
        # open: reach at most half maxPen; closed and lifting off: its flight ends where it began, not deeper
        reach = 0.0 if touching else gap[i] + 0.5 * settings[MAX_PEN]
        accel = row_dot(rows.WN, i, a1) + rows.wbar_n[i]
        dt = min(dt, _time_to_reach(reach, rows.gd_n[i], accel))
    for a in range(na):  # a sliding contact stops at the end of the step, not beyond
        i = pb.active[a]
        if not pb.stick[i]:
            accel = row_dot(rows.WT, i, a1) + rows.wbar_t[i]
            if rows.gd_t[i] * accel < 0.0:
                dt = min(dt, -rows.gd_t[i] / accel)
    return max(dt, settings[DT_MIN])


@jit(inline="always")
def _heun(mass_matrix, h_vector, dependent_state, dependent_jacobian, mechanical_energy, model, settings, tol_lex,
          clock, q, u, t2, dt, na, point_loss, point_interval, events, bodies, contacts, rows, dyn, pb, forces, back):
    """Heun's method (explicit trapezoidal rule) from clock[T] to t2 = clock[T] + dt with the
    contact set of the start; contact forces are solved again at the predicted end point and
    the lost work of each contact is integrated by the trapezoidal rule. At the end point only
    the contacts of that set are followed (their geometry, rows and M^-1 W); with none, only
    M and h are evaluated there. The contacts of the set then settle towards zero gap by a shift
    of the positions alone (mbds.kernel.settling), whose change of the mechanical energy is
    counted as lost work."""
    n = q.shape[0]
    active = pb.active
    lam_n, lam_t, lam_n1, lam_t1 = forces.lam_n, forces.lam_t, forces.lam_n1, forces.lam_t1
    gam_n, gam_t, a1, a2 = forces.gam_n, forces.gam_t, forces.a1, forces.a2
    q_star, u_star = forces.q_star, forces.u_star
    gd_n, gd_t, what_n, what_t = rows.gd_n, rows.gd_t, rows.what_n, rows.what_t
    power = 0.0
    drive = 0.0
    for a in range(na):
        i = active[a]
        power += lam_n1[i] * gd_n[i] + lam_t1[i] * gd_t[i]
        drive -= lam_n1[i] * what_n[i] + lam_t1[i] * what_t[i]
        gam_n[i] = gd_n[i]
        gam_t[i] = gd_t[i]
        forces.gap0[i] = contacts.gap[i]
    for k in range(n):
        q_star[k] = q[k] + dt * u[k]
        u_star[k] = u[k] + dt * a1[k]
    if na > 0:
        _body_kinematics(dependent_state, dependent_jacobian, model, q_star, u_star, t2, bodies)
        contact_points(bodies.pose, bodies.trig, model.points, contacts.vb, contacts.vertex, contacts.eb,
                       contacts.edge, active, na, bodies.world)
        contact_geometry(bodies.world, contacts.vertex, contacts.edge, active, na, contacts.xi, contacts.gap,
                         contacts.normal, contacts.point)
        _contact_kinematics(active, na, contacts, model, bodies, rows)
    end_ok = dynamics(mass_matrix, h_vector, q_star, u_star, t2, model.p, rows, dyn, active, na)
    if na > 0:
        end_ok = end_ok and accelerations(na, contacts, rows, dyn, pb, settings, tol_lex, lam_n, lam_t, a2, events, t2)
    else:
        end_ok = end_ok and free_accelerations(dyn.minv_h, a2)
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
        record(contacts, i, 0.5 * dt * (lam_n1[i] + lam_n[i]), 0.5 * dt * (lam_t1[i] + lam_t[i]),
               -0.5 * dt * (lam_n1[i] * gam_n[i] + lam_t1[i] * gam_t[i] + lam_n[i] * gd_n[i] + lam_t[i] * gd_t[i]),
               model, point_loss, point_interval, back)
    for k in range(n):
        q[k] += 0.5 * dt * (u[k] + u_star[k])
        u[k] += 0.5 * dt * (a1[k] + a2[k])
    clock[LOST] -= 0.5 * dt * power
    clock[DRIVE_WORK] += 0.5 * dt * drive
    if na > 0:  # the contacts at rest settle towards zero gap: the positions move, the velocities do not
        before = mechanical_energy(q, u, t2, model.p)
        settle_positions(active, na, forces.gap0, rows.WN, dyn.YN, settings, dt, q, pb.fwork, pb.iwork)
        clock[LOST] += before - mechanical_energy(q, u, t2, model.p)
    clock[T] = t2


@jit(inline="always")
def _after_impulses(dependent_state, dependent_jacobian, mass_matrix, h_vector, contact_law, model, q, u, t, nc,
                    point_interval, events, bodies, contacts, rows, dyn):
    """Everything that depends on the velocities, again after impulses changed u (the positions
    did not change: M, the force directions and M^-1 W stay)."""
    _body_kinematics(dependent_state, dependent_jacobian, model, q, u, t, bodies)
    _contact_rows(nc, contacts, model, bodies, rows)
    contact_laws(contact_law, nc, contacts, model, point_interval, rows, events, t)
    free_dynamics(mass_matrix, h_vector, q, u, t, model.p, dyn)


@jit(inline="always")
def _resting_forces(nc, contacts, rows, dyn, pb, forces, settings, tol_lex, events, t):
    """The contacts at rest, their forces (forces.lam_n1, lam_t1) and the accelerations
    forces.a1 at the start of the step: (their number, solved)."""
    na = resting_contacts(nc, contacts.gap, rows.gd_n, rows.gd_t, pb.active, pb.stick, pb.sign, pb.jammed, settings)
    if na > 0:
        return na, accelerations(na, contacts, rows, dyn, pb, settings, tol_lex, forces.lam_n1, forces.lam_t1,
                                 forces.a1, events, t)
    return na, free_accelerations(dyn.minv_h, forces.a1)


@jit(inline="always")
def _body_kinematics(dependent_state, dependent_jacobian, model, q, u, t, bodies):
    """Dependent coordinates and every body's pose, velocity and Jacobian terms at (q, u, t)."""
    if bodies.dpos.shape[0] > 0:
        dependent_state(q, u, bodies.zero, t, model.p, bodies.dpos, bodies.dvel, bodies.dacc)
        dependent_jacobian(q, u, t, model.p, bodies.djac, bodies.dsc)
    body_states(model.binding, model.binding_index, model.carrier, model.offset, q, u,
                bodies.dpos, bodies.dvel, bodies.djac, bodies.dsc, bodies.pose, bodies.vel, bodies.B, bodies.bhat,
                bodies.beta, bodies.trig)


@jit(inline="always")
def _contact_rows(nc, contacts, model, bodies, rows):
    """Force directions, velocity terms and relative velocities of the nc contacts."""
    _contact_kinematics(contacts.order, nc, contacts, model, bodies, rows)


@jit(inline="always")
def _contact_kinematics(index, count, contacts, model, bodies, rows):
    """Force directions, velocity terms and relative velocities of the contacts index[:count]."""
    contact_kinematics(index, count, contacts.vb, contacts.eb, contacts.normal, contacts.point, model.carrier,
                       bodies.pose, bodies.vel, bodies.B, bodies.bhat, bodies.beta, rows.WN, rows.WT, rows.what_n,
                       rows.what_t, rows.wbar_n, rows.wbar_t, rows.gd_n, rows.gd_t)


@jit(refcount=False)
def _time_to_reach(distance, rate, accel):
    """The first time (s) at which a gap that is ``distance`` (m) above a target, changing at
    ``rate`` (m/s) with ``accel`` (m/s^2), reaches it; inf if it never does."""
    if accel == 0.0:
        return distance / -rate if rate < 0.0 else np.inf
    disc = rate * rate - 2.0 * accel * distance
    if disc < 0.0:
        return np.inf
    root = np.sqrt(disc)
    if accel < 0.0:  # one positive root; each form avoids the cancellation of -rate + root
        return (rate + root) / -accel if rate >= 0.0 else 2.0 * distance / (root - rate)
    first = (-rate - root) / accel
    if first > 0.0:
        return first
    second = (-rate + root) / accel
    return second if second > 0.0 else np.inf
