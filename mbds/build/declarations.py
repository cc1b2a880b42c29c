"""What a model script declares: bodies, energies, virtual work, contacts, watches, each with
the script line it was declared on (:class:`mbds.build.location.Location`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy

from mbds.build.location import Location
from mbds.expr import symbols as S
from mbds.model.geometry import polygon_properties


@dataclass(eq=False)
class Body:
    """A declared body. ``x``, ``y``, ``Rz`` are its coordinates (functions of t: m, m, rad),
    ``m`` and ``Jzz`` its mass (kg) and centroidal moment of inertia (kg m²) as symbols.

    ``shape`` is the closed counter-clockwise outline (m, body frame); ``mass``/``inertia``
    given values or None (then derived from ``density`` (kg/m³) × ``thickness`` (m) and the
    shape); ``position``/``velocity`` the start pose (x, y, Rz) and its rate.
    """

    name: str
    shape: np.ndarray
    mass: float | None
    inertia: float | None
    density: float | None
    thickness: float | None
    color: tuple[float, float, float]
    position: tuple[float, float, float]
    velocity: tuple[float, float, float]
    virtual_to: str | None
    correct_origin: bool
    skin_thickness: float | None
    displacement_factor: float | None
    where: Location

    x: sympy.Expr = field(init=False, repr=False, compare=False)
    y: sympy.Expr = field(init=False, repr=False, compare=False)
    Rz: sympy.Expr = field(init=False, repr=False, compare=False)  # noqa: N815 (the manual's name)
    m: sympy.Symbol = field(init=False, repr=False, compare=False)
    Jzz: sympy.Symbol = field(init=False, repr=False, compare=False)  # noqa: N815 (the manual's name)

    def __post_init__(self):
        self.x, self.y, self.Rz = (S.body_coordinate(self.name, c) for c in ("x", "y", "Rz"))
        self.m, self.Jzz = (S.mass_property(self.name, p) for p in ("m", "Jzz"))

    def point(self, px, py) -> tuple[sympy.Expr, sympy.Expr]:
        """World position (m) of the body-fixed point (px, py) (m, body frame)."""
        c, s = sympy.cos(self.Rz), sympy.sin(self.Rz)
        return self.x + c * px - s * py, self.y + s * px + c * py

    def mass_values(self) -> tuple[float, float]:
        """Mass (kg) and Jzz (kg m²): given, else derived from the shape as mbds derives them."""
        if self.mass is not None and self.inertia is not None:
            return self.mass, self.inertia
        props = polygon_properties(self.shape)
        rho_t = self.density * self.thickness
        mass = self.mass if self.mass is not None else rho_t * props.area
        inertia = self.inertia if self.inertia is not None else rho_t * props.second_moment
        return mass, inertia


@dataclass
class Term:
    """One contribution to an energy, the dissipation function or the virtual work."""

    expr: sympy.Expr
    where: Location


@dataclass
class Contact:
    """A ``.cop`` section: ``second`` None means ``[first:all]``; laws are numbers or
    expressions in constants, ``temp`` and ``vRel``."""

    first: str
    second: str | None
    laws: dict[str, object]
    where: Location


@dataclass
class Watch:
    """A ``.wtc`` body section (``contactWatch`` text and reshaping keys)."""

    body: str
    points: str
    direction_inside: int
    max_change: tuple[float, ...]
    where: Location


@dataclass
class Declarations:
    """Everything declared so far, in declaration order."""

    constants: dict[str, tuple[float, Location]] = field(default_factory=dict)
    bodies: dict[str, Body] = field(default_factory=dict)
    free: dict[str, tuple[float, float, Location]] = field(default_factory=dict)
    coordinates: list[tuple[sympy.Expr, Location]] = field(default_factory=list)
    dependent: list[tuple[sympy.Expr, sympy.Expr, Location]] = field(default_factory=list)
    kinetic: list[Term] = field(default_factory=list)
    potential: list[Term] = field(default_factory=list)
    dissipation: list[Term] = field(default_factory=list)
    virtual_work: list[Term] = field(default_factory=list)
    contacts: list[Contact] = field(default_factory=list)
    watches: list[Watch] = field(default_factory=list)
    world: dict[str, object] = field(default_factory=dict)


def variation(coordinate: sympy.Expr) -> sympy.Symbol:
    """The virtual displacement δc of a coordinate (a symbol of the virtual work)."""
    return sympy.Symbol(f"δ{S.display(coordinate)}", real=True)


def delta(expr) -> sympy.Expr:
    """The variation δf = Σ ∂f/∂c δc of a position expression f over the coordinates c it uses."""
    expr = sympy.sympify(expr)
    return sympy.Add(*(sympy.diff(expr, c) * variation(c) for c in sorted(S.coordinates_in(expr), key=str)))
