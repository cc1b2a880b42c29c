"""The linear complementarity problems of contacts: between impacts and at impacts.

Contacts are rows of WN, WT (force directions, (cap, n)); ``Y = M^-1 W^T`` is kept per row
(YN, YT). Of the ``na`` contacts in ``active``, those flagged in ``stick`` (``nh`` of them)
are stick candidates; the others slide with ``sign`` = sgn(gT'). The unknowns of one LCP are
x = (lambda_N [na], lambda_0R [nh], gT''^- [nh]) with y = (gN'' [na], gT''^+ [nh], lambda_0L [nh]):

    A = [ WN^T M^-1 (N_G - W_H mu_H)   WN^T M^-1 W_H   0 ]
        [ W_H^T M^-1 (N_G - W_H mu_H)  W_H^T M^-1 W_H  I ]
        [ 2 mu_H                        -I              0 ]

where N_G column j is w_N,j - mu_j sign_j w_T,j (sliding) or w_N,j (stick candidate), and
lambda_T = lambda_0R - mu lambda_N at stick candidates, -mu sign lambda_N at sliding contacts.
At impacts every contact is a stick candidate and the same matrix (with impulses in place of
forces, velocities in place of accelerations) serves the compression and expansion phases.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.events import log_event
from mbds.kernel.heat import contact_temperature
from mbds.kernel.jit import jit
from mbds.kernel.layout import (
    DT_MAX,
    EVENT_BAD_LAW,
    EVENT_LCP_RAY,
    MAX_PEN,
    MAX_PIVOTS,
    PIVOT_MAX,
    PIVOT_MIN,
    ZERO_VELOCITY,
)
from mbds.kernel.active_set import recall_states, remember_states, solve_states
from mbds.kernel.components import split_components
from mbds.kernel.lcp import SOLVED, lemke
from mbds.kernel.one_contact import solve_one_contact
from mbds.kernel.redundancy import project_targets
from mbds.kernel.linalg import cholesky, cholesky_solve, cholesky_solve_row, envelope
from mbds.kernel.rollback import edge_end_point

REST_FRACTION = 0.01
"""A closed contact whose normal speed is below the rest velocity REST_FRACTION * maxPen /
dt_max is at rest: within a maximum step it moves by at most 1 % of the allowed penetration. A
touching contact approaching slower than that (round-off, or the drift of a pivoting contact)
still gets its velocity from the impact laws, but this does not count as an impact; one not yet
touching settles onto its surface (:func:`impacts`)."""
STICK_FRACTION = 1.0
"""A contact at rest whose sliding speed is below STICK_FRACTION times the rest velocity is a
stick candidate; a faster one slides, and the step ends where its sliding speed reaches zero.
Where a stick candidate sticks, its remaining sliding speed decays with the time constant
REST_RELAXATION maximum steps (see :func:`accelerations`)."""
REST_RELAXATION = 10.0
"""Time constant (in maximum steps) of the decay of the speeds left at a contact at rest: the
normal speed below the rest velocity (approaching or separating), and a sticking contact's
sliding speed below the stick threshold."""
CLOSED_FRACTION = 0.01
"""A contact whose gap is below CLOSED_FRACTION * maxPen is closed (touching)."""
HELD_FRACTION = 0.25
"""A contact at rest stays held (in the contact-force LCP) up to a gap of HELD_FRACTION * maxPen,
above the closed band: the decay of a separating speed below the rest velocity lifts it by at
most 0.1 maxPen (see :func:`accelerations`), so it does not open and fall back onto its surface."""
STATE_ROUNDS = 4
"""Rounds of state changes tried from the remembered contact states before Lemke's method
takes over (see :func:`solve` and mbds.kernel.active_set)."""
TRUSTED_SPREAD = 0.01
"""A contact-force solution is trusted while its accelerations do not come from terms that
cancel to below this fraction of the LCP's data, at the relative precision tol_lex of the
solution check (:func:`trusted`). Forces far out of proportion with the data lie along a
near-null direction of the Delassus matrix: two stick candidates of one body pair whose friction
cones overlap (corners resting on each other) can carry any internal force between them, and
with a lever of round-off size it spins the bodies up. Such an LCP is solved once more with the
stick compliance (:func:`_compliant_lemke`), which bounds that internal force."""
COMPRESSION, EXPANSION, FORCES, SOLVING = range(4)
"""Families of LCPs whose contact states (mbds.kernel.active_set) are remembered apart: the
compression and the expansion phases of impacts and the contact forces; SOLVING is the memory
slot where the states of a phase's groups are collected until the phase ends
(:func:`keep_states`)."""
STICK_COMPLIANCE = 1e-6
"""Where Lemke's method fails on a contact LCP with stick rows (contact forces or an impact's
phase), they get this fraction of their largest diagonal entry as compliance and the LCP is
solved once more (see :func:`solve`)."""


@jit(inline="always")
def closed(gap, settings):
    """Whether a contact with ``gap`` (m) is closed (touching)."""
    return gap <= CLOSED_FRACTION * settings[MAX_PEN]


@jit(inline="always")
def held(gap, settings):
    """Whether a contact at rest with ``gap`` (m) is held (see HELD_FRACTION)."""
    return gap <= HELD_FRACTION * settings[MAX_PEN]


@jit(inline="always")
def rest_velocity(settings):
    """The rest velocity REST_FRACTION * maxPen / dt_max (m/s)."""
    return REST_FRACTION * settings[MAX_PEN] / settings[DT_MAX]


@jit(inline="always")
def settling_speed(gap, settings):
    """The speed (m/s) toward zero gap at which a contact at rest settles:
    -gap / (4 REST_RELAXATION dt_max), within half the rest velocity either way. The positions
    move at it (mbds.kernel.settling), not the velocities: the gap decays exponentially, without
    overshoot, and a penetration is pushed out slower than the rest velocity."""
    bound = 0.5 * rest_velocity(settings)
    return min(max(-gap / (4.0 * REST_RELAXATION * settings[DT_MAX]), -bound), bound)


@jit(inline="always")
def impacts(gap, rate, settings):
    """Whether a contact with ``gap`` (m) and normal rate (m/s) starts an impact: closed and
    approaching faster than ZeroVelocityTolerance, or slower but so that it would go beyond
    maximumPenetration within a maximum step (else the step would shrink to minimumTimestep
    and stay there). A contact not yet touching (gap > 0) that approaches slower than the rest
    velocity is settling onto its surface (:func:`settling_speed`): no impact."""
    if not closed(gap, settings) or rate >= 0.0 or gap > 0.0 and rate >= -rest_velocity(settings):
        return False
    return rate < -settings[ZERO_VELOCITY] or gap + rate * settings[DT_MAX] < -settings[MAX_PEN]


@jit(refcount=False)
def inverse_mass_rows(L, profile, rows, index, count, Y):
    """Y[i] = M^-1 rows[i] for the rows i in index[:count] (L: Cholesky factor of M, profile:
    its envelope)."""
    for c in range(count):
        cholesky_solve_row(L, profile, rows, index[c], Y)


@jit(inline="always")
def row_dot(A, i, v):
    """sum_k A[i, k] v[k]."""
    s = 0.0
    for k in range(A.shape[1]):
        s += A[i, k] * v[k]
    return s


@jit(inline="always")
def row_spans(active, na, WN, WT, YN, YT, span):
    """span[a, :2] = (first, last + 1) of the coordinates where row active[a] of WN or WT is
    nonzero (a contact moves the coordinates of its two bodies only), span[a, 2:] the same of
    its rows of YN, YT = M^-1 W (those of the bodies a mass couples to them); (0, 0) for zero
    rows."""
    for a in range(na):
        _nonzero_span(WN, WT, active[a], span, a, 0)
        _nonzero_span(YN, YT, active[a], span, a, 2)


@jit(inline="always")
def _nonzero_span(A, B, c, span, a, at):
    """span[a, at:at + 2] = (first, last + 1) of the columns where row c of A or B is nonzero."""
    n = A.shape[1]
    first = n
    last = -1
    for k in range(n):
        if A[c, k] != 0.0 or B[c, k] != 0.0:
            first = min(first, k)
            last = k
    span[a, at] = min(first, last + 1)
    span[a, at + 1] = last + 1


@jit(inline="always")
def coupled_dot(W, i, Y, j, span, a, b):
    """sum_k W[i, k] Y[j, k] for row i of W (contact a of the LCP) and row j of Y = M^-1 W^T
    (contact b), over the columns where both can be nonzero (:func:`row_spans`): the products
    left out are with exact zeros, so the sum is that over all columns, and 0 for contacts no
    mass couples."""
    s = 0.0
    for k in range(max(span[a, 0], span[b, 2]), min(span[a, 1], span[b, 3])):
        s += W[i, k] * Y[j, k]
    return s


@jit(inline="always")
def build_matrix(active, na, stick, sign, laws, WN, WT, YN, YT, column, hrow, span, A_flat):
    """Fill the matrix A (size m = na + 2 nh, row-major in A_flat[:m * m]) for the contacts
    active[:na]; return nh.

    column: (cap, n) scratch for M^-1 times the effective normal column of each contact (set
    within the nonzero span of its Y rows only); hrow: (cap,) int64 scratch, the index in
    ``active`` of each stick candidate; span: (cap, 4) int64, the nonzero spans of each
    contact's W and Y rows (:func:`row_spans`), filled here.
    """
    row_spans(active, na, WN, WT, YN, YT, span)
    nh = 0
    for a in range(na):
        c = active[a]
        if stick[c]:
            hrow[nh] = a
            nh += 1
        f = laws[c, 0] * (1.0 if stick[c] else sign[c])
        for k in range(span[a, 2], span[a, 3]):
            column[a, k] = YN[c, k] - f * YT[c, k]
    m = na + 2 * nh
    A = A_flat[: m * m].reshape((m, m))
    for i in range(m):
        for j in range(m):
            A[i, j] = 0.0
    for i in range(na):
        ci = active[i]
        for j in range(na):
            A[i, j] = coupled_dot(WN, ci, column, j, span, i, j)
        for h in range(nh):
            A[i, na + h] = coupled_dot(WN, ci, YT, active[hrow[h]], span, i, hrow[h])
    for g in range(nh):
        cg = active[hrow[g]]
        r = na + g
        for j in range(na):
            A[r, j] = coupled_dot(WT, cg, column, j, span, hrow[g], j)
        for h in range(nh):
            A[r, na + h] = coupled_dot(WT, cg, YT, active[hrow[h]], span, hrow[g], hrow[h])
        A[r, na + nh + g] = 1.0
        r2 = na + nh + g
        A[r2, hrow[g]] = 2.0 * laws[cg, 0]
        A[r2, na + g] = -1.0
    return nh


@jit(inline="always")
def tangential_forces(active, na, stick, sign, laws, z, lam_n, lam_t):
    """Normal and tangential forces (or impulses) of the active contacts from an LCP solution z."""
    h = 0
    for a in range(na):
        c = active[a]
        lam_n[c] = z[a]
        if stick[c]:
            lam_t[c] = z[na + h] - laws[c, 0] * z[a]
            h += 1
        else:
            lam_t[c] = -laws[c, 0] * sign[c] * z[a]


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


@jit(inline="always")
def contact_laws(contact_law, nc, contacts, model, point_interval, rows, events, t):
    """Friction and restitution coefficients of every contact at its current sliding speed and
    temperature (see mbds.kernel.heat)."""
    for i in range(nc):
        pair = contacts.pair[i]
        speed = abs(rows.gd_t[i])
        edge = contacts.edge[i]
        temperature = contact_temperature(model, pair, contacts.vertex[i], edge,
                                          edge_end_point(edge, contacts.eb[i], model.point_start), contacts.xi[i],
                                          point_interval)
        if not _contact_law(contact_law, model.pair_law[pair], speed, temperature, model.p, rows.law_out):
            log_event(events, t, EVENT_BAD_LAW, float(pair), speed)
        for j in range(4):
            rows.laws[i, j] = rows.law_out[j]


@jit(inline="always")
def free_dynamics(mass_matrix, h_vector, q, u, t, p, dyn):
    """M, its Cholesky factor, h and M^-1 h (the accelerations without contact forces) at
    (q, u, t); False if M is not positive definite. M is factorised only when it differs
    from the matrix the factor in dyn.L comes from (a constant M is factorised once)."""
    mass_matrix(q, t, p, dyn.M)
    if not _factorised(dyn.M, dyn.M_factored):
        if not cholesky(dyn.M, dyn.L):
            dyn.M_factored[0, 0] = np.nan
            return False
        envelope(dyn.L, dyn.profile)
        for i in range(dyn.M.shape[0]):
            for j in range(dyn.M.shape[1]):
                dyn.M_factored[i, j] = dyn.M[i, j]
    h_vector(q, u, t, p, dyn.hv)
    cholesky_solve(dyn.L, dyn.profile, dyn.hv, dyn.minv_h)
    return True


@jit(inline="always")
def _factorised(M, M_factored):
    """Whether M equals M_factored entry by entry (NaN in M_factored: no factor yet)."""
    for i in range(M.shape[0]):
        for j in range(M.shape[1]):
            if M[i, j] != M_factored[i, j]:
                return False
    return True


@jit(inline="always")
def contact_directions(rows, dyn, index, count):
    """M^-1 W_N and M^-1 W_T of the contacts index[:count] (after :func:`free_dynamics`); without
    contacts no call (its arguments cost more to pass than a step in flight spends elsewhere)."""
    if count > 0:
        inverse_mass_rows(dyn.L, dyn.profile, rows.WN, index, count, dyn.YN)
        inverse_mass_rows(dyn.L, dyn.profile, rows.WT, index, count, dyn.YT)


@jit(inline="always")
def held_directions(nc, contacts, rows, dyn, settings, index):
    """:func:`contact_directions` of the held contacts among the nc detected (the only ones
    the impact and contact-force LCPs take); index: scratch for their list."""
    count = 0
    for i in range(nc):
        if held(contacts.gap[i], settings):
            index[count] = i
            count += 1
    contact_directions(rows, dyn, index, count)


@jit(inline="always")
def dynamics(mass_matrix, h_vector, q, u, t, p, rows, dyn, index, count):
    """:func:`free_dynamics` and :func:`contact_directions` of the contacts index[:count] at
    (q, u, t); False if M is not positive definite."""
    if not free_dynamics(mass_matrix, h_vector, q, u, t, p, dyn):
        return False
    contact_directions(rows, dyn, index, count)
    return True


@jit(inline="always")
def solve(m, at, active, na, nh, family, kept, contacts, pb, settings, tol_lex, events, t):
    """Solve the LCP of size m = na + 2 nh over the contacts active[:na] (one group of
    mbds.kernel.components) held in pb.A_flat[at:] and pb.bvec; log failures; return True
    when solved (the solution in pb.z, pb.w).

    The contact states remembered from the last LCP of the same family (contacts matched by
    vertex and edge) are tried first (mbds.kernel.active_set, at most STATE_ROUNDS rounds of state
    changes), except for a contact-force LCP (FORCES) of a single contact: it is solved in closed
    form where its solution is provably unique (mbds.kernel.one_contact), so that Lemke's method
    could find no other. A point that does not pass Lemke's solution check is discarded and the
    problem is solved by lexicographic Lemke. The states of the solution are collected in memory
    slot SOLVING from row ``kept`` on, for :func:`keep_states`. Where Lemke's end point of an LCP
    with stick rows (any family) fails the solution check, the LCP is solved once more with a
    compliance on the stick rows (:func:`_compliant_lemke`): two stick candidates whose
    tangential rows coincide (a polygon resting flat on the floor) make the stick block singular
    to round-off. So is a contact-force solution that is not trusted (:func:`trusted`). Where
    the end point still fails, or a contact-force solution is still not trusted (normal rows
    that cancel as well), the normal rows get a compliance too (:func:`_normal_compliant_lemke`)."""
    if m == 0:
        return True
    A = pb.A_flat[at : at + m * m].reshape((m, m))
    q, z, w = pb.bvec[:m], pb.z[:m], pb.w[:m]
    solved = False
    if (family != FORCES or na > 1) and _negative(q):  # (else z = 0: Lemke answers without a pivot)
        recall_states(active, na, contacts.vertex, contacts.edge, pb.memory[family], pb.memory_count[family], q,
                      pb.state)
        solved = solve_states(A, q, z, w, na, nh, pb.hrow, pb.state, STATE_ROUNDS, settings[PIVOT_MAX], tol_lex,
                              int(settings[MAX_PIVOTS]), pb.fwork, pb.iwork)
    elif na == 1:
        solved = solve_one_contact(A, q, z, w, nh, tol_lex, pb.iwork, pb.fwork)
    status = SOLVED
    pivots = 0
    if not solved:
        status, pivots = lemke(A, q, z, w, settings[PIVOT_MIN], settings[PIVOT_MAX], tol_lex,
                               int(settings[MAX_PIVOTS]), pb.fwork, pb.iwork)
    doubtful = status != SOLVED or family == FORCES and not trusted(A, q, z, na + nh, tol_lex)
    if nh > 0 and doubtful:
        status, more = _compliant_lemke(A, q, z, w, na, nh, pb.hrow, settings, tol_lex, pb.fwork, pb.iwork)
        pivots += more
        doubtful = status != SOLVED or family == FORCES and not trusted(A, q, z, na + nh, tol_lex)
    if doubtful:
        status, more = _normal_compliant_lemke(A, q, z, w, na, settings, tol_lex, pb.fwork, pb.iwork)
        pivots += more
    if status != SOLVED:
        log_event(events, t, EVENT_LCP_RAY + status - 1, float(m), float(pivots))
        return False
    remember_states(active, na, nh, pb.hrow, contacts.vertex, contacts.edge, z, w, pb.memory[SOLVING][kept:])
    return True


@jit(inline="always")
def trusted(A, q, z, rows, tol_lex):
    """Whether the accelerations (m/s^2; velocities, m/s, for impulses) of a solution z of a
    contact LCP(A, q) are determined to within TRUSTED_SPREAD of the data: in each of the rows
    i < ``rows`` (the normal and stick rows), tol_lex times the size of the terms that cancel,
    sum_j |A_ij z_j|, stays below TRUSTED_SPREAD max|q_i| over those rows."""
    data = 0.0
    for i in range(rows):
        data = max(data, abs(q[i]))
    for i in range(rows):
        terms = 0.0
        for j in range(q.shape[0]):
            terms += abs(A[i, j] * z[j])
        if tol_lex * terms > TRUSTED_SPREAD * data:
            return False
    return True


@jit(refcount=False)
def _compliant_lemke(A, q, z, w, na, nh, hrow, settings, tol_lex, fwork, iwork):
    """Lemke's method on the LCP (A, q) with a compliance on its stick rows na .. na + nh - 1
    (hrow[g]: the normal column of stick row na + g): c = STICK_COMPLIANCE times the largest
    diagonal entry of the stick block is added to the tangential block W_H^T M^-1 W_H of the
    Delassus matrix, so a sticking contact slides by c per unit of its friction force
    lambda_T = lambda_0R - mu lambda_N (m/s^2 per N, or m/s per N s at impacts). This makes
    coinciding stick rows independent, shares their friction force evenly, and leaves a contact
    without friction force (a body lying on a level floor) without sliding. A keeps the
    compliance (a contact-force LCP is built afresh each time; an impact's expansion reuses its
    compression's matrix, so it keeps the compliance the compression needed); returns (status,
    pivots), the solution checked on the compliant LCP."""
    compliance = 0.0
    for r in range(na, na + nh):
        compliance = max(compliance, abs(A[r, r]))
    compliance *= STICK_COMPLIANCE
    for g in range(nh):
        r = na + g
        mu = 0.5 * A[na + nh + g, hrow[g]]  # the cone row holds 2 mu lambda_N - lambda_0R >= 0
        A[r, r] += compliance
        A[r, hrow[g]] -= compliance * mu
    return lemke(A, q, z, w, settings[PIVOT_MIN], settings[PIVOT_MAX], tol_lex, int(settings[MAX_PIVOTS]), fwork,
                 iwork)


@jit(refcount=False)
def _normal_compliant_lemke(A, q, z, w, na, settings, tol_lex, fwork, iwork):
    """Lemke's method on the LCP (A, q) with STICK_COMPLIANCE times its largest normal diagonal
    entry added to the normal rows' diagonal: a contact then yields by that compliance per unit
    of its normal force (m/s^2 per N, or m/s per N s at impacts). The normal block is positive
    semidefinite; with the compliance it is definite, so that Lemke's method solves it where its
    rows are dependent to round-off (a vertex in the seam of two fixed bodies touching both,
    with opposite normals). A keeps the compliance; returns (status, pivots)."""
    compliance = 0.0
    for r in range(na):
        compliance = max(compliance, abs(A[r, r]))
    compliance *= STICK_COMPLIANCE
    for r in range(na):
        A[r, r] += compliance
    return lemke(A, q, z, w, settings[PIVOT_MIN], settings[PIVOT_MAX], tol_lex, int(settings[MAX_PIVOTS]), fwork,
                 iwork)


@jit(refcount=False)
def keep_states(pb, family, count):
    """Remember the states collected in memory slot SOLVING (rows :count) for the next LCPs
    of ``family``: the groups solved in this phase."""
    for r in range(count):
        for j in range(3):
            pb.memory[family, r, j] = pb.memory[SOLVING, r, j]
    pb.memory_count[family] = count


@jit(inline="always")
def _negative(q):
    """Whether an entry of q is negative (or NaN)."""
    for v in q:
        if not v >= 0.0:
            return True
    return False


@jit(inline="always")
def accelerations(na, contacts, rows, dyn, pb, settings, tol_lex, lam_n, lam_t, acc, events, t):
    """Contact forces (N) of the na contacts in pb.active, one LCP per group of coupled
    contacts (mbds.kernel.components: pb.active is reordered by group), and the accelerations
    acc = M^-1 (h + W lambda); False when an LCP failed (its group's forces are then 0, and
    its contacts are flagged in pb.jammed)."""
    active, stick, sign = pb.active, pb.stick, pb.sign
    n = acc.shape[0]
    ok = True
    # a contact slower than the rest velocity holds with g_N'' = -g_N' / (REST_RELAXATION dt_max), a sticking
    # one with g_T'' = -g_T' / (REST_RELAXATION dt_max): the speeds left below the rest velocity and the stick
    # threshold decay instead of drifting on, either way (a faster approach keeps its speed until the impact
    # law takes it: see :func:`impacts`; the gap settles to zero at the position level, mbds.kernel.settling);
    # the targets of a group whose rows are dependent are projected onto the
    # targets one motion meets (mbds.kernel.redundancy)
    relaxation = 1.0 / (REST_RELAXATION * settings[DT_MAX])
    rest = rest_velocity(settings)
    ng = split_components(active, na, rows.WN, rows.WT, dyn.YN, dyn.YT, pb.group, pb.root, pb.grouped, pb.masks)
    kept = 0
    for g in range(ng):
        part = active[pb.group[g] : pb.group[g + 1]]
        k = part.shape[0]
        nh = build_matrix(part, k, stick, sign, rows.laws, rows.WN, rows.WT, dyn.YN, dyn.YT, pb.column, pb.hrow,
                          pb.span, pb.A_flat)
        target = pb.z  # the rest targets, then the LCP's solution
        for a in range(k):
            c = part[a]
            left = rows.gd_n[c] if rows.gd_n[c] >= -rest else 0.0
            target[a] = left * relaxation
        for h in range(nh):
            target[k + h] = rows.gd_t[part[pb.hrow[h]]] * relaxation
        if k > 1:
            project_targets(part, k, nh, pb.hrow, rows.WN, rows.WT, pb.span, target, settings[PIVOT_MAX], pb.gram,
                            pb.gram[n:], pb.iwork)
        for a in range(k):
            c = part[a]
            pb.bvec[a] = row_dot(rows.WN, c, dyn.minv_h) + rows.wbar_n[c] + target[a]
        for h in range(nh):
            c = part[pb.hrow[h]]
            pb.bvec[k + h] = row_dot(rows.WT, c, dyn.minv_h) + rows.wbar_t[c] + target[k + h]
            pb.bvec[k + nh + h] = 0.0
        solved = solve(k + 2 * nh, 0, part, k, nh, FORCES, kept, contacts, pb, settings, tol_lex, events, t)
        for a in range(k):
            lam_n[part[a]] = 0.0
            lam_t[part[a]] = 0.0
        if solved:
            tangential_forces(part, k, stick, sign, rows.laws, pb.z, lam_n, lam_t)
            kept += k
        for a in range(k):
            pb.jammed[part[a]] = not solved
        ok = ok and solved
    keep_states(pb, FORCES, kept)
    for k in range(n):
        acc[k] = dyn.minv_h[k]
    for a in range(na):
        c = active[a]
        for k in range(n):
            acc[k] += lam_n[c] * dyn.YN[c, k] + lam_t[c] * dyn.YT[c, k]
    return ok


@jit(refcount=False)
def contact_forces(nc, contacts, rows, dyn, pb, settings, tol_lex, lam_n, lam_t, acc, events, t):
    """The contacts at rest (:func:`resting_contacts`), their forces and the accelerations;
    returns (number of contacts at rest, solved)."""
    na = resting_contacts(nc, contacts.gap, rows.gd_n, rows.gd_t, pb.active, pb.stick, pb.sign, pb.jammed, settings)
    ok = accelerations(na, contacts, rows, dyn, pb, settings, tol_lex, lam_n, lam_t, acc, events, t)
    return na, ok


@jit(refcount=False)
def resting_contacts(nc, gap, gd_n, gd_t, active, stick, sign, jammed, settings):
    """The contacts at rest among the nc detected (closed and not separating faster than the rest
    velocity, or held and slower than it either way) into active; stick: slower than the stick
    threshold tangentially; sign: the direction of sliding; jammed cleared (see
    :func:`accelerations`). Returns their number."""
    rest = rest_velocity(settings)
    na = 0
    for i in range(nc):
        jammed[i] = False
        if closed(gap[i], settings) and gd_n[i] <= rest or held(gap[i], settings) and abs(gd_n[i]) <= rest:
            active[na] = i
            na += 1
            stick[i] = abs(gd_t[i]) <= STICK_FRACTION * rest
            sign[i] = 1.0 if gd_t[i] > 0.0 else -1.0
    return na


@jit(refcount=False)
def free_accelerations(minv_h, acc):
    """acc = M^-1 h, the accelerations without contacts; returns True (solved)."""
    for k in range(acc.shape[0]):
        acc[k] = minv_h[k]
    return True
