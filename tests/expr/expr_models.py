"""A woodpecker-like test model: ring y and Rz on a fixed x; bird Rz, with bird x and y dependent."""

from __future__ import annotations

import sympy

from mbds.expr.codegen import DependentCoordinate, ModelExpressions
from mbds.expr.parse import parse_expression
from mbds.expr.symbols import body_coordinate, constant, mass_property

COORDINATES = [("ring", "y"), ("ring", "Rz"), ("bird", "Rz")]
CONSTANTS = ["lM", "lG", "g", "spring", "k", "ringx", "a"]
MASS = [("ring", "m"), ("ring", "Jzz"), ("bird", "m"), ("bird", "Jzz")]

# bird x and bird y: position, velocity, acceleration, Jacobian vector, Jacobian scalar
DEPENDENT = {
    "x": (
        "b'ring'x[t] + c'lM Cos[b'ring'Rz[t]] + c'lG*Cos[b`bird`Rz[t]]",
        "-(c'lM Sin[b'ring'Rz[t]] b'ring'Rz'[t]) - c'lG Sin[b'bird'Rz[t]] Derivative[1][b'bird'Rz][t]",
        "-c'lM (Sin[b'ring'Rz[t]] b'ring'Rz''[t] + Cos[b'ring'Rz[t]] b'ring'Rz'[t]^2)"
        " - c'lG (Sin[b'bird'Rz[t]] Derivative[2][b'bird'Rz][t] + Cos[b'bird'Rz[t]] Derivative[1][b'bird'Rz][t]^2)",
        ["0", "-(c'lM*Sin[b'ring'Rz[t]])", "-(c'lG*Sin[b'bird'Rz[t]])"],
        "-(c'lM*Cos[b'ring'Rz[t]]*Derivative[1][b'ring'Rz][t]^2)"
        " - c'lG*Cos[b'bird'Rz[t]]*Derivative[1][b'bird'Rz][t]^2",
    ),
    "y": (
        "b'ring'y[t] + c'lM Sin[b'ring'Rz[t]] + c'lG Sin[b'bird'Rz[t]]",
        "b'ring'y'[t] + c'lM Cos[b'ring'Rz[t]] b'ring'Rz'[t] + c'lG Cos[b'bird'Rz[t]] b'bird'Rz'[t]",
        "b'ring'y''[t] + c'lM (Cos[b'ring'Rz[t]] b'ring'Rz''[t] - Sin[b'ring'Rz[t]] b'ring'Rz'[t]^2)"
        " + c'lG (Cos[b'bird'Rz[t]] b'bird'Rz''[t] - Sin[b'bird'Rz[t]] b'bird'Rz'[t]^2)",
        ["1", "c'lM Cos[b'ring'Rz[t]]", "c'lG Cos[b'bird'Rz[t]]"],
        "-(c'lM Sin[b'ring'Rz[t]] b'ring'Rz'[t]^2) - c'lG Sin[b'bird'Rz[t]] b'bird'Rz'[t]^2",
    ),
}

ENERGY = (
    "(b'ring'm b'ring'y'[t]^2 + b'ring'Jzz b'ring'Rz'[t]^2"
    " + b'bird'm (Derivative[1][b'bird'x][t]^2 + Derivative[1][b'bird'y][t]^2) + b'bird'Jzz b'bird'Rz'[t]^2)/2"
    " + c'g (b'ring'm b'ring'y[t] + b'bird'm b'bird'y[t]) + c'spring (b'bird'Rz[t] - b'ring'Rz[t])^2/2"
    " + c'k b'bird'x[t]^2/2"
)

CONTACT_LAWS = [
    ("0.5-1/vRel", "0.5 - 1/temp", "0.5", "0"),
    ("0.3", "Max[0, 0.9 - c'a temp]", "c'a vRel", "Sqrt[vRel] + Exp[-temp/100]"),
]


def parse(text: str) -> sympy.Expr:
    return parse_expression(text, file="woodpecker", line=1)


def expressions() -> ModelExpressions:
    """The model; M and h are projected from body masses (M = Σ Bᵀ m B, h = Σ Bᵀ (F - m β))."""
    q = [body_coordinate(b, c) for b, c in COORDINATES]
    n = len(q)
    dependent = [
        DependentCoordinate(
            coordinate=body_coordinate("bird", axis),
            position=parse(pos),
            velocity=parse(vel),
            acceleration=parse(acc),
            jacobian=[parse(e) for e in jac],
            jacobian_scalar=parse(scalar),
        )
        for axis, (pos, vel, acc, jac, scalar) in DEPENDENT.items()
    ]
    jx, jy = (d.jacobian for d in dependent)
    sx, sy = (d.jacobian_scalar for d in dependent)
    m_ring, j_ring, m_bird, j_bird = (mass_property(b, p) for b, p in MASS)
    inertia = [m_ring, j_ring, j_bird]
    mass_matrix = [
        [(inertia[i] if i == k else 0) + m_bird * (jx[i] * jx[k] + jy[i] * jy[k]) for k in range(n)] for i in range(n)
    ]
    twist = parse("b'bird'Rz[t] - b'ring'Rz[t]")
    force_x = parse("-c'k b'bird'x[t]") - m_bird * sx  # spring on the bird's x, and inertia of its motion
    force_y = parse("-c'g b'bird'm") - m_bird * sy
    h_vector = [jx[i] * force_x + jy[i] * force_y for i in range(n)]
    h_vector[0] += parse("-c'g b'ring'm")
    h_vector[1] += constant("spring") * twist
    h_vector[2] -= constant("spring") * twist
    return ModelExpressions(
        coordinates=q,
        parameters=[constant(c) for c in CONSTANTS] + [mass_property(b, p) for b, p in MASS],
        fixed={body_coordinate("ring", "x"): constant("ringx")},
        dependent=dependent,
        mass_matrix=mass_matrix,
        h_vector=h_vector,
        mechanical_energy=parse(ENERGY),
        contact_laws=[tuple(parse(e) for e in law) for law in CONTACT_LAWS],
    )
