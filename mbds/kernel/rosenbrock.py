"""The stiff option: the linearly implicit Rosenbrock 2(3) pair of MATLAB's ode23s (numba).

Method, error estimate, step-size rules and the interpolant of the reports follow Shampine and
Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18 (1997) 1-22, Sec. 3: with
d = 1/(2 + sqrt 2) and W = I - h d J,

    k1 = W^-1 (F0 + h d T),  F1 = f(t + h/2, y + h k1/2),  k2 = W^-1 (F1 - k1) + k1,
    y_new = y + h k2,  F2 = f(t + h, y_new),
    k3 = W^-1 (F2 - e32 (k2 - F1) - 2 (k1 - F0) + h d T),  error = h (k1 - 2 k2 + k3)/6,

e32 = 6 + sqrt 2, J = df/dy and T = df/dt by forward differences at the start of each step
(the model memory is restored after those evaluations, so they never start a contact).
Every evaluation, those of the Jacobian included, counts in the number of evaluations.
Same calling convention and resumable state as mbds.kernel.dopri5.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.dapbc_layout import DONE, NEXT_OUTPUT, NFEV, REJECTED
from mbds.kernel.jit import jit
from mbds.kernel.linalg import lu_solve
from mbds.kernel.ode_control import accept, clamp, error_norm, start

D = 1.0 / (2.0 + np.sqrt(2.0))
E32 = 6.0 + np.sqrt(2.0)
POW = 1 / 3
DELTA = 1.4901161193847656e-08  # sqrt of the double-precision epsilon


@jit
def interpolate(y, k, h, s, out):
    """ode23s's interpolant at the fraction s of the step (k = (k1, k2))."""
    scale = 1.0 / (1.0 - 2.0 * D)
    out[:] = y + h * ((s * (1.0 - s) * scale) * k[0] + (s * (s - 2.0 * D) * scale) * k[1])


@jit(inline="always")
def _derivatives(evaluate, data, state, t, y, f0, J, T):
    """J = df/dy and T = df/dt at (t, y) by forward differences; returns the evaluations used."""
    n = y.shape[0]
    saved = state.copy()
    shifted, fs = y.copy(), np.empty(n)
    for j in range(n):
        delta = DELTA * max(abs(y[j]), 1.0)
        shifted[j] = y[j] + delta
        evaluate(t, shifted, data, state, fs)
        state[:] = saved
        shifted[j] = y[j]
        J[:, j] = (fs - f0) / delta
    dt = DELTA * max(abs(t), 1.0)
    evaluate(t + dt, y, data, state, fs)
    state[:] = saved
    T[:] = (fs - f0) / dt
    return n + 1


@jit(inline="always")
def rosenbrock23(evaluate, project, projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index):
    """See mbds.kernel.dopri5.dopri5 (same arguments and return codes)."""
    y, f0, clock, counts = integ.y, integ.f0, integ.clock, integ.counts
    n = y.shape[0]
    tfinal = t_out[-1]
    hmax, threshold = start(evaluate, data, state, t_out, rtol, atol, integ, out_y, out_state, 0.5)
    J, T = np.empty((n, n)), np.empty(n)
    W = np.empty((n, n))
    F1, F2, k1, k2, k3 = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    stage, ynew, dense = np.empty(n), np.empty(n), np.empty((2, n))
    while counts[DONE] == 0 and counts[NEXT_OUTPUT] <= stop_index:
        t = clock[0]
        hmin = 16.0 * np.spacing(t)
        absh = min(hmax, max(hmin, clock[1]))
        counts[NFEV] += _derivatives(evaluate, data, state, t, y, f0, J, T)
        nofailed = True
        done = False
        err = 0.0
        h = absh
        tnew = t
        while True:
            h, absh, done = clamp(absh, t, tfinal)
            for i in range(n):
                for j in range(n):
                    W[i, j] = -h * D * J[i, j]
                W[i, i] += 1.0
            k1[:] = lu_solve(W, f0 + h * D * T)[0]
            stage[:] = y + 0.5 * h * k1
            evaluate(t + 0.5 * h, stage, data, state, F1)
            k2[:] = lu_solve(W, F1 - k1)[0] + k1
            tnew = tfinal if done else t + h
            ynew[:] = y + h * k2
            evaluate(tnew, ynew, data, state, F2)
            k3[:] = lu_solve(W, F2 - E32 * (k2 - F1) - 2.0 * (k1 - f0) + h * D * T)[0]
            counts[NFEV] += 2
            err = error_norm(y, ynew, (k1 - 2.0 * k2 + k3) / 6.0, threshold, absh)
            if err <= rtol:
                break
            counts[REJECTED] += 1
            if absh <= hmin:
                return 1
            if nofailed and np.isfinite(err):
                absh = max(hmin, absh * max(0.5, 0.8 * (rtol / err) ** POW))
            else:
                absh = max(hmin, 0.5 * absh)
            nofailed = False
        dense[0], dense[1] = k1, k2
        status = accept(project, projecting, interpolate, data, state, t_out, t, tnew, h, dense, ynew, F2, integ,
                        out_y, out_state, absh, err, rtol, POW, nofailed, done)
        if status:
            return status
    return 0
