"""Lagrange's equations of a declared model: M(q, t) q̈ = h(q, q̇, t), the mechanical energy,
and the position, velocity, acceleration, J and j of every dependent coordinate.

With T the kinetic energy, V the potential energy, D Rayleigh's dissipation function and
Q_k = ∂(δW)/∂(δq_k) the generalized forces of the virtual work (Pfeiffer and Glocker 1996,
ch. 2; the manual's ``EquationsOfMotion`` and ``MassMatrixAndHVector``):

    M_ik = ∂²T/∂q̇_i∂q̇_k,
    h_i = ∂T/∂q_i − ∂V/∂q_i + Q_i − ∂D/∂q̇_i − Σ_k ∂²T/∂q̇_i∂q_k q̇_k − ∂²T/∂q̇_i∂t,

which is d/dt ∂T/∂q̇_i − ∂T/∂q_i + ∂V/∂q_i + ∂D/∂q̇_i = Q_i with M q̈ moved to the left. A
dependent coordinate c(q, t) has J_k = ∂c/∂q_k and j = c̈ − J·q̈ (the manual's
``PrepareDependentCoordinates``, section 3.4.6).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from mbds.build.declarations import Declarations, Term, variation
from mbds.build.location import Location
from mbds.errors import ModelError
from mbds.expr import symbols as S

SINGULAR = 1e-12
"""Smallest eigenvalue of M at the start state, relative to the largest, that counts as regular."""


@dataclass
class DependentEquations:
    """A dependent coordinate: position, velocity, acceleration (functions of q(t) and t),
    J (one entry per generalized coordinate) and j, with c̈ = J·q̈ + j; ``start`` its position
    and velocity at the start state."""

    coordinate: sympy.Expr
    position: sympy.Expr
    velocity: sympy.Expr
    acceleration: sympy.Expr
    jacobian: list[sympy.Expr]
    scalar: sympy.Expr
    start: tuple[float, float]


@dataclass
class Equations:
    """The derived model: generalized coordinates q(t), M (n x n), h (n), the mechanical
    energy T + V (J), the dependent coordinates, the start state q0, qd0 and the values of the
    constants and mass properties."""

    coordinates: list[sympy.Expr]
    mass_matrix: list[list[sympy.Expr]]
    h_vector: list[sympy.Expr]
    energy: sympy.Expr
    dependent: list[DependentEquations]
    q0: np.ndarray
    qd0: np.ndarray
    values: dict[sympy.Symbol, float]


class _States:
    """Plain symbols for q, q̇, q̈ of the generalized coordinates and for the fixed body
    coordinates (whose derivatives are 0), and the maps both ways."""

    def __init__(self, coordinates: list[sympy.Expr], fixed: list[sympy.Expr]):
        self.q = [sympy.Symbol(f"q{k}", real=True) for k in range(len(coordinates))]
        self.qd = [sympy.Symbol(f"qd{k}", real=True) for k in range(len(coordinates))]
        self.qdd = [sympy.Symbol(f"qdd{k}", real=True) for k in range(len(coordinates))]
        self.fixed = {sympy.Symbol(f"fixed{k}", real=True): f for k, f in enumerate(fixed)}
        self.to_symbols, self.to_functions = {}, {}
        for c, q, qd, qdd in zip(coordinates, self.q, self.qd, self.qdd):
            for f, s in ((sympy.Derivative(c, (S.T, 2)), qdd), (sympy.Derivative(c, S.T), qd), (c, q)):
                self.to_symbols[f] = s
                self.to_functions[s] = f
        for s, f in self.fixed.items():
            self.to_symbols.update({sympy.Derivative(f, (S.T, 2)): 0, sympy.Derivative(f, S.T): 0, f: s})
            self.to_functions[s] = f

    def symbols(self, expr: sympy.Expr) -> sympy.Expr:
        return sympy.sympify(expr).xreplace(self.to_symbols)

    def functions(self, expr: sympy.Expr) -> sympy.Expr:
        return sympy.sympify(expr).xreplace(self.to_functions)

    def rate(self, expr: sympy.Expr) -> sympy.Expr:
        """The time derivative of an expression in these symbols."""
        return sympy.diff(expr, S.T) + sympy.Add(*(
            sympy.diff(expr, q) * qd + sympy.diff(expr, qd) * qdd for q, qd, qdd in zip(self.q, self.qd, self.qdd)
        ))


def tidy(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` as derived, with the factors common to its terms and to the sums inside each
    term pulled out (-½k(2a - 2b) is -k(a - b), -g m1 - g m2 is -g(m1 + m2)), and sin² + cos² = 1
    applied where it shortens it; energies written like the hand-made files thus give the same
    expressions."""
    expr = sympy.factor_terms(sympy.Add(*(sympy.factor_terms(term) for term in sympy.Add.make_args(expr))))
    if not expr.has(sympy.sin, sympy.cos):
        return expr
    simpler = sympy.factor_terms(sympy.trigsimp(sympy.expand(expr)))
    return simpler if sympy.count_ops(simpler) < sympy.count_ops(expr) else expr


def derive_equations(d: Declarations) -> Equations:
    """:class:`Equations` of the declarations; ModelError at the declaration that is wrong."""
    if not d.coordinates:
        raise ModelError("no generalized coordinates declared (builder.generalized(...))")
    if not d.kinetic:
        raise ModelError("no kinetic energy declared (builder.kinetic_energy(...))")
    coordinates = [c for c, _ in d.coordinates]
    definitions = _resolve_dependent(d, coordinates)
    states = _States(coordinates, _fixed(d, definitions))

    def expanded(term: Term, what: str, variations: bool = False) -> sympy.Expr:
        _check_names(term.expr, d, definitions, term.where, what, variations)
        return states.symbols(term.expr.subs(definitions).doit())

    kinetic = sympy.Add(*(expanded(t, "kinetic energy") for t in d.kinetic))
    potential = sympy.Add(*(_without_velocities(expanded(t, "potential energy"), states, t.where) for t in d.potential))
    dissipation = sympy.Add(*(expanded(t, "dissipation function") for t in d.dissipation))
    forces = _generalized_forces(d, definitions, coordinates, states, expanded)
    _check_every_coordinate_moves(d, states, kinetic, potential, dissipation, forces)

    n = len(coordinates)
    momenta = [sympy.diff(kinetic, states.qd[i]) for i in range(n)]
    mass = [[sympy.diff(momenta[i], states.qd[k]) for k in range(n)] for i in range(n)]
    if any(e.has(*states.qd) for row in mass for e in row):
        raise ModelError("the kinetic energy is not quadratic in the velocities (M depends on them)", *d.kinetic[0].where)
    h = []
    for i in range(n):
        coupling = sum((sympy.diff(momenta[i], states.q[k]) * states.qd[k] for k in range(n)), sympy.Integer(0))
        h.append(
            sympy.diff(kinetic, states.q[i]) - sympy.diff(potential, states.q[i]) + forces[i]
            - sympy.diff(dissipation, states.qd[i]) - coupling - sympy.diff(momenta[i], S.T)
        )
    values = _values(d, states)
    q0, qd0 = _start_state(d, coordinates)
    _check_regular(mass, states, q0, values, d)
    dependent = [
        _dependent_equations(c, definitions[c], states, q0, qd0, values)
        for c, _, _ in d.dependent
    ]
    return Equations(
        coordinates=coordinates,
        mass_matrix=[[states.functions(tidy(e)) for e in row] for row in mass],
        h_vector=[states.functions(tidy(e)) for e in h],
        energy=states.functions(tidy(kinetic + potential)),
        dependent=dependent,
        q0=q0,
        qd0=qd0,
        values=values,
    )


def _resolve_dependent(d: Declarations, coordinates: list[sympy.Expr]) -> dict[sympy.Expr, sympy.Expr]:
    """Each dependent coordinate as an expression of q(t) and t only (definitions that use
    other dependent coordinates substituted); ModelError for unknown names and cycles."""
    given = {c: (expr, where) for c, expr, where in d.dependent}
    resolved: dict[sympy.Expr, sympy.Expr] = {}

    def visit(c: sympy.Expr, chain: list[sympy.Expr]) -> sympy.Expr:
        if c in resolved:
            return resolved[c]
        expr, where = given[c]
        if c in chain:
            cycle = " -> ".join(S.display(x) for x in [*chain[chain.index(c):], c])
            raise ModelError(f"dependent coordinates define each other in a cycle: {cycle}", *where)
        _check_names(expr, d, given, where, f"definition of {S.display(c)}", False)
        if S.derivative_order(expr) > 0:
            raise ModelError(f"the definition of {S.display(c)} may not use velocities", *where)
        inner = {u: visit(u, [*chain, c]) for u in S.coordinates_in(expr) if u in given}
        resolved[c] = expr.subs(inner)
        return resolved[c]

    for c in given:
        visit(c, [])
    return resolved


def _check_names(expr, d: Declarations, dependent, where: Location, what: str, variations: bool) -> None:
    """Every name in ``expr`` is declared: ModelError naming the first that is not."""
    allowed = {S.T} | {S.constant(n) for n in d.constants}
    for body in d.bodies.values():
        if body.virtual_to is None:
            allowed |= {body.m, body.Jzz}
    moving = {c for c, _ in d.coordinates} | set(dependent)
    fixed = set(_fixed(d, dependent))
    if variations:
        allowed |= {variation(c) for c in moving}
    for s in sorted(expr.free_symbols - allowed, key=str):
        ref = S.reference(s)
        if s.name.startswith("δ") and variations:
            message = f"{s.name} varies a coordinate that is neither generalized nor dependent"
        elif ref is not None and ref.kind == "constant":
            message = f"undefined constant {S.display(s)} (declare it with builder.constant('{ref.name}', value))"
        elif ref is not None and ref.kind == "mass_property":
            message = f"{S.display(s)}: no body '{ref.body}' with a mass (declared bodies: {', '.join(d.bodies)})"
        else:
            message = f"undefined symbol '{s}'"
        raise ModelError(f"{what}: {message}", *where)
    for f in sorted(expr.atoms(AppliedUndef) - moving - fixed, key=str):
        ref = S.reference(f)
        if ref is None:
            message = f"undefined function '{f}'"
        elif ref.kind == "coordinate" and ref.body not in d.bodies:
            message = f"{S.display(f)}: no body '{ref.body}' is declared"
        elif ref.kind == "coordinate" and d.bodies[ref.body].virtual_to is not None:
            message = f"{S.display(f)} belongs to a virtual body, which has no coordinates"
        else:
            message = f"{S.display(f)} is neither a generalized nor a dependent coordinate"
        raise ModelError(f"{what}: {message}", *where)
    if S.derivative_order(expr) > 1:
        raise ModelError(f"{what} may not use accelerations", *where)


def _fixed(d: Declarations, dependent) -> list[sympy.Expr]:
    """Body coordinates x, y, Rz of non-virtual bodies that are neither generalized nor
    dependent: they stay at their start values (ground, walls, pivots)."""
    moving = {c for c, _ in d.coordinates} | set(dependent)
    every = [getattr(b, axis) for b in d.bodies.values() if b.virtual_to is None for axis in ("x", "y", "Rz")]
    return [c for c in every if c not in moving]


def _without_velocities(expr: sympy.Expr, states: _States, where: Location) -> sympy.Expr:
    if expr.has(*states.qd):
        raise ModelError("the potential energy may not depend on velocities", *where)
    return expr


def _generalized_forces(d, definitions, coordinates, states, expanded) -> list[sympy.Expr]:
    """Q_k: the coefficients of δq_k in the virtual work, dependent variations δc = Σ J_k δq_k."""
    deltas = [variation(c) for c in coordinates]
    through = {
        variation(c): sympy.Add(*(sympy.diff(states.symbols(expr), q) * dq for q, dq in zip(states.q, deltas)))
        for c, expr in definitions.items()
    }
    forces = [sympy.Integer(0)] * len(coordinates)
    for term in d.virtual_work:
        work = sympy.expand(expanded(term, "virtual work", variations=True).xreplace(through))
        parts = [sympy.diff(work, dq) for dq in deltas]
        rest = sympy.expand(work - sum(p * dq for p, dq in zip(parts, deltas)))
        if rest != 0 or any(p.has(*deltas) for p in parts):
            raise ModelError("the virtual work must be linear in the variations δq (a sum of force × δ(position))", *term.where)
        forces = [f + p for f, p in zip(forces, parts)]
    return forces


def _check_every_coordinate_moves(d, states, kinetic, potential, dissipation, forces) -> None:
    for k, (c, where) in enumerate(d.coordinates):
        used = [e for e in (kinetic, potential, dissipation, forces[k]) if e.has(states.q[k], states.qd[k])]
        if not used:
            raise ModelError(f"{S.display(c)} appears in no energy, dissipation or virtual work", *where)
        if not kinetic.has(states.qd[k]):
            raise ModelError(f"{S.display(c)} has no kinetic energy: its row of the mass matrix is zero", *where)


def _values(d: Declarations, states: _States) -> dict[sympy.Symbol, float]:
    """Constants, mass properties and fixed coordinates (their start values)."""
    values = {S.constant(n): v for n, (v, _) in d.constants.items()}
    for symbol, f in states.fixed.items():
        ref = S.reference(f)
        values[symbol] = d.bodies[ref.body].position[("x", "y", "Rz").index(ref.name)]
    for body in d.bodies.values():
        if body.virtual_to is None:
            values[body.m], values[body.Jzz] = body.mass_values()
    return values


def _start_state(d: Declarations, coordinates: list[sympy.Expr]) -> tuple[np.ndarray, np.ndarray]:
    """q0 and qd0: body coordinates from the bodies' start pose, free ones from builder.free."""
    q0, qd0 = np.zeros(len(coordinates)), np.zeros(len(coordinates))
    for k, c in enumerate(coordinates):
        ref = S.reference(c)
        if ref.kind == "generalized":
            q0[k], qd0[k] = d.free[ref.name][:2]
        else:
            body = d.bodies[ref.body]
            axis = ("x", "y", "Rz").index(ref.name)
            q0[k], qd0[k] = body.position[axis], body.velocity[axis]
    return q0, qd0


def _at_start(expr: sympy.Expr, states: _States, q0, qd0, values) -> float:
    point = {**values, S.T: 0.0, **dict(zip(states.q, q0)), **dict(zip(states.qd, qd0))}
    return float(expr.xreplace({k: sympy.Float(v) for k, v in point.items()}))


def _check_regular(mass, states: _States, q0, values, d: Declarations) -> None:
    """ModelError at the kinetic energy when M is singular at the start state."""
    numbers = np.array([[_at_start(e, states, q0, q0 * 0, values) for e in row] for row in mass])
    eigenvalues, vectors = np.linalg.eigh(numbers)
    if eigenvalues[-1] > 0 and eigenvalues[0] > SINGULAR * eigenvalues[-1]:
        return
    null = vectors[:, 0]
    involved = [S.display(c) for (c, _), v in zip(d.coordinates, null) if abs(v) > 0.1]
    raise ModelError(
        f"the mass matrix is singular at the start state (eigenvalues {eigenvalues[0]:.3g} to {eigenvalues[-1]:.3g}); "
        f"the motion along {', '.join(involved)} has no inertia",
        *d.kinetic[0].where,
    )


def _dependent_equations(c, position, states: _States, q0, qd0, values) -> DependentEquations:
    position = states.symbols(position)
    velocity = states.rate(position)
    acceleration = states.rate(velocity)
    jacobian = [sympy.diff(position, q) for q in states.q]
    scalar = acceleration.xreplace({qdd: 0 for qdd in states.qdd})
    start = (_at_start(position, states, q0, qd0, values), _at_start(velocity, states, q0, qd0, values))
    f = states.functions
    return DependentEquations(c, f(position), f(velocity), f(acceleration), [f(e) for e in jacobian], f(scalar), start)
