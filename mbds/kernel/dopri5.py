"""The Dormand-Prince 5(4) pair with error control as MATLAB's ode45 applies it (numba).

Step-size rules, error norm, initial step and the interpolant of the reports are ode45's
(Shampine and Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18 (1997) 1-22; the pair:
Dormand and Prince, J. Comput. Appl. Math. 6 (1980) 19-26), so that at the same RelTol and
AbsTol the steps, the answers and the count of function evaluations (1 + 6 per attempted step)
are those of ode45.  The integration is resumable: it stops once a given report index is
written and goes on from the same state (mbds.kernel.dapbc_layout.IntegratorState), so a
caller can show progress without changing a single step.

``evaluate(t, y, data, state, yd)`` is the right-hand side; ``state`` is the model's memory
between evaluations (contact states), passed through.  With ``projecting`` set,
``project(t, y, data)`` moves every accepted step's end and every report onto the constraint
manifold (coordinates, then velocities); the step's last derivative is still used as the next
step's first, so the count of evaluations stays ode45's.  Without it the steps are ode45's.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.dapbc_layout import DONE, NEXT_OUTPUT, NFEV, REJECTED
from mbds.kernel.jit import jit
from mbds.kernel.ode_control import accept, clamp, error_norm, start

C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0.0],
    [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
])
#: error estimate weights (5th minus 4th order solution), over the seven stages
E = np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])
#: the continuous extension of ode45's ntrp45: y(t + s h) = y + h K BI (s, s^2, s^3, s^4)
BI = np.array([
    [1.0, -183 / 64, 37 / 12, -145 / 128],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 1500 / 371, -1000 / 159, 1000 / 371],
    [0.0, -125 / 32, 125 / 12, -375 / 64],
    [0.0, 9477 / 3392, -729 / 106, 25515 / 6784],
    [0.0, -11 / 7, 11 / 3, -55 / 28],
    [0.0, 3 / 2, -4.0, 5 / 2],
])
POW = 1 / 5


@jit
def interpolate(y, K, h, s, out):
    """ode45's interpolant at the fraction s of the step from y with stage derivatives K."""
    w = np.zeros(7)
    for i in range(7):
        w[i] = BI[i, 0] * s + BI[i, 1] * s ** 2 + BI[i, 2] * s ** 3 + BI[i, 3] * s ** 4
    for j in range(y.shape[0]):
        acc = 0.0
        for i in range(7):
            acc += K[i, j] * w[i]
        out[j] = y[j] + h * acc


@jit(inline="always")
def dopri5(evaluate, project, projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index):
    """Integrate from t_out[0] (state ``integ``) and write y at each t_out[k] into out_y[k] and
    the model memory into out_state[k], until report ``stop_index`` is written.  Returns
    0 (reports up to stop_index written), 1 (the step size fell below ode45's minimum) or
    2 (a state that is not finite)."""
    y, f0, clock, counts = integ.y, integ.f0, integ.clock, integ.counts
    n = y.shape[0]
    tfinal = t_out[-1]
    hmax, threshold = start(evaluate, data, state, t_out, rtol, atol, integ, out_y, out_state, POW)
    K = np.empty((7, n))
    stage, ynew, estimate = np.empty(n), np.empty(n), np.empty(n)
    while counts[DONE] == 0 and counts[NEXT_OUTPUT] <= stop_index:
        t = clock[0]
        hmin = 16.0 * np.spacing(t)
        absh = min(hmax, max(hmin, clock[1]))
        h, absh, done = clamp(absh, t, tfinal)
        nofailed = True
        err = 0.0
        while True:
            K[0] = f0
            for i in range(1, 7):
                for j in range(n):
                    acc = 0.0
                    for m in range(i):
                        acc += A[i, m] * K[m, j]
                    stage[j] = y[j] + h * acc
                if i < 6:
                    evaluate(t + C[i] * h, stage, data, state, K[i])
            tnew = tfinal if done else t + h
            h = tnew - t
            ynew[:] = stage
            evaluate(tnew, ynew, data, state, K[6])
            counts[NFEV] += 6
            for j in range(n):
                estimate[j] = 0.0
                for i in range(7):
                    estimate[j] += K[i, j] * E[i]
            err = error_norm(y, ynew, estimate, threshold, absh)
            if err <= rtol:
                break
            counts[REJECTED] += 1
            if absh <= hmin:
                return 1
            if nofailed:
                nofailed = False
                if np.isfinite(err):
                    absh = max(hmin, absh * max(0.1, 0.8 * (rtol / err) ** POW))
                else:
                    absh = max(hmin, 0.1 * absh)
            else:
                absh = max(hmin, 0.5 * absh)
            h = absh
            done = False
        status = accept(project, projecting, interpolate, data, state, t_out, t, tnew, h, K, ynew, K[6], integ,
                        out_y, out_state, absh, err, rtol, POW, nofailed, done)
        if status:
            return status
    return 0
