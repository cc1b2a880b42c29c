"""Generate, cache and load the numba functions of a model's equations.

One Python module per model holds six functions compiled for float64 with explicit signatures
(so they compile, or load from numba's cache, when the module is imported). All arrays are
C-contiguous float64 and preallocated by the caller; ``n`` is the number of generalized
coordinates, ``m`` of dependent coordinates:

- ``mass_matrix(q, t, p, out)``: ``out[n, n]``
- ``h_vector(q, qd, t, p, out)``: ``out[n]``
- ``dependent_state(q, qd, qdd, t, p, pos, vel, acc)``: ``pos, vel, acc[m]``
- ``dependent_jacobian(q, qd, t, p, J, j)``: ``J[m, n]``, ``j[m]``
- ``mechanical_energy(q, qd, t, p) -> float`` (0.0 when the model defines none)
- ``contact_law(k, vRel, temp, p, out)``: ``out[4]`` = friction, restitutionNormal,
  restitutionTangent, parameterNi of contact-property set ``k`` (NaN for an unknown ``k``)

Arithmetic follows IEEE rules (no fast-math, no exceptions): a value such as ``0.5 - 1/vRel`` at
``vRel = 0`` comes out as inf or NaN, and the caller is expected to check it. Parameter values
are never part of the code, only their positions in ``p``; the text therefore depends on the
model's structure alone and its hash names the cached module.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import sympy

from mbds._version import __version__
from mbds.expr import cache
from mbds.expr.model import DependentCoordinate, ModelExpressions, resolve
from mbds.expr.printer import NumbaPrinter
from mbds.kernel.jit import kernel_source_hash

__all__ = ["CompiledModel", "DependentCoordinate", "ModelExpressions", "compile_model", "generate_source"]

_V = "float64[::1]"
_M = "float64[:, ::1]"
SIGNATURES = {
    "mass_matrix": f"void({_V}, float64, {_V}, {_M})",
    "h_vector": f"void({_V}, {_V}, float64, {_V}, {_V})",
    "dependent_state": f"void({_V}, {_V}, {_V}, float64, {_V}, {_V}, {_V}, {_V})",
    "dependent_jacobian": f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
    "mechanical_energy": f"float64({_V}, {_V}, float64, {_V})",
    "contact_law": f"void(int64, float64, float64, {_V}, {_V})",
}
_ARGUMENTS = {
    "mass_matrix": "q, t, p, out",
    "h_vector": "q, qd, t, p, out",
    "dependent_state": "q, qd, qdd, t, p, pos, vel, acc",
    "dependent_jacobian": "q, qd, t, p, J, j",
    "mechanical_energy": "q, qd, t, p",
    "contact_law": "k, vRel, temp, p, out",
}
_DOCS = {
    "mass_matrix": "Mass matrix M(q, t) into out[n, n].",
    "h_vector": "Right-hand side h(q, qd, t) of M qdd = h into out[n].",
    "dependent_state": "Position, velocity and acceleration of the dependent coordinates into pos, vel, acc[m].",
    "dependent_jacobian": "Jacobian J[m, n] and scalar j[m] of the dependent coordinates (acc = J qdd + j).",
    "mechanical_energy": "Mechanical energy (J).",
    "contact_law": "Friction, restitutionNormal, restitutionTangent, parameterNi of property set k into out[4].",
}
GENERATED_FUNCTIONS = tuple(SIGNATURES)


@dataclass(frozen=True)
class CompiledModel:
    """The compiled functions of one model (see the module documentation for their signatures)."""

    mass_matrix: Callable
    h_vector: Callable
    dependent_state: Callable
    dependent_jacobian: Callable
    mechanical_energy: Callable
    contact_law: Callable
    advance: Callable  # the time stepper bound to these functions (compiled on first call)
    n: int  # generalized coordinates
    m: int  # dependent coordinates
    n_contact_laws: int
    n_parameters: int  # length of p
    source_path: Path
    source_hash: str

    def dispatchers(self) -> dict[str, Callable]:
        """The six numba dispatchers by name."""
        return {name: getattr(self, name) for name in GENERATED_FUNCTIONS}


def compile_model(expressions: ModelExpressions, cache_dir: Path | None = None) -> CompiledModel:
    """Generate the model's module, store it in ``cache_dir`` and load it (compiling or loading from numba's cache).

    ``cache_dir`` defaults to :func:`mbds.expr.cache.default_cache_dir`.

    Raises :class:`~mbds.errors.ModelError` if an expression uses something its function does not
    receive (an unknown coordinate or constant, a velocity in the mass matrix, ...).
    """
    source = generate_source(expressions)
    path = cache.store(source, Path(cache_dir) if cache_dir is not None else cache.default_cache_dir())
    module = cache.load(path)
    return CompiledModel(
        **{name: getattr(module, name) for name in GENERATED_FUNCTIONS},
        advance=module.advance,
        n=module.N,
        m=module.M,
        n_contact_laws=module.CONTACT_LAWS,
        n_parameters=module.PARAMETERS,
        source_path=path,
        source_hash=cache.source_hash(source),
    )


def generate_source(expressions: ModelExpressions) -> str:
    """Text of the module for ``expressions``; the same structure always gives the same text."""
    r = resolve(expressions)
    printer = NumbaPrinter()
    m = len(r.positions)
    bodies = {
        "mass_matrix": _assign(
            printer,
            [f"out[{i}, {k}]" for i in range(r.n) for k in range(r.n)],
            [e for row in r.mass_matrix for e in row],
        ),
        "h_vector": _assign(printer, [f"out[{i}]" for i in range(r.n)], r.h_vector),
        "dependent_state": _assign(
            printer,
            [f"{array}[{i}]" for array in ("pos", "vel", "acc") for i in range(m)],
            [*r.positions, *r.velocities, *r.accelerations],
        ),
        "dependent_jacobian": _assign(
            printer,
            [f"J[{i}, {k}]" for i in range(m) for k in range(r.n)] + [f"j[{i}]" for i in range(m)],
            [*(e for row in r.jacobians for e in row), *r.jacobian_scalars],
        ),
        "mechanical_energy": [*_assign(printer, ["energy"], [r.mechanical_energy]), "return energy"],
        "contact_law": _contact_law_body(printer, r.contact_laws),
    }
    header = [
        f"# Generated by mbds {__version__} (mbds.expr.codegen) from a model's equations. Do not edit:",
        "# the file is named after the hash of its text, and numba caches its machine code in __pycache__.",
        *(f"# {symbol} = {_comment_text(name)}" for symbol, name in r.names.items()),
        "import math",
        "",
        "import numpy as np",
        "",
        "from mbds.kernel.jit import jit",
        "",
        f"N = {r.n}  # generalized coordinates",
        f"M = {m}  # dependent coordinates",
        f"CONTACT_LAWS = {len(r.contact_laws)}",
        f"PARAMETERS = {r.n_parameters}",
    ]
    functions = [_function(name, body) for name, body in bodies.items()]
    return "\n".join(header) + "\n\n\n" + "\n\n\n".join([*functions, _driver()]) + "\n"


def _driver() -> str:
    """The model's time stepper: the kernel's stepper bound to this module's functions.

    Compiled on first use and cached with the module. The kernel's source hash is part of the
    text, so a changed kernel gives a new module instead of stale cached machine code.
    """
    functions = ", ".join(GENERATED_FUNCTIONS)
    return "\n".join(
        [
            f"# kernel source {kernel_source_hash()}",
            "from mbds.kernel.stepper import advance as _advance  # noqa: E402",
            "",
            "",
            "@jit(cache=True, refcount=False)",
            "def advance(model, settings, until, clock, q, u, rng, point_loss, point_interval, history, events, ws):",
            '    """Integrate this model (see mbds.kernel.stepper.advance)."""',
            f"    return _advance({functions}, model, settings, until, clock, q, u, rng, point_loss, point_interval,",
            "                    history, events, ws)",
        ]
    )


def _comment_text(name: str) -> str:
    return ascii(name)[1:-1]


def _function(name: str, body: list[str]) -> str:
    lines = [
        f'@jit("{SIGNATURES[name]}", fastmath=False, error_model="numpy")',
        f"def {name}({_ARGUMENTS[name]}):",
        f'    """{_DOCS[name]}"""',
        *(f"    {line}" for line in body),
    ]
    return "\n".join(lines)


def _assign(
    printer: NumbaPrinter, targets: list[str], exprs: list[sympy.Expr], temporaries: Iterator | None = None
) -> list[str]:
    """Lines computing ``targets = exprs`` with common subexpressions computed once."""
    if not exprs:
        return []
    temporaries = temporaries if temporaries is not None else sympy.numbered_symbols("x")
    shared, reduced = sympy.cse(exprs, symbols=temporaries, order="canonical")
    lines = [f"{symbol} = {printer.doprint(value)}" for symbol, value in shared]
    lines += [f"{target} = {printer.doprint(value)}" for target, value in zip(targets, reduced, strict=True)]
    return lines


def _contact_law_body(printer: NumbaPrinter, laws: list[tuple[sympy.Expr, ...]]) -> list[str]:
    """An if/elif chain on k; temporaries are numbered across branches so none is reused."""
    temporaries = sympy.numbered_symbols("x")
    outputs = [f"out[{i}]" for i in range(4)]
    lines = []
    for k, law in enumerate(laws):
        lines.append(f"{'if' if k == 0 else 'elif'} k == {k}:")
        lines += [f"    {line}" for line in _assign(printer, outputs, list(law), temporaries)]
    unknown = [f"{target} = math.nan" for target in outputs]
    if not laws:
        return unknown
    return [*lines, "else:", *(f"    {line}" for line in unknown)]
