"""DAP_BC's analyses for any model, compiled once and cached with the kernel.

Each takes the table of the model's generated functions (rows: mbds.kernel.dapbc_layout.
DAPBC_FUNCTIONS; see mbds.kernel.function_table) and its number of constraint equations nc as its first two
arguments; the equations are those of mbds.kernel.dapbc_equations. A model of a new structure
therefore compiles only its own functions. Units: SI; arrays float64, C-contiguous.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel import dapbc_equations as eq
from mbds.kernel.dapbc_layout import DAPBC_FUNCTIONS, DapbcFunctions
from mbds.kernel.dopri5 import dopri5
from mbds.kernel.function_table import function_at
from mbds.kernel.jit import jit
from mbds.kernel.rosenbrock import rosenbrock23

_PHI, _D, _NU, _GAMMA, _BEFORE, _AFTER, _USER, _ENERGY = (function_at(s) for s in DAPBC_FUNCTIONS.values())


@jit(inline="always")
def _functions(table, nc):
    """The model's functions of ``table`` as a DapbcFunctions bundle."""
    return DapbcFunctions(_PHI(table, 0), _D(table, 1), _NU(table, 2), _GAMMA(table, 3), _BEFORE(table, 4),
                          _AFTER(table, 5), _USER(table, 6), _ENERGY(table, 7), nc)


PROJECTION_TOLERANCE = 1e-12
"""Largest |Phi| (m, rad) left by the projection of forward dynamics onto the constraints."""


@jit
def _evaluate(t, y, model, state, yd):
    """yd = (qd, qdd) of y = (q, qd) at time t (s); model: (DapbcFunctions, DapbcData)."""
    f, data = model
    eq.accelerations(f.jacobian, f.acceleration_rhs, f.forces_before, f.forces_after, f.user_force, t, y, data,
                     state, yd, np.empty(f.nc), np.empty((f.nc, y.shape[0] // 2)))


@jit
def _project(t, y, model):
    """y = (q, qd) moved onto the constraints at time t: Newton on the coordinates, then the
    velocities (the initial-condition correction); model: (DapbcFunctions, DapbcData)."""
    f, data = model
    n = y.shape[0] // 2
    q, qd = y[:n].copy(), y[n:].copy()
    _correct(f, q, qd, t, data.par, data.functs, PROJECTION_TOLERANCE)
    y[:n] = q
    y[n:] = qd


@jit(entry=True)
def forward_dopri5(table, nc, projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index):
    """Forward dynamics with the Dormand-Prince 5(4) pair (mbds.kernel.dopri5)."""
    f = _functions(table, nc)
    return dopri5(_evaluate, _project, projecting, (f, data), state, t_out, rtol, atol, integ, out_y, out_state,
                  stop_index)


@jit(entry=True)
def forward_stiff(table, nc, projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index):
    """Forward dynamics with the Rosenbrock 2(3) pair (mbds.kernel.rosenbrock)."""
    f = _functions(table, nc)
    return rosenbrock23(_evaluate, _project, projecting, (f, data), state, t_out, rtol, atol, integ, out_y,
                        out_state, stop_index)


@jit(entry=True)
def post(table, nc, times, Y, states, data, out):
    """DAP_BC's post arrays of the reports (mbds.kernel.dapbc_equations.post)."""
    f = _functions(table, nc)
    eq.post(f.jacobian, f.acceleration_rhs, f.forces_before, f.forces_after, f.user_force, f.potential_energy,
            times, Y, states, data, out)


@jit(entry=True)
def correct(table, nc, q, qd, t, par, functs, tolerance):
    """DAP_BC's initial-condition correction in place; returns the Newton iterations (-1: failed)."""
    return _correct(_functions(table, nc), q, qd, t, par, functs, tolerance)


@jit(inline="always")
def _correct(f, q, qd, t, par, functs, tolerance):
    """Newton on the coordinates q to |Phi| <= tolerance, then the velocities qd, in place (f:
    DapbcFunctions); returns the Newton iterations (-1: failed)."""
    iterations = eq.correct_positions(f.constraints, f.jacobian, f.nc, q, t, par, functs, tolerance)
    eq.correct_velocities(f.jacobian, f.velocity_rhs, f.nc, q, qd, t, par, functs)
    return iterations


@jit(entry=True)
def kinematic_state(table, nc, q, qd, qdd, t, par, functs, tolerance):
    """Kinematic analysis at time t (mbds.kernel.dapbc_equations.kinematic_state)."""
    f = _functions(table, nc)
    return eq.kinematic_state(f.constraints, f.jacobian, f.velocity_rhs, f.acceleration_rhs, f.nc, q, qd, qdd, t,
                              par, functs, tolerance)


@jit(entry=True)
def inverse_multipliers(table, nc, t, q, qd, qdd, data, state, lam, D):
    """Inverse dynamics: lam from D^T lam = M qdd - h."""
    f = _functions(table, nc)
    eq.inverse_multipliers(f.jacobian, f.forces_before, f.forces_after, f.user_force, t, q, qd, qdd, data, state,
                           lam, D)


@jit(entry=True)
def static_equilibrium(table, nc, t, x, data, state, tolerance):
    """Static equilibrium by Newton's method from x = (q, lam)."""
    f = _functions(table, nc)
    return eq.static_equilibrium(f.constraints, f.jacobian, f.forces_before, f.forces_after, f.user_force, t, x,
                                 data, state, tolerance)


ANALYSES = (forward_dopri5, forward_stiff, post, correct, kinematic_state, inverse_multipliers, static_equilibrium)
"""The functions a model's compiled module is bound to (mbds.expr.dapbc_codegen)."""
