"""Energies, dissipation functions and virtual work of the common elements, as sympy
expressions in body coordinates (SI units: J, W)."""

from __future__ import annotations

import sympy

from mbds.build.declarations import Body, delta, variation

_T = sympy.Symbol("t", real=True)


def _rate(expr) -> sympy.Expr:
    return sympy.diff(sympy.sympify(expr), _T)


def rigid_body_kinetic(body: Body) -> sympy.Expr:
    """½ m (ẋ² + ẏ²) + ½ Jzz Ṙz² of a body whose origin is its centroid (J)."""
    return (body.m * (_rate(body.x) ** 2 + _rate(body.y) ** 2) + body.Jzz * _rate(body.Rz) ** 2) / 2


def point_mass_kinetic(mass, x, y) -> sympy.Expr:
    """½ m (ẋ² + ẏ²) of a mass at the position (x, y) (m; expressions in coordinates) (J)."""
    return mass * (_rate(x) ** 2 + _rate(y) ** 2) / 2


def gravity(mass, height, g) -> sympy.Expr:
    """m g h: the potential of a mass whose centre is at ``height`` (m) in gravity g (J)."""
    return mass * g * height


def spring(stiffness, length, rest_length=0) -> sympy.Expr:
    """½ k (l − l₀)² of a linear spring of stiffness k (N/m) and length l (m) (J)."""
    return stiffness * (length - rest_length) ** 2 / 2


def torsional_spring(stiffness, angle, rest_angle=0) -> sympy.Expr:
    """½ k (φ − φ₀)² of a torsional spring of stiffness k (N m/rad) at angle φ (rad) (J)."""
    return stiffness * (angle - rest_angle) ** 2 / 2


def distance(x1, y1, x2, y2) -> sympy.Expr:
    """The distance between two points (m), for springs between bodies."""
    return sympy.sqrt((x2 - x1) ** 2 + (y2 - y1) ** 2)


def damper(damping, elongation) -> sympy.Expr:
    """Rayleigh's dissipation function ½ c ṡ² of a viscous damper of damping c (N s/m, or
    N m s/rad for a rotary one) across the elongation or angle s (W); the builder turns it
    into the generalized forces −∂D/∂q̇."""
    return damping * _rate(elongation) ** 2 / 2


def force(fx, fy, x, y) -> sympy.Expr:
    """Virtual work F·δr (J) of the force (fx, fy) (N) applied at the point (x, y) (m)."""
    return fx * delta(x) + fy * delta(y)


def torque(moment, body: Body) -> sympy.Expr:
    """Virtual work M δRz (J) of the torque ``moment`` (N m) acting on ``body``."""
    return moment * variation(body.Rz)
