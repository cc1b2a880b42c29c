"""The symbols a DAP_BC model's expressions are written in, and body-fixed vectors in them.

Coordinates q = (x1, y1, phi1, x2, ...) and velocities qd are the symbols ``q[k]`` and
``qd[k]``; every number taken from an element's fields is a parameter symbol ``par[k]`` whose
value is kept beside it (so the generated code depends on the model's structure only and a
campaign can change the numbers without compiling again); the driver functions' values
f, f', f'' at the current time are ``fv[k, 0]``, ``fv[k, 1]``, ``fv[k, 2]``.  Units: SI.
"""

from __future__ import annotations

import sympy

from mbds.io.dapbc.records import DapbcModel


def rot90(v: sympy.Matrix) -> sympy.Matrix:
    """v turned by +90 degrees (the book's breve operator, DAP_BC's s_rot)."""
    return sympy.Matrix([-v[1], v[0]])


class Symbols:
    """The coordinate, velocity, parameter and function symbols of one model."""

    def __init__(self, model: DapbcModel):
        self.model = model
        self.n = 3 * model.nB
        self.q = sympy.Matrix([sympy.Symbol(f"q[{k}]") for k in range(self.n)])
        self.qd = sympy.Matrix([sympy.Symbol(f"qd[{k}]") for k in range(self.n)])
        self.values: list[float] = []
        self.labels: list[str] = []
        self.functions = [tuple(sympy.Symbol(f"fv[{k}, {d}]") for d in range(3)) for k in range(len(model.functs))]

    def parameter(self, value: float, label: str) -> sympy.Symbol:
        """A new parameter symbol of ``value`` (``label``: what it is, e.g. 'force 1 k')."""
        self.values.append(float(value))
        self.labels.append(label)
        return sympy.Symbol(f"par[{len(self.values) - 1}]")

    def vector(self, values, label: str) -> sympy.Matrix:
        """A 2-vector of parameters."""
        return sympy.Matrix([self.parameter(values[0], f"{label} x"), self.parameter(values[1], f"{label} y")])

    def position(self, body: int) -> sympy.Matrix:
        """r of body ``body`` (1-based; 0 is the ground, at the origin)."""
        if body == 0:
            return sympy.zeros(2, 1)
        k = 3 * (body - 1)
        return sympy.Matrix([self.q[k], self.q[k + 1]])

    def angle(self, body: int) -> sympy.Expr:
        """phi of body ``body`` (0 for the ground)."""
        return sympy.Integer(0) if body == 0 else self.q[3 * body - 1]

    def rotation(self, body: int) -> sympy.Matrix:
        """The rotation matrix A of body ``body``."""
        phi = self.angle(body)
        return sympy.Matrix([[sympy.cos(phi), -sympy.sin(phi)], [sympy.sin(phi), sympy.cos(phi)]])

    def point(self, index: int) -> tuple[int, sympy.Matrix]:
        """(body, world position r + A s'P) of the 1-based point ``index``."""
        point = self.model.points[index - 1]
        local = self.vector(point.sPlocal, f"point {index} sPlocal")
        return point.Bindex, self.position(point.Bindex) + self.rotation(point.Bindex) * local

    def unit(self, index: int) -> tuple[int, sympy.Matrix]:
        """(body, world components A u') of the 1-based unit vector ``index``."""
        u = self.model.uvectors[index - 1]
        return u.Bindex, self.rotation(u.Bindex) * self.vector(u.ulocal, f"unit vector {index} ulocal")

    def rate(self, expr):
        """d/dt of an expression of q (not of time explicitly): its Jacobian times qd."""
        matrix = sympy.Matrix(expr) if not isinstance(expr, sympy.Matrix) else expr
        return matrix.jacobian(self.q) * self.qd
