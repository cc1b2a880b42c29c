"""Impacts: Poisson's law over all closed contacts, as a compression and an expansion LCP
(see docs/theory.md and mbds.kernel.contact_problem)."""

from __future__ import annotations

from mbds.kernel.contact_problem import (
    CLOSED_FRACTION,
    COMPRESSION,
    EXPANSION,
    build_matrix,
    row_dot,
    solve,
    span_dot,
    tangential_forces,
)
from mbds.kernel.jit import jit
from mbds.kernel.layout import DRIVE_WORK, LOST, MAX_PEN
from mbds.kernel.rollback import record


@jit(refcount=False)
def impact(nc, contacts, rows, dyn, pb, forces, u, settings, tol_lex, clock, model, point_loss,
           point_interval, back, events, t):
    """Compression and expansion LCPs over all closed contacts; updates u (and the relative
    velocities rows.gd_n, rows.gd_t), records impulses (N s) and losses (J). Returns False when
    an LCP failed: velocities are then left unchanged (compression failed) or those after
    compression are kept (expansion failed)."""
    active, laws, gd_n, gd_t = pb.active, rows.laws, rows.gd_n, rows.gd_t
    WN, WT, YN, YT = rows.WN, rows.WT, dyn.YN, dyn.YT
    imp_n, imp_t, gam_n, gam_t = forces.imp_n, forces.imp_t, forces.gam_n, forces.gam_t
    lam_ne, lam_te, compression_loss = forces.lam_n, forces.lam_t, forces.compression_loss
    bvec, z = pb.bvec, pb.z
    na = 0
    for i in range(nc):
        if contacts.gap[i] <= CLOSED_FRACTION * settings[MAX_PEN]:
            active[na] = i
            na += 1
            pb.stick[i] = True
            pb.sign[i] = 0.0
            gam_n[i] = gd_n[i]  # gamma_A
            gam_t[i] = gd_t[i]
    nh = build_matrix(active, na, pb.stick, pb.sign, laws, WN, WT, YN, YT, pb.column, pb.hrow, pb.span, pb.A_flat)
    m = na + 2 * nh
    for a in range(na):  # compression: b = (gamma_NA, gamma_TA, 0)
        c = active[a]
        bvec[a] = gd_n[c]
        bvec[na + a] = gd_t[c]
        bvec[2 * na + a] = 0.0
    if not solve(m, na, nh, COMPRESSION, contacts.vertex, contacts.edge, pb, settings, tol_lex, events, t):
        return False
    tangential_forces(active, na, pb.stick, pb.sign, laws, z, imp_n, imp_t)
    _apply_impulses(active, na, imp_n, imp_t, YN, YT, u)
    _relative_velocities(active, na, rows, u)
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
            sn += span_dot(WN, c, YN, e, pb.span, a) * lam_ne[e] + span_dot(WN, c, YT, e, pb.span, a) * lam_te[e]
            st += span_dot(WT, c, YN, e, pb.span, a) * lam_ne[e] + span_dot(WT, c, YT, e, pb.span, a) * lam_te[e]
        bvec[a] = sn
        bvec[na + a] = st
        bvec[2 * na + a] = 2.0 * laws[c, 0] * lam_ne[c]
    expanded = solve(m, na, nh, EXPANSION, contacts.vertex, contacts.edge, pb, settings, tol_lex, events, t)
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
