"""Generate, cache and load the numba module of a DAP_BC model's equations.

The module holds the model's sympy-derived functions (q, qd: coordinates and velocities;
par: parameters; fv: (nFunct, 3) values f, f', f'' of the driver functions at t):

- ``constraints(q, t, par, fv, out)``: Phi (nConst,)
- ``jacobian(q, t, par, fv, D)``: D = dPhi/dq (nConst, 3 nB)
- ``velocity_rhs(q, t, par, fv, out)``: nu with D qd = nu
- ``acceleration_rhs(q, qd, t, par, fv, out)``: gamma with D qdd = gamma
- ``forces_before``, ``forces_after(q, qd, t, par, fv, h)``: add the force elements before and
  after the ``user`` element to h
- ``potential_energy(q, par)``: J

then the user force (compiled MATLAB subset or the model's Python function) and the analyses of
mbds.kernel bound to these functions: ``evaluate``, ``forward_dopri5``, ``forward_stiff``,
``post``, ``correct``, ``kinematic_state``, ``inverse_multipliers``, ``static_equilibrium``.
Parameter values are not part of the text, so its hash (the cache key) depends on the model's
structure only; the kernel's source hash is part of it too.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

import sympy

from mbds._version import version as mbds_version
from mbds.expr import cache
from mbds.expr.codegen import _assign
from mbds.expr.printer import NumbaPrinter
from mbds.kernel.jit import kernel_source_hash


@dataclass(frozen=True)
class DapbcExpressions:
    """A DAP_BC model's equations as sympy expressions (see the module documentation), and the
    Python source of its user force (None when it has none)."""

    n: int
    phi: list
    jacobian: list  # rows of D
    nu: list
    gamma: list
    forces_before: list  # h of the elements before the user element, 3 nB entries
    forces_after: list
    potential: sympy.Expr
    user_imports: str | None
    user_source: str | None


_V, _M = "float64[::1]", "float64[:, ::1]"
_FUNCTIONS = (
    ("constraints", "q, t, par, fv, out", f"void({_V}, float64, {_V}, {_M}, {_V})", "Constraint equations Phi into out."),
    ("jacobian", "q, t, par, fv, D", f"void({_V}, float64, {_V}, {_M}, {_M})", "Jacobian D = dPhi/dq into D."),
    ("velocity_rhs", "q, t, par, fv, out", f"void({_V}, float64, {_V}, {_M}, {_V})", "nu (D qd = nu) into out."),
    ("acceleration_rhs", "q, qd, t, par, fv, out", f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
     "gamma (D qdd = gamma) into out."),
    ("forces_before", "q, qd, t, par, fv, out", f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
     "Add the force elements before the user element to out."),
    ("forces_after", "q, qd, t, par, fv, out", f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
     "Add the force elements after the user element to out."),
)
#: the user force's signature (mbds.io.dapbc.user_force.SIGNATURE)
USER_FORCE_TYPES = (f"void(float64, {_M}, {_V}, {_M}, {_V}, float64[:, :, ::1], {_M}, {_M}, {_M}, {_M}, {_V}, "
                    f"{_M}, {_V})")


#: explicit signatures (compiled when the module is imported, so that the analyses bound to
#: these functions can be cached) and IEEE arithmetic without exceptions, as mbds.expr.codegen


def _decorator(types: str) -> str:
    return f'@jit("{types}", error_model="numpy")'


_NO_USER_FORCE = f'''
{_decorator(USER_FORCE_TYPES)}
def user_force(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):
    """The model has no user force element (never called: data.has_user is 0)."""
    return None
'''

_BINDINGS = '''
from mbds.kernel import dapbc_equations as _eq  # noqa: E402
from mbds.kernel.dopri5 import dopri5 as _dopri5  # noqa: E402
from mbds.kernel.rosenbrock import rosenbrock23 as _rosenbrock23  # noqa: E402


@jit
def evaluate(t, y, data, state, yd):
    """yd = (qd, qdd) of y = (q, qd) at time t (s)."""
    _eq.accelerations(jacobian, acceleration_rhs, forces_before, forces_after, user_force, t, y, data, state,
                      yd, np.empty(NC), np.empty((NC, N)))


@jit
def project(t, y, data):
    """y = (q, qd) moved onto the constraints at time t: Newton on the coordinates, then the
    velocities (the initial-condition correction)."""
    q, qd = y[:N].copy(), y[N:].copy()
    _eq.correct_positions(constraints, jacobian, NC, q, t, data.par, data.functs, PROJECTION_TOLERANCE)
    _eq.correct_velocities(jacobian, velocity_rhs, NC, q, qd, t, data.par, data.functs)
    y[:N] = q
    y[N:] = qd


@jit
def forward_dopri5(projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index):
    """Forward dynamics with the Dormand-Prince 5(4) pair (mbds.kernel.dopri5)."""
    return _dopri5(evaluate, project, projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index)


@jit
def forward_stiff(projecting, data, state, t_out, rtol, atol, integ, out_y, out_state, stop_index):
    """Forward dynamics with the Rosenbrock 2(3) pair (mbds.kernel.rosenbrock)."""
    return _rosenbrock23(evaluate, project, projecting, data, state, t_out, rtol, atol, integ, out_y, out_state,
                         stop_index)


@jit
def post(times, Y, states, data, out):
    """DAP_BC's post arrays of the reports (mbds.kernel.dapbc_equations.post)."""
    _eq.post(jacobian, acceleration_rhs, forces_before, forces_after, user_force, potential_energy,
             times, Y, states, data, out)


@jit
def correct(q, qd, t, par, functs, tolerance):
    """DAP_BC's initial-condition correction in place; returns the Newton iterations (-1: failed)."""
    iterations = _eq.correct_positions(constraints, jacobian, NC, q, t, par, functs, tolerance)
    _eq.correct_velocities(jacobian, velocity_rhs, NC, q, qd, t, par, functs)
    return iterations


@jit
def constraint_values(q, t, par, functs, out):
    """Phi at (q, t) into out."""
    fv = np.empty((functs.shape[0], 3))
    _eq.funct_values(functs, t, fv)
    constraints(q, t, par, fv, out)


@jit
def kinematic_state(q, qd, qdd, t, par, functs, tolerance):
    """Kinematic analysis at time t (mbds.kernel.dapbc_equations.kinematic_state)."""
    return _eq.kinematic_state(constraints, jacobian, velocity_rhs, acceleration_rhs, NC, q, qd, qdd, t, par,
                               functs, tolerance)


@jit
def inverse_multipliers(t, q, qd, qdd, data, state, lam, D):
    """Inverse dynamics: lam from D^T lam = M qdd - h."""
    _eq.inverse_multipliers(jacobian, forces_before, forces_after, user_force, t, q, qd, qdd, data, state, lam, D)


@jit
def static_equilibrium(t, x, data, state, tolerance):
    """Static equilibrium by Newton's method from x = (q, lam)."""
    return _eq.static_equilibrium(constraints, jacobian, forces_before, forces_after, user_force, t, x, data,
                                  state, tolerance)
'''


def generate_source(e: DapbcExpressions) -> str:
    """The module's text; the same structure always gives the same text."""
    printer = NumbaPrinter()
    nc = len(e.phi)
    bodies = {
        "constraints": _assign(printer, [f"out[{k}]" for k in range(nc)], list(e.phi)),
        "jacobian": _assign(printer, [f"D[{k}, {i}]" for k in range(nc) for i in range(e.n)],
                            [x for row in e.jacobian for x in row]),
        "velocity_rhs": _assign(printer, [f"out[{k}]" for k in range(nc)], list(e.nu)),
        "acceleration_rhs": _assign(printer, [f"out[{k}]" for k in range(nc)], list(e.gamma)),
    }
    for name, h in (("forces_before", e.forces_before), ("forces_after", e.forces_after)):
        pairs = [(f"out[{i}]", x) for i, x in enumerate(h) if x != 0]
        lines = _assign(printer, [f"add{i}" for i in range(len(pairs))], [x for _, x in pairs])
        bodies[name] = lines + [f"{target} += add{i}" for i, (target, _) in enumerate(pairs)]
    functions = []
    for name, arguments, types, doc in _FUNCTIONS:
        body = bodies[name] or ["return None"]
        functions.append("\n".join([_decorator(types), f"def {name}({arguments}):", f'    """{doc}"""',
                                    *(f"    {line}" for line in body)]))
    energy = _assign(printer, ["energy"], [e.potential]) + ["return energy"]
    functions.append("\n".join([_decorator(f"float64({_V}, {_V})"), "def potential_energy(q, par):",
                                '    """Potential energy (J) of gravity and the linear springs."""',
                                *(f"    {line}" for line in energy)]))
    if e.user_source is None:
        user = _NO_USER_FORCE
    else:
        user = (e.user_imports + "\n" + e.user_source
                + "\n\nif not isinstance(user_force, _Dispatcher):\n    user_force = jit(" + repr(USER_FORCE_TYPES) + ", error_model='numpy')(user_force)\n")
    header = [
        f"# Generated by mbds {mbds_version()} (mbds.expr.dapbc_codegen) from a DAP_BC model. Do not edit:",
        "# the file is named after the hash of its text, and numba caches its machine code in __pycache__.",
        f"# kernel source {kernel_source_hash()}",
        "import math",
        "",
        "import numpy as np",
        "from numba.core.registry import CPUDispatcher as _Dispatcher",
        "",
        "from mbds.kernel.jit import jit",
        "",
        f"N = {e.n}  # coordinates (3 per body)",
        f"NC = {nc}  # constraint equations",
        "PROJECTION_TOLERANCE = 1e-12  # max |Phi| (m, rad) after a projection",
    ]
    return "\n".join(header) + "\n\n\n" + "\n\n\n".join(functions) + "\n\n" + user + "\n" + _BINDINGS


def compile_dapbc(expressions: DapbcExpressions, cache_dir: Path | None = None) -> ModuleType:
    """Store the module in the cache (default mbds.expr.cache.default_cache_dir) and import it."""
    source = generate_source(expressions)
    path = cache.store(source, Path(cache_dir) if cache_dir is not None else cache.default_cache_dir())
    return cache.load(path)
