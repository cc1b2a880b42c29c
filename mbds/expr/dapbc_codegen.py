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

then the user force (compiled MATLAB subset or the model's Python function), each compiled for
one signature. :func:`compile_dapbc` binds the analyses of mbds.kernel.dapbc_analyses (compiled
once for all models) to these functions. Parameter values are not part of the text, so its hash
(the cache key) depends on the model's structure only; the kernel's source hash is part of it
too (a user force calls the kernel's library, mbds.kernel.dapbc_library).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType, SimpleNamespace

import sympy

from mbds._version import version as mbds_version
from mbds.expr import cache
from mbds.expr.codegen import _assign
from mbds.expr.printer import NumbaPrinter
from mbds.kernel.dapbc_analyses import ANALYSES
from mbds.kernel.dapbc_layout import DAPBC_FUNCTIONS
from mbds.kernel.function_table import address_table
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


_FUNCTIONS = (  # name, arguments, doc; signatures: mbds.kernel.dapbc_layout.DAPBC_FUNCTIONS
    ("constraints", "q, t, par, fv, out", "Constraint equations Phi into out."),
    ("jacobian", "q, t, par, fv, D", "Jacobian D = dPhi/dq into D."),
    ("velocity_rhs", "q, t, par, fv, out", "nu (D qd = nu) into out."),
    ("acceleration_rhs", "q, qd, t, par, fv, out", "gamma (D qdd = gamma) into out."),
    ("forces_before", "q, qd, t, par, fv, out", "Add the force elements before the user element to out."),
    ("forces_after", "q, qd, t, par, fv, out", "Add the force elements after the user element to out."),
)
USER_FORCE_TYPES = DAPBC_FUNCTIONS["user_force"]


#: explicit signatures (compiled when the module is imported, so that the kernel's analyses can
#: call them through their addresses) and IEEE arithmetic without exceptions, as mbds.expr.codegen


def _decorator(types: str) -> str:
    return f'@jit("{types}", error_model="numpy")'


#: after a user force's source: compiled for its one signature (a Python user force that is a numba
#: function already keeps its options)
_ONE_SIGNATURE = f'''

_options = user_force.targetoptions if isinstance(user_force, _Dispatcher) else {{}}
user_force = jit({USER_FORCE_TYPES!r}, **{{"error_model": "numpy", **_options}})(getattr(user_force, "py_func", user_force))
'''

_NO_USER_FORCE = f'''
{_decorator(USER_FORCE_TYPES)}
def user_force(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):
    """The model has no user force element (never called: data.has_user is 0)."""
    return None
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
    for name, arguments, doc in _FUNCTIONS:
        body = bodies[name] or ["return None"]
        functions.append("\n".join([_decorator(DAPBC_FUNCTIONS[name]), f"def {name}({arguments}):", f'    """{doc}"""',
                                    *(f"    {line}" for line in body)]))
    energy = _assign(printer, ["energy"], [e.potential]) + ["return energy"]
    functions.append("\n".join([_decorator(DAPBC_FUNCTIONS["potential_energy"]), "def potential_energy(q, par):",
                                '    """Potential energy (J) of gravity and the linear springs."""',
                                *(f"    {line}" for line in energy)]))
    if e.user_source is None:
        user = _NO_USER_FORCE
    else:
        user = e.user_imports + "\n" + e.user_source + _ONE_SIGNATURE
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
    ]
    return "\n".join(header) + "\n\n\n" + "\n\n\n".join(functions) + "\n\n" + user


def compile_dapbc(expressions: DapbcExpressions, cache_dir: Path | None = None) -> SimpleNamespace:
    """Store the module in the cache (default mbds.expr.cache.default_cache_dir), import it and
    return the analyses of mbds.kernel.dapbc_analyses bound to its functions (the same object
    for the same module): ``forward_dopri5``, ``forward_stiff``, ``post``, ``correct``,
    ``kinematic_state``, ``inverse_multipliers``, ``static_equilibrium``, called as the kernel's
    functions without their first two arguments (the function table and nc)."""
    source = generate_source(expressions)
    path = cache.store(source, Path(cache_dir) if cache_dir is not None else cache.default_cache_dir())
    return _bound(cache.load(path))


@functools.cache
def _bound(module: ModuleType) -> SimpleNamespace:
    """The kernel's DAP_BC analyses bound to the functions of ``module``."""
    table = address_table(module, DAPBC_FUNCTIONS)
    bound = SimpleNamespace(**{f.__name__: functools.partial(f, table, module.NC) for f in ANALYSES})
    bound.module = module  # (keeps the functions of the table alive)
    return bound
