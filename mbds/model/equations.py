"""The model's expressions: parsed, checked against the model, and gathered for compilation.

Every expression is parsed with its file and line, and every name it uses is checked: constants
must be in the ``.cns`` file, bodies in the world, free coordinates in the ``.gc`` file;
``temp`` and ``vRel`` only appear in contact-property functions. The parameter array ``p`` of the
compiled functions holds, in this order: the constants (``.cns`` order), each non-virtual
body's mass and Jzz, the values of fixed pose coordinates, and the numbers written in the contact
laws (see :func:`lift_law_numbers`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import sympy

from mbds.errors import ModelError, warn
from mbds.expr import symbols as S
from mbds.expr.codegen import DependentCoordinate, ModelExpressions
from mbds.expr.parse import parse_expression
from mbds.io.contacts import ContactLaw
from mbds.io.coordinates import CoordinateName
from mbds.io.folder import ModelFiles
from mbds.io.ini import Located
from mbds.model.bodies import FIXED, POSE, Body
from mbds.model.known import base_parameters
from mbds.model.system import Parameters


def coordinate_symbol(name: CoordinateName) -> sympy.Expr:
    """The sympy function of time that stands for a coordinate of the files."""
    if name.kind == "g":
        return S.generalized(name.name)
    return S.body_coordinate(name.name, name.coordinate)


def build_parameters(files: ModelFiles, bodies: list[Body]) -> tuple[Parameters, dict]:
    """The parameter array and the fixed-coordinate substitutions (coordinate -> p symbol)."""
    names = [S.constant(name) for name in files.constants.values]
    for body in bodies:
        if not body.virtual:
            names += [S.mass_property(body.name, "m"), S.mass_property(body.name, "Jzz")]
    fixed = {}
    for body in bodies:
        if body.virtual:
            continue
        for axis, coordinate in enumerate(POSE):
            if body.binding[axis] == FIXED:
                symbol = sympy.Symbol(f"fixed`{body.name}`{coordinate}", real=True)
                names.append(symbol)
                fixed[S.body_coordinate(body.name, coordinate)] = symbol
    values = np.array(base_parameters(files, bodies), dtype=float)
    return Parameters(names, values, len(files.constants.values)), fixed


_TOO_HIGH = {
    0: "a velocity is not allowed here (mass matrix, dependent-coordinate position)",
    1: "an acceleration is not allowed here (only a dependent coordinate's acceleration may use one)",
    2: "a third time derivative is not allowed",
}


class ExpressionReader:
    """Parses located expressions of one model and checks the names they use."""

    def __init__(self, files: ModelFiles, bodies: list[Body]):
        self.separator = files.separator
        self.constants = set(files.constants.values)
        self.bodies = {b.name: b for b in bodies}
        self.free = {c.name for c in files.coordinates.coordinates if c.kind == "g"}
        self.free |= {c.coordinate.name for c in files.dependent.coordinates if c.coordinate.kind == "g"}

    def read(self, item: Located, path: Path | None, *, contact: bool = False, constant_only: bool = False,
             max_order: int = 1):
        """The sympy expression of ``item``, or a :class:`ModelError` at its file and line;
        ``max_order`` is the highest time derivative of a coordinate it may use."""
        expr = parse_expression(item.text, file=path, line=item.line, decimal_separator=self.separator)
        for obj in expr.free_symbols | expr.atoms(sympy.core.function.AppliedUndef):
            self._check(S.reference(obj), obj, path, item.line, contact, constant_only)
        if S.derivative_order(expr) > max_order:
            raise ModelError(_TOO_HIGH[max_order], path, item.line)
        return expr

    def _check(self, ref, obj, path, line, contact, constant_only):
        if ref is None:
            raise ModelError(f"unknown name '{obj}'", path, line)
        shown = S.display(obj)
        if ref.kind == "constant":
            if ref.name not in self.constants:
                raise ModelError(f"unknown constant {shown} (not in the .cns file)", path, line)
            return
        if ref.kind == "variable":
            if ref.name in ("temp", "vRel") and not contact:
                raise ModelError(f"'{ref.name}' can only be used in contact-property functions", path, line)
            if constant_only and ref.name != "temp" and ref.name != "vRel":
                raise ModelError(f"'{ref.name}' cannot be used here (only constants)", path, line)
            return
        if constant_only or contact:
            raise ModelError(f"{shown} cannot be used here (only constants{', temp and vRel' if contact else ''})", path, line)
        if ref.kind == "generalized":
            if ref.name not in self.free:
                raise ModelError(f"{shown} is not a coordinate of the .gc or .dc file", path, line)
            return
        body = self.bodies.get(ref.body)
        if body is None:
            raise ModelError(f"{shown} names no body (bodies: {', '.join(self.bodies)})", path, line)
        if body.virtual:
            raise ModelError(f"{shown} belongs to a virtual body, which has no coordinates or mass", path, line)
        if ref.kind == "coordinate" and ref.name not in POSE:
            raise ModelError(f"{shown}: a planar model moves bodies in x, y and Rz only", path, line)


def gather_expressions(files: ModelFiles, bodies: list[Body], laws: list[ContactLaw]) -> tuple[ModelExpressions, Parameters]:
    """The model's expressions for compilation (contact laws in the order of ``laws``) and its
    parameters."""
    reader = ExpressionReader(files, bodies)
    params, fixed = build_parameters(files, bodies)
    n = files.world.settings.number_of_coordinates
    gc = files.coordinates
    if len(gc.coordinates) != n:
        raise ModelError(
            f"the .gc file lists {len(gc.coordinates)} coordinates but numberOfGeneralizedCoordinates is {n}",
            gc.path,
            gc.lines[-1] if gc.lines else 1,
        )
    coordinates = [coordinate_symbol(c) for c in gc.coordinates]
    mmx = files.mass_matrix
    mass_matrix = [[reader.read(e, mmx.path, max_order=0) for e in row] for row in mmx.rows]
    hv = files.h_vector
    h_vector = [reader.read(e, hv.path) for e in hv.expressions]
    energy = files.energy
    mechanical_energy = reader.read(energy.expressions[0], energy.path) if energy.expressions else None
    dependent = [_dependent(c, coordinates, reader, files.dependent.path) for c in files.dependent.coordinates]
    contact_laws = []
    for law in laws:
        items = (law.friction, law.restitution_normal, law.restitution_tangent, law.parameter_ni)
        contact_laws.append(tuple(reader.read(x, files.contacts.path, contact=True) for x in items))
        if not contact_laws[-1][3].is_zero:
            warn(
                "parameterNi is not supported: the impact law uses restitutionNormal and "
                "restitutionTangent only, and treats parameterNi as 0 (see docs/theory.md)",
                files.contacts.path,
                law.parameter_ni.line,
            )
    contact_laws = lift_law_numbers(contact_laws, params)
    expressions = ModelExpressions(
        coordinates=coordinates,
        parameters=params.symbols,
        fixed=fixed,
        dependent=dependent,
        mass_matrix=mass_matrix,
        h_vector=h_vector,
        mechanical_energy=mechanical_energy,
        contact_laws=contact_laws,
    )
    return expressions, params


def lift_law_numbers(laws: list[tuple], params: Parameters) -> list[tuple]:
    """The contact laws with their numbers replaced by parameters appended to ``params``.

    A law that is a number (``friction = 0.3``, ``restitutionNormal = 1``) and every
    floating-point number inside a law (``0.3 - 0.001*temp``) becomes an entry of ``p``, so
    models that differ only in these numbers generate the same code and share one compiled
    module. Integers and fractions inside a law (powers, ``1/2``) stay in the code.
    """
    symbols, values, lifted = [], [], []
    for k, law in enumerate(laws):
        fields = []
        for field, expr in enumerate(law):
            numbers = [expr] if expr.is_Number else [a for a in sympy.preorder_traversal(expr) if a.is_Float]
            replace = {}
            for number in dict.fromkeys(numbers):
                replace[number] = sympy.Symbol(f"law`{k + 1}`{field}`{len(replace)}", real=True)
                symbols.append(replace[number])
                values.append(float(number))
            fields.append(expr.xreplace(replace))
        lifted.append(tuple(fields))
    params.symbols.extend(symbols)
    params.values = np.concatenate([params.values, np.array(values, dtype=float)])
    return lifted


def _dependent(c, coordinates, reader: ExpressionReader, path) -> DependentCoordinate:
    """A dependent coordinate; velocity, acceleration, J and j are derived from the position
    where the file leaves them out, and checked against it where the file gives them."""
    position = reader.read(c.definition[0], path, max_order=0)
    velocity_d = sympy.diff(position, S.T)
    acceleration_d = sympy.diff(velocity_d, S.T)
    jacobian_d = [sympy.diff(position, q) for q in coordinates]
    scalar_d = acceleration_d.subs({sympy.Derivative(q, (S.T, 2)): 0 for q in coordinates})
    if len(c.definition) == 3:
        velocity = reader.read(c.definition[1], path)
        acceleration = reader.read(c.definition[2], path, max_order=2)
    else:
        velocity, acceleration = velocity_d, acceleration_d
    if c.jacobian is not None:
        if len(c.jacobian) != len(coordinates):
            raise ModelError(
                f"%%J of {c.coordinate} has {len(c.jacobian)} entries, expected {len(coordinates)} (one per generalized coordinate)",
                path,
                c.line,
            )
        jacobian = [reader.read(e, path) for e in c.jacobian]
    else:
        jacobian = jacobian_d
    scalar = reader.read(c.jacobian_scalar, path) if c.jacobian_scalar is not None else scalar_d
    _warn_if_inconsistent(c, coordinates, (velocity, acceleration, jacobian, scalar), (velocity_d, acceleration_d, jacobian_d, scalar_d), path)
    return DependentCoordinate(coordinate_symbol(c.coordinate), position, velocity, acceleration, jacobian, scalar)


def _warn_if_inconsistent(c, coordinates, given, derived, path) -> None:
    """Warn when the given velocity, acceleration, J or j differ from those derived from the
    position, compared at a fixed pseudo-random state of every name they use."""
    rng = np.random.default_rng(12345)
    flat_given = [given[0], given[1], *given[2], given[3]]
    flat_derived = [derived[0], derived[1], *derived[2], derived[3]]
    labels = ["velocity", "acceleration", *(f"J[{k}]" for k in range(len(given[2]))), "j"]
    atoms = set()
    for e in flat_given + flat_derived:
        atoms |= e.atoms(sympy.Derivative) | e.atoms(sympy.core.function.AppliedUndef) | e.free_symbols
    values = {a: sympy.Float(rng.uniform(0.3, 1.1)) for a in sorted(atoms, key=str)}
    for label, g, d in zip(labels, flat_given, flat_derived):
        try:
            gv = complex(g.subs(values).evalf())
            dv = complex(d.subs(values).evalf())
        except (TypeError, ValueError):  # not a finite number at that state
            continue
        if abs(gv - dv) > 1e-8 * max(1.0, abs(gv), abs(dv)):
            warn(f"{label} of {c.coordinate} differs from the one derived from its position", path, c.line)
