"""DAP_BC's force elements (manual Table B.4; the book's Sec. 7.5), one small class per type,
registered by its type name.  Each adds its generalised forces (forces and moments about the
mass centres, in N and N m) to h as sympy expressions and gives its potential energy (J) where
DAP_BC's post counts one: gravity and linear point-to-point springs, and here also linear
rotational springs.  The ``user`` element is compiled separately (mbds.io.dapbc.user_force)
and called at its place in the list."""

from __future__ import annotations

import sympy

from mbds.io.dapbc.records import Force
from mbds.model.dapbc.registry import registrar
from mbds.model.dapbc.symbolic import Symbols, rot90

FORCES: dict[str, type["ForceElement"]] = {}
register_force = registrar(FORCES)


class ForceElement:
    """One force element: ``add`` adds its forces to h (a list of sympy expressions, 3 per
    body) and returns its potential energy."""

    type_name = ""

    def __init__(self, force: Force, index: int):
        self.force, self.index = force, index

    def add(self, s: Symbols, h: list, mass: list) -> sympy.Expr:
        raise NotImplementedError

    def par(self, s: Symbols, name: str):
        value = getattr(self.force, name)
        if hasattr(value, "shape"):
            return s.vector(value, f"force {self.index} {name}")
        return s.parameter(value, f"force {self.index} {name}")


def apply(h: list, body: int, force: sympy.Matrix, arm: sympy.Matrix | None = None) -> None:
    """Add ``force`` acting at the world-frame ``arm`` A s'P from body's mass centre."""
    if body == 0:
        return
    k = 3 * (body - 1)
    h[k] += force[0]
    h[k + 1] += force[1]
    if arm is not None:
        h[k + 2] += (rot90(arm).T * force)[0]


def torque(h: list, body: int, value) -> None:
    if body != 0:
        h[3 * body - 1] += value


@register_force("ptp")
class PointToPoint(ForceElement):
    """Spring-damper-actuator between Pi and Pj: tension f = k (L - L0) + dc L' + f_a along
    d = rPi - rPj, pulling Pi towards Pj and Pj towards Pi."""

    def add(self, s, h, mass):
        (bi, ri), (bj, rj) = s.point(self.force.iPindex), s.point(self.force.jPindex)
        d = ri - rj
        length = sympy.sqrt((d.T * d)[0])
        u = d / length
        rate = (u.T * s.rate(d))[0]
        stretch = length - self.par(s, "L0")
        k = self.par(s, "k")
        tension = k * stretch + self.par(s, "dc") * rate + self.par(s, "f_a")
        apply(h, bi, -tension * u, ri - s.position(bi))
        apply(h, bj, tension * u, rj - s.position(bj))
        return k * stretch ** 2 / 2


@register_force("rot-sda")
class RotationalSpringDamper(ForceElement):
    """Rotational spring-damper-actuator between bodies i and j: torque
    T = k (theta - theta0) + dc theta' + T_a with theta = phi_i - phi_j; -T on i, +T on j."""

    def add(self, s, h, mass):
        i, j = self.force.iBindex, self.force.jBindex
        theta = s.angle(i) - s.angle(j)
        k = self.par(s, "k")
        stretch = theta - self.par(s, "theta0")
        value = k * stretch + self.par(s, "dc") * s.rate(sympy.Matrix([theta]))[0] + self.par(s, "T_a")
        torque(h, i, -value)
        torque(h, j, value)
        return k * stretch ** 2 / 2


@register_force("weight")
class Weight(ForceElement):
    """Gravity m g wgt on every body; potential energy -m g wgt . r."""

    def add(self, s, h, mass):
        g, wgt = self.par(s, "gravity"), self.par(s, "wgt")
        potential = sympy.Integer(0)
        for b in range(1, s.model.nB + 1):
            apply(h, b, mass[b - 1] * g * wgt)
            potential -= mass[b - 1] * g * (wgt.T * s.position(b))[0]
        return potential


@register_force("flocal")
class LocalForce(ForceElement):
    """A constant force given in body i's frame (flocal), acting at its mass centre."""

    def add(self, s, h, mass):
        b = self.force.iBindex
        apply(h, b, s.rotation(b) * self.par(s, "flocal"))
        return sympy.Integer(0)


@register_force("f")
class GlobalForce(ForceElement):
    """A constant force f given in the x-y frame, acting at body i's mass centre."""

    def add(self, s, h, mass):
        apply(h, self.force.iBindex, self.par(s, "f"))
        return sympy.Integer(0)


@register_force("T")
class Torque(ForceElement):
    """A constant torque T on body i."""

    def add(self, s, h, mass):
        torque(h, self.force.iBindex, self.par(s, "T"))
        return sympy.Integer(0)
