"""What the two integrators of DAP_BC's forward dynamics share (numba): the start of a run
(first evaluation, first report, initial step from the initial derivative as in Shampine and
Reichelt, SIAM J. Sci. Comput. 18 (1997) 1-22) and the end of an accepted step (projection,
reports by the method's interpolant, the next step size, the resumable state).  See
mbds.kernel.dopri5 for the calling convention."""

from __future__ import annotations

import numpy as np

from mbds.kernel.dapbc_layout import ACCEPTED, DONE, NEXT_OUTPUT, NFEV
from mbds.kernel.jit import jit


@jit(inline="always")
def start(evaluate, data, state, t_out, rtol, atol, integ, out_y, out_state, power):
    """The maximum step (a tenth of the interval) and the error threshold AbsTol/RelTol; at the
    start of a run (no evaluation yet) also the first evaluation and report, and the first step
    size min(h_max, DT, 1/rh) with rh = 1.25 max_j |f_j| / max(|y_j|, threshold) / RelTol^power."""
    y, f0, clock, counts = integ.y, integ.f0, integ.clock, integ.counts
    t0 = t_out[0]
    span = abs(t_out[-1] - t0)
    if counts[NFEV] > 0:
        return 0.1 * span, atol / rtol
    evaluate(t0, y, data, state, f0)
    counts[NFEV] = 1
    out_y[0] = y
    out_state[0] = state
    counts[NEXT_OUTPUT] = 1
    clock[0] = t0
    absh = min(0.1 * span, abs(t_out[1] - t0) if t_out.shape[0] > 1 else span)
    rh = 0.0
    for j in range(y.shape[0]):
        rh = max(rh, abs(f0[j]) / max(abs(y[j]), atol / rtol))
    rh = 1.25 * rh / rtol ** power
    clock[1] = 1.0 / rh if absh * rh > 1.0 else absh
    return 0.1 * span, atol / rtol


@jit(inline="always")
def accept(project, projecting, interpolant, data, state, t_out, t, tnew, h, dense, ynew, last, integ, out_y,
           out_state, absh, err, rtol, power, nofailed, done):
    """Finish an accepted step from (t, y) to (tnew, ynew): project it, write the reports in
    (t, tnew] (``interpolant(y, dense, h, s, out)`` between the ends), grow the step after a
    step without failure by 1/max(0.2, 1.25 (err/RelTol)^power) (at most 5), and move the
    state on (``last``: the derivative at the new point).  Returns 2 when ynew is not finite."""
    y, f0, clock, counts = integ.y, integ.f0, integ.clock, integ.counts
    counts[ACCEPTED] += 1
    if projecting:
        project(tnew, ynew, data)
    k = counts[NEXT_OUTPUT]
    while k < t_out.shape[0] and t_out[k] <= tnew:
        if t_out[k] == tnew:
            out_y[k] = ynew
        else:
            interpolant(y, dense, h, (t_out[k] - t) / h, out_y[k])
        if projecting:
            project(t_out[k], out_y[k], data)
        out_state[k] = state
        k += 1
    counts[NEXT_OUTPUT] = k
    if done:
        counts[DONE] = 1
    if nofailed:
        temp = 1.25 * (err / rtol) ** power
        absh = absh / temp if temp > 0.2 else 5.0 * absh
    clock[0] = tnew
    clock[1] = absh
    y[:] = ynew
    f0[:] = last
    return 0 if np.all(np.isfinite(ynew)) else 2


@jit
def error_norm(y, ynew, e, threshold, absh):
    """ode45's and ode23s's error measure absh max_j |e_j| / max(|y_j|, |ynew_j|, threshold)
    of the local error estimate e per unit step; inf when it is not finite."""
    err = 0.0
    for j in range(y.shape[0]):
        err = max(err, abs(e[j]) / max(max(abs(y[j]), abs(ynew[j])), threshold))
    err *= absh
    return err if np.isfinite(err) else np.inf


@jit
def clamp(absh, t, tfinal):
    """(h, |h|, last): the step from t, stretched or cut to end at tfinal when within 10 % of it."""
    if 1.1 * absh >= abs(tfinal - t):
        return tfinal - t, abs(tfinal - t), True
    return absh, absh, False
