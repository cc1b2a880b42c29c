"""The symbolic description of a model's equations, and its reduction to code symbols.

:func:`resolve` replaces every coordinate, derivative and parameter of a
:class:`ModelExpressions` by the names the generated code uses (``q[k]``, ``qd[k]``,
``qdd[k]``, ``p[i]``, ``t``, ``vRel``, ``temp``) and checks that each expression uses only what
its generated function receives.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy
from sympy.core.function import AppliedUndef

from mbds.errors import ModelError
from mbds.expr.symbols import TEMP, VREL, T, coordinates_in, derivative_order, display

CONTACT_LAW_FIELDS = ("friction", "restitutionNormal", "restitutionTangent", "parameterNi")


@dataclass
class DependentCoordinate:
    """A coordinate given by expressions in the generalized ones (a ``.dc`` entry).

    Its acceleration is ``jacobian · q̈ + jacobian_scalar``; only ``acceleration`` may use
    second derivatives.
    """

    coordinate: sympy.Expr
    position: sympy.Expr
    velocity: sympy.Expr
    acceleration: sympy.Expr
    jacobian: list[sympy.Expr]  # n entries, one per generalized coordinate
    jacobian_scalar: sympy.Expr


@dataclass
class ModelExpressions:
    """Everything symbolic a model needs, in the canonical objects of :mod:`mbds.expr.symbols`."""

    coordinates: list[sympy.Expr]  # the n generalized coordinates q_k(t), in order
    parameters: list[sympy.Symbol]  # order of the parameter array p
    fixed: dict[sympy.Expr, sympy.Expr]  # coordinate -> value in parameters; derivatives are 0
    dependent: list[DependentCoordinate]
    mass_matrix: list[list[sympy.Expr]]  # n x n
    h_vector: list[sympy.Expr]  # n
    mechanical_energy: sympy.Expr | None
    contact_laws: list[tuple[sympy.Expr, sympy.Expr, sympy.Expr, sympy.Expr]]  # see CONTACT_LAW_FIELDS


@dataclass
class Resolved:
    """The expressions of :class:`ModelExpressions` written in code symbols, ready to print."""

    n: int
    n_parameters: int
    mass_matrix: list[list[sympy.Expr]]
    h_vector: list[sympy.Expr]
    positions: list[sympy.Expr]
    velocities: list[sympy.Expr]
    accelerations: list[sympy.Expr]
    jacobians: list[list[sympy.Expr]]
    jacobian_scalars: list[sympy.Expr]
    mechanical_energy: sympy.Expr
    contact_laws: list[tuple[sympy.Expr, ...]]
    names: dict[sympy.Symbol, str]  # code symbol -> MBDS spelling, for comments


def code_vector(name: str, size: int) -> list[sympy.Symbol]:
    """Symbols printed as ``name[0]``, ``name[1]``, ..."""
    return [sympy.Symbol(f"{name}[{i}]", real=True) for i in range(size)]


def _derivative(coordinate: sympy.Expr, order: int) -> sympy.Expr:
    return sympy.Derivative(coordinate, (T, order)) if order else coordinate


class _Resolver:
    def __init__(self, expressions: ModelExpressions):
        self.x = expressions
        self.n = len(expressions.coordinates)
        self.q, self.qd, self.qdd = (code_vector(v, self.n) for v in ("q", "qd", "qdd"))
        self.p = code_vector("p", len(expressions.parameters))
        self.names: dict[sympy.Symbol, str] = {}
        self.rules: dict[sympy.Basic, sympy.Expr] = {}
        self._check_unique()
        for k, coordinate in enumerate(expressions.coordinates):
            for order, symbol in enumerate((self.q[k], self.qd[k], self.qdd[k])):
                self.rules[_derivative(coordinate, order)] = symbol
                self.names[symbol] = display(_derivative(coordinate, order))
        for i, parameter in enumerate(expressions.parameters):
            self.rules[parameter] = self.p[i]
            self.names[self.p[i]] = display(parameter)
        for coordinate, value in expressions.fixed.items():
            where = f"fixed value of {display(coordinate)}"
            self.rules[coordinate] = self.substitute(value, where, allowed=set(self.p))
            self.rules[_derivative(coordinate, 1)] = sympy.Integer(0)
            self.rules[_derivative(coordinate, 2)] = sympy.Integer(0)

    def _check_unique(self) -> None:
        x = self.x
        seen: set[sympy.Basic] = set()
        for item in [*x.coordinates, *(d.coordinate for d in x.dependent), *x.fixed, *x.parameters]:
            if item in seen:
                raise ModelError(f"{display(item)} is declared twice (generalized, dependent, fixed or parameter)")
            seen.add(item)

    def substitute(self, expr: sympy.Expr, where: str, allowed: set[sympy.Symbol], max_order: int = 1) -> sympy.Expr:
        """Rewrite ``expr`` in code symbols; ModelError if it uses anything outside ``allowed``.

        ``where`` names the expression in messages; ``max_order`` is the highest time derivative
        it may use.
        """
        expr = sympy.sympify(expr)
        if derivative_order(expr) > max_order:
            worst = max(expr.atoms(sympy.Derivative), key=lambda d: d.derivative_count)
            raise ModelError(f"{where} may not use {display(worst)} (derivatives of order above {max_order})")
        result = expr.xreplace(self.rules)
        derivatives = result.atoms(sympy.Derivative)
        functions = result.atoms(AppliedUndef) - {d.expr for d in derivatives}
        strays = {s for s in result.free_symbols if s not in self.names and s not in (T, TEMP, VREL)}
        unknown = sorted(display(a) for a in derivatives | functions | strays)
        if unknown:
            raise ModelError(f"{where} uses unknown {', '.join(unknown)} (not a coordinate or parameter of the model)")
        forbidden = sorted(self.names.get(s, str(s)) for s in result.free_symbols - allowed)
        if forbidden:
            raise ModelError(f"{where} may not depend on {', '.join(forbidden)}")
        return result

    def dependent_rules(self) -> None:
        """Add the rules for dependent coordinates, resolving those that use each other."""
        by_coordinate = {d.coordinate: d for d in self.x.dependent}
        done: set[sympy.Expr] = set()
        chain: list[sympy.Expr] = []
        allowed = {T, *self.q, *self.qd, *self.p}

        def visit(d: DependentCoordinate) -> None:
            if d.coordinate in done:
                return
            if d.coordinate in chain:
                cycle = " -> ".join(display(c) for c in [*chain[chain.index(d.coordinate) :], d.coordinate])
                raise ModelError(f"dependent coordinates depend on each other in a cycle: {cycle}")
            chain.append(d.coordinate)
            kinematics = (d.position, d.velocity, d.acceleration)
            used = set().union(*(coordinates_in(sympy.sympify(e)) for e in kinematics))
            for other in sorted(used, key=sympy.default_sort_key):
                if other in by_coordinate:
                    visit(by_coordinate[other])
            name = display(d.coordinate)
            for order, (what, expr) in enumerate(zip(("position", "velocity", "acceleration"), kinematics)):
                extra = set(self.qdd) if order == 2 else set()
                self.rules[_derivative(d.coordinate, order)] = self.substitute(
                    expr, f"{what} of dependent coordinate {name}", allowed | extra, max_order=max(order, 1)
                )
            chain.pop()
            done.add(d.coordinate)

        for d in self.x.dependent:
            visit(d)


def resolve(expressions: ModelExpressions) -> Resolved:
    """Substitute coordinates, derivatives and parameters by code symbols and validate the model."""
    x = expressions
    r = _Resolver(x)
    _check_shapes(x, r.n)
    r.dependent_rules()
    positions = {T, *r.q, *r.p}
    states = positions | set(r.qd)
    contact = {TEMP, VREL, *r.p}
    sub = r.substitute
    mass_matrix = [
        [sub(e, f"mass matrix entry ({i + 1}, {k + 1})", positions, max_order=0) for k, e in enumerate(row)]
        for i, row in enumerate(x.mass_matrix)
    ]
    jacobians = [
        [sub(e, f"Jacobian entry {k + 1} of {display(d.coordinate)}", states) for k, e in enumerate(d.jacobian)]
        for d in x.dependent
    ]
    energy = x.mechanical_energy if x.mechanical_energy is not None else sympy.Integer(0)
    laws = [
        tuple(sub(e, f"{field} of contact properties {k + 1}", contact) for field, e in zip(CONTACT_LAW_FIELDS, law))
        for k, law in enumerate(x.contact_laws)
    ]
    kinematics = [[r.rules[_derivative(d.coordinate, order)] for d in x.dependent] for order in range(3)]
    return Resolved(
        n=r.n,
        n_parameters=len(x.parameters),
        mass_matrix=mass_matrix,
        h_vector=[sub(e, f"h vector entry {i + 1}", states) for i, e in enumerate(x.h_vector)],
        positions=kinematics[0],
        velocities=kinematics[1],
        accelerations=kinematics[2],
        jacobians=jacobians,
        jacobian_scalars=[
            sub(d.jacobian_scalar, f"Jacobian scalar of {display(d.coordinate)}", states) for d in x.dependent
        ],
        mechanical_energy=sub(energy, "mechanical energy", states),
        contact_laws=laws,
        names={s: r.names[s] for s in [*r.q, *r.p]},
    )


def _check_shapes(x: ModelExpressions, n: int) -> None:
    if len(x.mass_matrix) != n or any(len(row) != n for row in x.mass_matrix):
        raise ModelError(f"the mass matrix must be {n} x {n} (one row and column per generalized coordinate)")
    if len(x.h_vector) != n:
        raise ModelError(f"the h vector must have {n} entries, not {len(x.h_vector)}")
    for d in x.dependent:
        if len(d.jacobian) != n:
            name = display(d.coordinate)
            raise ModelError(f"the Jacobian vector of {name} must have {n} entries, not {len(d.jacobian)}")
    if any(len(law) != len(CONTACT_LAW_FIELDS) for law in x.contact_laws):
        raise ModelError(f"a contact law has {len(CONTACT_LAW_FIELDS)} expressions: {', '.join(CONTACT_LAW_FIELDS)}")
