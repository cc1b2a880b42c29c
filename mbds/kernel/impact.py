"""Impacts: Poisson's law over the closed contacts of each group that holds an impacting contact
(mbds.kernel.components), as a compression and an expansion LCP (see docs/theory.md and
mbds.kernel.contact_problem)."""

from __future__ import annotations

from mbds.kernel.active_set import solve_states
from mbds.kernel.components import split_components
from mbds.kernel.contact_problem import (
    COMPRESSION,
    EXPANSION,
    SOLVING,
    build_matrix,
    closed,
    impacts,
    keep_states,
    rest_velocity,
    row_dot,
    solve,
    tangential_forces,
    trusted,
)
from mbds.kernel.jit import jit
from mbds.kernel.layout import DRIVE_WORK, DT_MAX, LOST, MAX_PIVOTS, PIVOT_MAX, PIVOT_MIN
from mbds.kernel.lcp import SOLVED, lemke
from mbds.kernel.linalg import span_dot
from mbds.kernel.rollback import record

LEFT_APPROACH = 1e-3
"""A contact that still approaches after the compression LCP faster than LEFT_APPROACH times the
rest velocity (it would go 1e-5 maxPen deeper within a maximum step) is stopped by the normal
rows alone (:func:`_stop_approach`). The compression LCP holds its rows to tol_lex of its largest
data, the sliding speeds among them: a contact at rest beside one sliding at 1 m/s kept
approaching at 3e-8 m/s, and beyond maximumPenetration that held the step at minimumTimestep."""


@jit(refcount=False)
def impact(nc, contacts, rows, dyn, pb, forces, u, settings, tol_lex, clock, model, point_loss,
           point_interval, back, events, t, jam, present):
    """Compression and expansion LCPs over the closed contacts of each group of coupled contacts
    (mbds.kernel.components) that holds an impacting one (:func:`impacts`); the other groups
    are left to the contact forces of the step. With ``jam``, the groups that hold a contact
    flagged in pb.jammed take an impact without collision instead: their contact-force LCP has
    no solution (Painlevé's case). At the present rates the zero impulse solves their
    compression, so its states are found from the rates after a maximum step of motion without
    contact forces (g' + dt_max (W^T M^-1 h + w-bar)): which contacts that motion presses, which
    stick. With ``present`` the impulse is then the one that stops the present rates in those
    states (:func:`_stop_present_rates`), so a sticking contact is left at rest; without it, or
    where that point is not a solution of the compression LCP, the impulse is the one that stops
    the approach of the maximum step, leaving the contacts with rates that cancel that motion.
    Updates u (and the relative velocities rows.gd_n, rows.gd_t), records impulses (N s) and
    losses (J). Returns False when an LCP failed: velocities are then left unchanged (a
    compression failed) or a group whose expansion failed keeps those after compression (a
    plastic impact). A group whose contacts would all rebound slower than the rest velocity
    expands without normal restitution."""
    active, group, laws, gd_n, gd_t = pb.active, pb.group, rows.laws, rows.gd_n, rows.gd_t
    WN, WT, YN, YT = rows.WN, rows.WT, dyn.YN, dyn.YT
    imp_n, imp_t, gam_n, gam_t = forces.imp_n, forces.imp_t, forces.gam_n, forces.gam_t
    lam_ne, lam_te, compression_loss = forces.lam_n, forces.lam_t, forces.compression_loss
    bvec, z = pb.bvec, pb.z
    na = 0
    for i in range(nc):
        if closed(contacts.gap[i], settings):
            active[na] = i
            na += 1
    ng = split_components(active, na, WN, WT, YN, YT, group, pb.root, pb.grouped, pb.masks)
    na, ng = _impacting_groups(active, group, ng, contacts.gap, gd_n, jam, pb.jammed, settings)
    ahead = settings[DT_MAX] if jam else 0.0
    for a in range(na):
        c = active[a]
        pb.stick[c] = True
        pb.sign[c] = 0.0
        gam_n[c] = gd_n[c]  # gamma_A
        gam_t[c] = gd_t[c]
    # compression: b = (gamma_NA, gamma_TA, 0); each group's matrix stays in A_flat for the expansion
    at = 0
    for g in range(ng):
        s = group[g]
        part = active[s : group[g + 1]]
        k = part.shape[0]
        build_matrix(part, k, pb.stick, pb.sign, laws, WN, WT, YN, YT, pb.column, pb.hrow, pb.span[s:],
                     pb.A_flat[at:])
        for a in range(k):
            c = part[a]
            bvec[a] = gd_n[c] + ahead * (row_dot(WN, c, dyn.minv_h) + rows.wbar_n[c])
            bvec[k + a] = gd_t[c] + ahead * (row_dot(WT, c, dyn.minv_h) + rows.wbar_t[c])
            bvec[2 * k + a] = 0.0
        if not solve(3 * k, at, part, k, k, COMPRESSION, s, contacts, pb, settings, tol_lex, events, t):
            return False
        tangential_forces(part, k, pb.stick, pb.sign, laws, z, imp_n, imp_t)
        if jam and present and _stop_present_rates(part, k, s, at, pb, rows, settings, tol_lex):
            tangential_forces(part, k, pb.stick, pb.sign, laws, z, imp_n, imp_t)
        at += 9 * k * k
    keep_states(pb, COMPRESSION, na)
    _apply_impulses(active, na, imp_n, imp_t, YN, YT, u)
    _relative_velocities(active, na, rows, u)
    stopped = compression_loss  # (the impulses of _stop_approach, until the compression losses replace them)
    for a in range(na):
        stopped[active[a]] = 0.0
    for g in range(ng):
        _stop_approach(active[group[g] : group[g + 1]], pb, rows, dyn, stopped, lam_ne, lam_te, u, settings,
                       tol_lex, pb.span[group[g] :], pb.A_flat[at:])
    # expansion: start from eN Lambda_NC (with its -mu tangential partner) and eT Lambda_TC;
    # the LCP adds the increments that keep contacts from closing, within Coulomb's cone
    for a in range(na):
        c = active[a]
        lam_ne[c] = laws[c, 1] * imp_n[c]
        lam_te[c] = laws[c, 2] * imp_t[c] - laws[c, 0] * lam_ne[c]
    at = 0
    expanded = True
    kept = 0
    rest = rest_velocity(settings)
    for g in range(ng):
        s = group[g]
        part = active[s : group[g + 1]]
        k = part.shape[0]
        # the fastest rebound Newton's law would give a contact of the group (m/s); where every
        # rebound would be slower than the rest velocity the group's impact is plastic in the normal
        # direction, so a body's bounces end instead of going on at the scale of one step's fall
        bounce = 0.0
        for a in range(k):
            bounce = max(bounce, -laws[part[a], 1] * gam_n[part[a]])
        if bounce < rest:
            for a in range(k):
                c = part[a]
                lam_ne[c] = 0.0
                lam_te[c] = laws[c, 2] * imp_t[c]
        for a in range(k):
            c = part[a]
            sn = gd_n[c]
            st = gd_t[c]
            for b in range(k):
                e = part[b]
                sn += (span_dot(WN, c, YN, e, pb.span, s + a) * lam_ne[e]
                       + span_dot(WN, c, YT, e, pb.span, s + a) * lam_te[e])
                st += (span_dot(WT, c, YN, e, pb.span, s + a) * lam_ne[e]
                       + span_dot(WT, c, YT, e, pb.span, s + a) * lam_te[e])
            bvec[a] = sn
            bvec[k + a] = st
            bvec[2 * k + a] = 2.0 * laws[c, 0] * lam_ne[c]
        solved = solve(3 * k, at, part, k, k, EXPANSION, kept, contacts, pb, settings, tol_lex, events, t)
        for a in range(k):
            c = part[a]
            if solved:
                lam_ne[c] += z[a]
                lam_te[c] = laws[c, 2] * imp_t[c] + z[k + a] - laws[c, 0] * lam_ne[c]
            else:  # keep the compression result: a plastic impact
                lam_ne[c] = 0.0
                lam_te[c] = 0.0
        if solved:
            kept += k
        expanded = expanded and solved
        at += 9 * k * k
    keep_states(pb, EXPANSION, kept)
    lost = 0.0
    drive = 0.0
    for a in range(na):  # loss of the compression phase; then gam_* <- gamma_C, imp_n the whole compression's
        c = active[a]
        imp_n[c] += stopped[c]
        compression_loss[c] = -0.5 * (imp_n[c] * (gam_n[c] + gd_n[c]) + imp_t[c] * (gam_t[c] + gd_t[c]))
        gam_n[c] = gd_n[c]
        gam_t[c] = gd_t[c]
    _apply_impulses(active, na, lam_ne, lam_te, YN, YT, u)
    _relative_velocities(active, na, rows, u)
    for a in range(na):
        c = active[a]
        loss = compression_loss[c] - 0.5 * (lam_ne[c] * (gam_n[c] + gd_n[c]) + lam_te[c] * (gam_t[c] + gd_t[c]))
        lost += loss
        drive -= (imp_n[c] + lam_ne[c]) * rows.what_n[c] + (imp_t[c] + lam_te[c]) * rows.what_t[c]
        record(contacts, c, imp_n[c] + lam_ne[c], imp_t[c] + lam_te[c], loss, model, point_loss,
               point_interval, back)
    clock[LOST] += lost
    clock[DRIVE_WORK] += drive
    return expanded


@jit(refcount=False)
def _stop_present_rates(part, k, s, at, pb, rows, settings, tol_lex):
    """The compression LCP of the jammed group ``part`` (k contacts, all stick candidates; its
    matrix at pb.A_flat[at:], the states of its look-ahead solution in memory slot SOLVING from row
    s on) for the present rates (g_N', g_T', 0), solved in those states alone: True when that
    point is a solution (in pb.z), which then stops the present rates of the contacts the
    look-ahead pressed (a sticking one is left with g_N' = g_T' = 0). The zero impulse solves
    the same LCP; this is the other solution, the one the look-ahead selects."""
    m = 3 * k
    for a in range(k):
        c = part[a]
        pb.state[a] = pb.memory[SOLVING, s + a, 2]
        pb.bvec[a] = rows.gd_n[c]
        pb.bvec[k + a] = rows.gd_t[c]
        pb.bvec[2 * k + a] = 0.0
    return solve_states(pb.A_flat[at : at + m * m].reshape((m, m)), pb.bvec[:m], pb.z[:m], pb.w[:m], k, k, pb.hrow,
                        pb.state, 0, settings[PIVOT_MAX], tol_lex, int(settings[MAX_PIVOTS]), pb.fwork, pb.iwork)


@jit(refcount=False)
def _stop_approach(part, pb, rows, dyn, stopped, dn, dt, u, settings, tol_lex, span, A_flat):
    """Stop what the compression of the group ``part`` left approaching: where a contact still
    approaches faster than LEFT_APPROACH times the rest velocity, the normal rows alone (their
    LCP has the approach velocities as its only data, so Lemke's solution check holds them to
    round-off of those) give normal impulses (N s, into ``stopped``), and u and the relative
    velocities follow. They are not restituted: the expansion starts from the compression LCP's
    impulses, so what corrects its round-off cannot feed energy back. dn, dt: scratch; span: the
    group's rows of pb.span; A_flat: room for the k x k matrix."""
    k = part.shape[0]
    left = False
    for a in range(k):
        left = left or rows.gd_n[part[a]] < -LEFT_APPROACH * rest_velocity(settings)
    if not left:
        return
    for a in range(k):
        pb.stick[part[a]] = False
    build_matrix(part, k, pb.stick, pb.sign, rows.laws, rows.WN, rows.WT, dyn.YN, dyn.YT, pb.column, pb.hrow, span,
                 A_flat)
    for a in range(k):
        pb.stick[part[a]] = True
        pb.bvec[a] = rows.gd_n[part[a]]
    status, _ = lemke(A_flat[: k * k].reshape((k, k)), pb.bvec[:k], pb.z[:k], pb.w[:k], settings[PIVOT_MIN],
                      settings[PIVOT_MAX], tol_lex, int(settings[MAX_PIVOTS]), pb.fwork, pb.iwork)
    if status != SOLVED or not trusted(A_flat[: k * k].reshape((k, k)), pb.bvec[:k], pb.z[:k], k, tol_lex):
        return  # (dependent normal rows: the squeeze between them is not determined; leave it)
    for a in range(k):
        c = part[a]
        stopped[c] = pb.z[a]
        dn[c] = pb.z[a]
        dt[c] = 0.0
    _apply_impulses(part, k, dn, dt, dyn.YN, dyn.YT, u)
    _relative_velocities(part, k, rows, u)


@jit(refcount=False)
def _impacting_groups(active, group, ng, gap, gd_n, jam, jammed, settings):
    """Keep the groups active[group[g]:group[g + 1]] that hold an impacting contact (with ``jam``:
    a jammed one), moved to the front in their order; return (their number of contacts, their
    number)."""
    na = 0
    kept = 0
    for g in range(ng):
        start, end = group[g], group[g + 1]
        hit = False
        for a in range(start, end):
            hit = hit or (jammed[active[a]] if jam else impacts(gap[active[a]], gd_n[active[a]], settings))
        if hit:
            group[kept] = na
            for a in range(start, end):
                active[na] = active[a]
                na += 1
            kept += 1
    group[kept] = na
    return na, kept


@jit(refcount=False)
def _apply_impulses(active, na, imp_n, imp_t, YN, YT, u):
    """u += M^-1 (W_N imp_n + W_T imp_t) over the active contacts (impulses in N s)."""
    for a in range(na):
        c = active[a]
        for k in range(u.shape[0]):
            u[k] += imp_n[c] * YN[c, k] + imp_t[c] * YT[c, k]


@jit(refcount=False)
def _relative_velocities(active, na, rows, u):
    """Normal and tangential relative velocities (m/s) of the active contacts at u."""
    for a in range(na):
        c = active[a]
        rows.gd_n[c] = row_dot(rows.WN, c, u) + rows.what_n[c]
        rows.gd_t[c] = row_dot(rows.WT, c, u) + rows.what_t[c]
