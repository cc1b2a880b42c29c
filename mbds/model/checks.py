"""Checks of an assembled model that need its numbers: the mass matrix at the start state and
the contact laws at their start temperature (``mbds check``, and every run before it starts)."""

from __future__ import annotations

import math

import numpy as np

from mbds.errors import ModelError
from mbds.io.contacts import LAW_RULES, ContactLaw
from mbds.io.folder import ModelFiles
from mbds.io.ini import Located

SYMMETRY_TOLERANCE = 1e-9
"""Largest |M - Mᵀ| accepted, relative to the largest |M| entry."""


def check_mass_matrix(expressions, parameters, q0: np.ndarray, path) -> None:
    """The mass matrix at the start coordinates ``q0`` (t = 0) is symmetric positive definite;
    ModelError naming the ``.mmx`` file with its eigenvalues otherwise."""
    import sympy

    from mbds.expr import symbols as S
    from mbds.expr.model import code_vector, resolve

    n = len(q0)
    if n == 0:
        return
    resolved = resolve(expressions)
    values = {S.T: sympy.Float(0)}
    values.update(zip(code_vector("q", n), map(sympy.Float, q0)))
    values.update(zip(code_vector("p", len(parameters.values)), map(sympy.Float, parameters.values)))
    try:
        matrix = np.array([[float(e.xreplace(values)) for e in row] for row in resolved.mass_matrix])
    except (TypeError, ValueError):
        raise ModelError("the mass matrix is not a real number at the start state", path) from None
    check_matrix_at_start(matrix, q0, path)


def check_compiled_mass_matrix(compiled, parameters: np.ndarray, q0: np.ndarray, path) -> None:
    """:func:`check_mass_matrix` with the mass matrix of the compiled model (float64 arithmetic
    instead of sympy's), for a model assembled from the cache's record (:mod:`mbds.model.known`)."""
    if len(q0) == 0:
        return
    matrix = np.empty((len(q0), len(q0)))
    compiled.mass_matrix(np.ascontiguousarray(q0, dtype=float), 0.0, parameters, matrix)
    check_matrix_at_start(matrix, q0, path)


def check_matrix_at_start(matrix: np.ndarray, q0: np.ndarray, path) -> None:
    """The mass matrix ``matrix`` at the start coordinates ``q0`` is finite, symmetric and
    positive definite; ModelError naming ``path`` with its eigenvalues otherwise."""
    where = f"at the start state (q = {np.array2string(q0, precision=6)})"
    if not np.all(np.isfinite(matrix)):
        raise ModelError(f"the mass matrix is not finite {where}", path)
    scale = float(np.abs(matrix).max())
    if np.abs(matrix - matrix.T).max() > SYMMETRY_TOLERANCE * max(scale, 1e-300):
        raise ModelError(f"the mass matrix is not symmetric {where}", path)
    eigenvalues = np.linalg.eigvalsh(matrix)
    if not eigenvalues[0] > 1e-12 * max(scale, 1e-300):
        shown = ", ".join(f"{v:.6g}" for v in eigenvalues)
        raise ModelError(f"the mass matrix is not positive definite {where}: its eigenvalues are {shown}", path)


def law_value(item: Located, files: ModelFiles, temperature: float, path) -> float:
    """The value of a contact-law expression at ``temp = temperature``, ``vRel = 0``."""
    from mbds.expr import symbols as S
    from mbds.model.equations import ExpressionReader

    expr = ExpressionReader(files, []).read(item, path, contact=True)
    values = {S.constant(name): v for name, v in files.constants.values.items()}
    values.update({S.TEMP: temperature, S.VREL: 0.0})
    try:
        return float(expr.subs(values).evalf())
    except (TypeError, ValueError):
        return math.nan


def check_law_value(name: str, item: Located, files: ModelFiles, temperature: float, path) -> None:
    """Law field ``name`` (friction, restitution_normal, restitution_tangent) in its range at
    ``temp = temperature``, ``vRel = 0``; ModelError at ``item``'s line of ``path`` otherwise."""
    rule = LAW_RULES.get(name)
    if rule is None:
        return
    value = law_value(item, files, temperature, path)
    if not (math.isfinite(value) and rule.holds(value)):
        key = ContactLaw.__dataclass_fields__[name].metadata["key"]
        raise ModelError(f"{key} = {item.text} is {value:.6g} at temp = {temperature:g} (initialTemperature), "
                         f"vRel = 0: it {rule.says}", path, item.line)


def check_laws(laws: list[ContactLaw], files: ModelFiles) -> None:
    """Every contact law's friction and restitutions in range at its initial temperature."""
    for law in laws:
        for name in LAW_RULES:
            check_law_value(name, getattr(law, name), files, law.initial_temperature, files.contacts.path)
