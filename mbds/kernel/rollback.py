"""Per-point accumulators of a step's contacts, and going back to the start of a step.

Contributions of a step (impulses, lost work) go to the shape points at once and are also
kept as records, so that going back (``TryToSolveByGoingBack``, two steps, or a step rejected for
penetration, one) can take them out again. Slot LAST_SLOT holds the last step, the slots below it
the steps before.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit
from mbds.kernel.layout import (
    ANGLE,
    DT,
    HEATING,
    IMP_N,
    IMP_T,
    IMP_X,
    IMP_Y,
    IMPACTS,
    LAST_SLOT,
    LCP_FAILURES,
    MAX_PENETRATION,
    OVER_PENETRATIONS,
    R_ANGLE,
    R_IMP_N,
    R_IMP_T,
    R_IMP_X,
    R_IMP_Y,
    R_LOSS,
    R_XI,
    REJECTED,
    ROLLBACK_SLOTS,
    STEPS,
    TEMP,
    WORK,
)


@jit(inline="always")
def record(contacts, i, imp_n, imp_t, loss, model, point_loss, point_interval, back):
    """Add contact i's impulses (N s) and lost work (J) of this step to its points, and keep
    the record so that going back can take it out again.

    The vertex point gets all of it; the edge's two points share it as (1 - xi, xi) (xi clipped
    to [0, 1]: a vertex beyond an end of its edge loads that end only), with the impulse
    reversed (the reaction). Impulses are normal-tangential (n out of the edge body,
    t = (-n_y, n_x)) and x-y, as acting on the watched point's body. Points with a heat model
    (model.point_heat) warm by their share of the loss times their HEATING (deg C per J).
    """
    point_start, point_heat = model.point_start, model.point_heat
    vertex = contacts.vertex[i]
    edge = contacts.edge[i]
    edge_end = edge_end_point(edge, contacts.eb[i], point_start)
    xi = min(max(contacts.xi[i], 0.0), 1.0)
    nx = contacts.normal[i, 0]
    ny = contacts.normal[i, 1]
    imp_x = imp_n * nx - imp_t * ny
    imp_y = imp_n * ny + imp_t * nx
    angle = np.arctan2(ny, nx)
    _add_contact(vertex, edge, edge_end, xi, imp_n, imp_t, imp_x, imp_y, loss, angle, 1.0, point_heat, point_loss,
                 point_interval)
    records_int, records_float, record_count = back.records_int, back.records_float, back.record_count
    last = LAST_SLOT
    k = max(record_count[last], 0)
    if k < records_int.shape[1]:
        records_int[last, k, 0] = vertex
        records_int[last, k, 1] = edge
        records_int[last, k, 2] = edge_end
        records_float[last, k, R_XI] = xi
        records_float[last, k, R_IMP_N] = imp_n
        records_float[last, k, R_IMP_T] = imp_t
        records_float[last, k, R_IMP_X] = imp_x
        records_float[last, k, R_IMP_Y] = imp_y
        records_float[last, k, R_LOSS] = loss
        records_float[last, k, R_ANGLE] = angle
        record_count[last] = k + 1
    else:  # no room to keep it: this step becomes final
        forget_steps(back)


@jit(inline="always")
def edge_end_point(edge, body, point_start):
    """The point an edge ends at: the next point, or the body's first for its closing edge."""
    end = edge + 1
    return point_start[body] if end == point_start[body + 1] - 1 else end


@jit(inline="always")
def _take_out(records_int, records_float, slot, k, point_heat, point_loss, point_interval):
    """Take record k of ``slot`` out of the per-point accumulators."""
    r = records_float
    _add_contact(records_int[slot, k, 0], records_int[slot, k, 1], records_int[slot, k, 2], r[slot, k, R_XI],
                 r[slot, k, R_IMP_N], r[slot, k, R_IMP_T], r[slot, k, R_IMP_X], r[slot, k, R_IMP_Y],
                 r[slot, k, R_LOSS], r[slot, k, R_ANGLE], -1.0, point_heat, point_loss, point_interval)


@jit(inline="always")
def _add_contact(vertex, edge, edge_end, xi, imp_n, imp_t, imp_x, imp_y, loss, angle, scale, point_heat, point_loss,
                 point_interval):
    """Add (scale 1) or take out (scale -1) a contact's share at its vertex and edge points."""
    _add_point(vertex, scale, 1.0, imp_n, imp_t, imp_x, imp_y, loss, angle, point_heat, point_loss, point_interval)
    _add_point(edge, (1.0 - xi) * scale, -1.0, imp_n, imp_t, imp_x, imp_y, loss, angle, point_heat, point_loss,
               point_interval)
    _add_point(edge_end, xi * scale, -1.0, imp_n, imp_t, imp_x, imp_y, loss, angle, point_heat, point_loss,
               point_interval)


@jit(inline="always")
def _add_point(point, share, direction, imp_n, imp_t, imp_x, imp_y, loss, angle, point_heat, point_loss,
               point_interval):
    point_loss[point] += share * loss
    if point_heat[point, HEATING] > 0.0:
        point_interval[point, TEMP] += share * loss * point_heat[point, HEATING]
    point_interval[point, IMP_N] += share * imp_n
    point_interval[point, IMP_T] += share * direction * imp_t
    point_interval[point, IMP_X] += share * direction * imp_x
    point_interval[point, IMP_Y] += share * direction * imp_y
    point_interval[point, WORK] += share * loss
    if share > 0.0:
        point_interval[point, ANGLE] = angle if direction > 0.0 else angle + np.pi


@jit(refcount=False)
def begin_step(q, u, clock, point_interval, heated, back):
    """Keep the start of this step (slot LAST_SLOT), the starts of the steps before it moving one
    slot down (with the point temperatures when ``heated``), for going back."""
    records_int, records_float, record_count = back.records_int, back.records_float, back.record_count
    for s in range(LAST_SLOT):
        count = record_count[s + 1]
        if count >= 0:
            for k in range(count):
                for j in range(records_int.shape[2]):
                    records_int[s, k, j] = records_int[s + 1, k, j]
                for j in range(records_float.shape[2]):
                    records_float[s, k, j] = records_float[s + 1, k, j]
            for k in range(q.shape[0]):
                back.q[s, k] = back.q[s + 1, k]
                back.u[s, k] = back.u[s + 1, k]
            for k in range(clock.shape[0]):
                back.clock[s, k] = back.clock[s + 1, k]
            if heated:
                for k in range(point_interval.shape[0]):
                    back.temperature[s, k] = back.temperature[s + 1, k]
        record_count[s] = count
    for k in range(q.shape[0]):
        back.q[LAST_SLOT, k] = q[k]
        back.u[LAST_SLOT, k] = u[k]
    for k in range(clock.shape[0]):
        back.clock[LAST_SLOT, k] = clock[k]
    if heated:
        for k in range(point_interval.shape[0]):
            back.temperature[LAST_SLOT, k] = point_interval[k, TEMP]
    record_count[LAST_SLOT] = 0


@jit(inline="always")
def forget_steps(back):
    """No step kept can be gone back to (after a history sample, or a step whose records did not
    fit)."""
    for s in range(ROLLBACK_SLOTS):
        back.record_count[s] = -1


@jit(refcount=False)
def go_back(slot, q, u, clock, model, point_loss, point_interval, back):
    """Return to the start of the step kept in ``slot`` (LAST_SLOT: the last step, each slot below
    one step earlier), taking the records of the steps undone out of the accumulators and
    restoring the point temperatures; counters keep counting."""
    record_count = back.record_count
    for s in range(LAST_SLOT, slot - 1, -1):
        for k in range(max(record_count[s], 0)):
            _take_out(back.records_int, back.records_float, s, k, model.point_heat, point_loss, point_interval)
    if model.pair_heated.any():
        for k in range(point_interval.shape[0]):
            point_interval[k, TEMP] = back.temperature[slot, k]
    kept = (clock[STEPS], clock[IMPACTS], clock[REJECTED], clock[LCP_FAILURES], clock[OVER_PENETRATIONS],
            clock[MAX_PENETRATION])
    for k in range(q.shape[0]):
        q[k] = back.q[slot, k]
        u[k] = back.u[slot, k]
    for k in range(clock.shape[0]):
        clock[k] = back.clock[slot, k]
    (clock[STEPS], clock[IMPACTS], clock[REJECTED], clock[LCP_FAILURES], clock[OVER_PENETRATIONS],
     clock[MAX_PENETRATION]) = kept
    forget_steps(back)


@jit(inline="always")
def kept_slot(back, first, last, dt_min):
    """The earliest slot from ``first`` to ``last`` that can be gone back to, or -1 when none
    can or when its step was already minimumTimestep ``dt_min`` (s) long (going back would
    change nothing)."""
    for slot in range(first, last + 1):
        if back.record_count[slot] >= 0:
            return slot if back.clock[slot, DT] > dt_min * 1.000001 else -1
    return -1
