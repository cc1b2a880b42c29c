"""DAP_BC's joints and drivers (manual Table B.5; the book's Sec. 7.3-7.4), one small class per
type, registered by its type name.  Each emits its constraint equations Phi(q, f(t)) = 0 as
sympy expressions, in DAP_BC's row order and sign; the Jacobian, nu and gamma are derived from
them (mbds.model.dapbc.system)."""

from __future__ import annotations

import sympy

from mbds.io.dapbc.records import Joint
from mbds.model.dapbc.registry import registrar
from mbds.model.dapbc.symbolic import Symbols, rot90

JOINTS: dict[str, type["JointElement"]] = {}
register_joint = registrar(JOINTS)


class JointElement:
    """One joint of the model: ``rows`` gives its constraint expressions and ``names`` what each is."""

    type_name = ""
    names: tuple[str, ...] = ()

    def __init__(self, joint: Joint, index: int, initial: dict):
        self.joint, self.index, self.initial = joint, index, initial

    def rows(self, s: Symbols) -> list[sympy.Expr]:
        raise NotImplementedError

    def par(self, s: Symbols, name: str) -> sympy.Symbol:
        return s.parameter(getattr(self.joint, name), f"joint {self.index} {name}")

    def distance(self, s: Symbols) -> sympy.Matrix:
        """d = rPi - rPj (pointing to point iPindex)."""
        return s.point(self.joint.iPindex)[1] - s.point(self.joint.jPindex)[1]


@register_joint("rev")
class Revolute(JointElement):
    """Pin joint: the points Pi and Pj coincide: Phi = rPi - rPj (2 rows, x and y)."""

    names = ("x", "y")

    def rows(self, s):
        return list(self.distance(s))


@register_joint("tran")
class Translational(JointElement):
    """Sliding joint: Phi = (u_i breve . d, u_i breve . u_j) (book Eq. 7.29)."""

    names = ("normal", "angle")

    def rows(self, s):
        normal = rot90(s.unit(self.joint.iUindex)[1])
        return [(normal.T * self.distance(s))[0], (normal.T * s.unit(self.joint.jUindex)[1])[0]]


@register_joint("rev-rev")
class RevRev(JointElement):
    """Massless link of length L between Pi and Pj: Phi = (d.d - L^2)/2."""

    names = ("length",)

    def rows(self, s):
        d = self.distance(s)
        return [((d.T * d)[0] - self.par(s, "L") ** 2) / 2]


@register_joint("rev-tran")
class RevTran(JointElement):
    """Revolute-translational link: Pj stays at distance L from the line through Pi along u_i:
    Phi = u_i breve . d - L."""

    names = ("offset",)

    def rows(self, s):
        normal = rot90(s.unit(self.joint.iUindex)[1])
        return [(normal.T * self.distance(s))[0] - self.par(s, "L")]


@register_joint("rigid")
class Rigid(JointElement):
    """Bracket (book Eq. 7.35): r_i - (r_j + A_j d0) = 0 and phi_i - phi_j - p0 = 0, with d0
    (in body j's frame) taken from the initial coordinates; p0 is the joint's field."""

    names = ("x", "y", "angle")

    def rows(self, s):
        i, j = self.joint.iBindex, self.joint.jBindex
        d0 = s.vector(self.initial["rigid_d0"], f"joint {self.index} d0")
        offset = s.position(i) - s.position(j) - s.rotation(j) * d0
        return [offset[0], offset[1], s.angle(i) - s.angle(j) - self.par(s, "p0")]


@register_joint("disc")
class Disc(JointElement):
    """Disc of radius R on body i rolling without slip on the ground y = 0 (book Eq. 7.38):
    y_i - R = 0 and (x_i - x0) + R (phi_i - p0) = 0."""

    names = ("height", "rolling")

    def rows(self, s):
        b = self.joint.iBindex
        r, phi, radius = s.position(b), s.angle(b), self.par(s, "R")
        return [r[1] - radius, r[0] - self.par(s, "x0") + radius * (phi - self.par(s, "p0"))]


@register_joint("rel-rot")
class RelativeRotation(JointElement):
    """Rotational driver: phi_i - phi_j - f(t) = 0."""

    names = ("driver",)

    def rows(self, s):
        f = s.functions[self.joint.iFunct - 1][0]
        return [s.angle(self.joint.iBindex) - s.angle(self.joint.jBindex) - f]


@register_joint("rel-tran")
class RelativeTranslation(JointElement):
    """Translational driver: the distance between Pi and Pj is f(t): (d.d - f^2)/2 = 0."""

    names = ("driver",)

    def rows(self, s):
        d = self.distance(s)
        f = s.functions[self.joint.iFunct - 1][0]
        return [((d.T * d)[0] - f ** 2) / 2]
