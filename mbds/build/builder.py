"""Declaring a model: constants, bodies, coordinates, energies, virtual work, contacts, watches.

A :class:`ModelBuilder` collects the declarations of a script; :meth:`ModelBuilder.derive`
turns them into the equations of motion (:mod:`mbds.build.lagrange`) and
:meth:`ModelBuilder.write` into a model folder (:mod:`mbds.build.files`). Every declaration
remembers the script line it was made on, and an error about it names that line.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import sympy

from mbds.build.declarations import Body, Contact, Declarations, Term, Watch
from mbds.build.files import write_model
from mbds.build.lagrange import Equations, derive_equations
from mbds.build.location import Location, declared_here
from mbds.build.shapes import check_shape
from mbds.errors import ModelError
from mbds.expr import symbols as S
from mbds.io.world import WorldSettings

_BAD_NAME = "`'\u2018\u2019[]-: \t,"


class ModelBuilder:
    """Declarations of one model; see ``docs/building-models.md``."""

    def __init__(self):
        self.declared = Declarations()

    # -- names ---------------------------------------------------------------------------

    def constant(self, name: str, value: float) -> sympy.Symbol:
        """Declare the constant ``c'name`` with its value (SI units); returns its symbol."""
        where = declared_here()
        if not name.isidentifier():
            raise ModelError(f"constant name {name!r} must be a letter followed by letters, digits or _", *where)
        if name in self.declared.constants:
            raise ModelError(f"constant c'{name} declared twice (first at line {self.declared.constants[name][1].line})", *where)
        if not np.isfinite(float(value)):
            raise ModelError(f"constant c'{name} needs a finite value, not {value}", *where)
        self.declared.constants[name] = (float(value), where)
        return S.constant(name)

    def body(self, name: str, shape, *, mass: float | None = None, inertia: float | None = None,
             density: float | None = None, thickness: float | None = None,
             color: tuple[float, float, float] = (0.0, 1.0, 0.0),
             position: tuple[float, float, float] = (0.0, 0.0, 0.0),
             velocity: tuple[float, float, float] = (0.0, 0.0, 0.0),
             virtual_to: Body | str | None = None, correct_origin: bool = False,
             skin_thickness: float | None = None, displacement_factor: float | None = None) -> Body:
        """Declare a body: ``shape`` a closed counter-clockwise outline (N, 2) in m; ``mass``
        (kg) and ``inertia`` (Jzz about the centroid, kg m²), or ``density`` (kg/m³) and
        ``thickness`` (m) to derive them; start ``position`` (m, m, rad) and ``velocity``;
        ``virtual_to`` another body that this one lends its shape to."""
        where = declared_here()
        if not name or any(ch in name for ch in _BAD_NAME):
            raise ModelError(f"body name {name!r} is empty or has a quote, bracket, '-', ':', ',' or space", *where)
        if name in self.declared.bodies:
            raise ModelError(f"body '{name}' declared twice (first at line {self.declared.bodies[name].where.line})", *where)
        points = np.asarray(shape, dtype=float)
        problems = check_shape(points) if points.ndim == 2 and points.shape[1:] == (2,) else ["not an (N, 2) array of points"]
        if problems:
            raise ModelError(f"shape of body '{name}': {'; '.join(problems)}", *where)
        carrier = virtual_to.name if isinstance(virtual_to, Body) else virtual_to
        if carrier is not None and carrier not in self.declared.bodies:
            raise ModelError(f"body '{name}' is virtual to '{carrier}', which is not declared (declare it first)", *where)
        if carrier is None and (mass is None or inertia is None) and (density is None or thickness is None):
            raise ModelError(f"body '{name}' needs mass and inertia, or density and thickness to derive them", *where)
        for label, value in (("mass", mass), ("inertia", inertia), ("density", density), ("thickness", thickness)):
            if value is not None and not value > 0:
                raise ModelError(f"{label} of body '{name}' must be positive, not {value}", *where)
        body = Body(name, points, mass, inertia, density, thickness, tuple(color), tuple(map(float, position)),
                    tuple(map(float, velocity)), carrier, correct_origin, skin_thickness, displacement_factor, where)
        self.declared.bodies[name] = body
        return body

    def free(self, name: str, position: float = 0.0, velocity: float = 0.0) -> sympy.Expr:
        """A coordinate ``g'name`` bound to no body, with its start value and rate; returns it
        as a function of t (declare it generalized or dependent as well)."""
        where = declared_here()
        if not name.isidentifier():
            raise ModelError(f"coordinate name {name!r} must be a letter followed by letters, digits or _", *where)
        self.declared.free[name] = (float(position), float(velocity), where)
        return S.generalized(name)

    # -- coordinates ---------------------------------------------------------------------

    def generalized(self, *coordinates: sympy.Expr) -> None:
        """Declare the generalized coordinates q, in order (body coordinates or free ones)."""
        where = declared_here()
        for c in coordinates:
            self._check_coordinate(c, where)
            self.declared.coordinates.append((c, where))

    def dependent(self, coordinate: sympy.Expr, definition) -> None:
        """Declare ``coordinate`` as a function of the generalized coordinates and t."""
        where = declared_here()
        self._check_coordinate(coordinate, where)
        self.declared.dependent.append((coordinate, sympy.sympify(definition), where))

    def _check_coordinate(self, c, where: Location) -> None:
        ref = S.reference(c) if isinstance(c, sympy.Basic) else None
        if ref is None or ref.kind not in ("coordinate", "generalized"):
            raise ModelError(f"{c} is not a coordinate (use body.x, body.y, body.Rz or builder.free(name))", *where)
        if ref.kind == "coordinate":
            body = self.declared.bodies.get(ref.body)
            if body is None:
                raise ModelError(f"{S.display(c)} names no declared body", *where)
            if body.virtual_to is not None:
                raise ModelError(f"{S.display(c)} belongs to a virtual body, which has no coordinates", *where)
            if ref.name not in ("x", "y", "Rz"):
                raise ModelError(f"{S.display(c)}: a planar body moves in x, y and Rz only", *where)
        elif ref.name not in self.declared.free:
            raise ModelError(f"{S.display(c)} is not declared (builder.free('{ref.name}'))", *where)
        taken = [w for d, w in self.declared.coordinates if d == c] + [w for d, _, w in self.declared.dependent if d == c]
        if taken:
            raise ModelError(f"{S.display(c)} is already a coordinate (declared at line {taken[0].line})", *where)

    # -- energies ------------------------------------------------------------------------

    def kinetic_energy(self, expr) -> None:
        """Add to the kinetic energy T (J), in coordinates and their first derivatives."""
        self.declared.kinetic.append(Term(sympy.sympify(expr), declared_here()))

    def potential_energy(self, expr) -> None:
        """Add to the potential energy V (J), in coordinates (no velocities)."""
        self.declared.potential.append(Term(sympy.sympify(expr), declared_here()))

    def dissipation(self, expr) -> None:
        """Add to Rayleigh's dissipation function D (W): generalized forces -∂D/∂q̇."""
        self.declared.dissipation.append(Term(sympy.sympify(expr), declared_here()))

    def virtual_work(self, expr) -> None:
        """Add to the virtual work δW (J) of applied forces: linear in the variations
        (:func:`variation`, :func:`delta`) of generalized or dependent coordinates."""
        self.declared.virtual_work.append(Term(sympy.sympify(expr), declared_here()))

    # -- contacts, watches, world ----------------------------------------------------------

    def contact(self, first: Body | str, second: Body | str | None = None, *, friction=0,
                restitution_normal=0, restitution_tangent=0, parameter_ni=0,
                initial_temperature: float = 0.0, resisting_penetration: str = "T:T") -> None:
        """Contact properties of a pair, or of ``first`` with all bodies when ``second`` is None;
        laws are numbers or expressions in constants, ``temp`` and ``vRel``."""
        where = declared_here()
        names = [b.name if isinstance(b, Body) else b for b in (first, second)]
        for n in names:
            if n is not None and n not in self.declared.bodies:
                raise ModelError(f"contact names body '{n}', which is not declared", *where)
        laws = {"friction": friction, "restitutionNormal": restitution_normal,
                "restitutionTangent": restitution_tangent, "parameterNi": parameter_ni,
                "initialTemperature": initial_temperature, "resistingPenetration": resisting_penetration}
        allowed = {S.TEMP, S.VREL} | {S.constant(n) for n in self.declared.constants}
        for key in ("friction", "restitutionNormal", "restitutionTangent", "parameterNi"):
            unknown = sorted(S.display(s) for s in sympy.sympify(laws[key]).free_symbols - allowed)
            if unknown:
                raise ModelError(f"{key} uses {', '.join(unknown)}: only declared constants, temp and vRel", *where)
        self.declared.contacts.append(Contact(names[0], names[1], laws, where))

    def watch(self, body: Body | str, points: str = "all", *, direction_inside: int = 0,
              max_change: float | tuple[float, float] = 0.0) -> None:
        """Watch contact points of ``body`` (``contactWatch`` syntax: ``all``, ``0-2``, ``1:3``)
        and reshape them by up to ``max_change`` (m) per version (``directionInside`` 1: inward)."""
        where = declared_here()
        name = body.name if isinstance(body, Body) else body
        if name not in self.declared.bodies:
            raise ModelError(f"watch names body '{name}', which is not declared", *where)
        change = tuple(max_change) if isinstance(max_change, (tuple, list)) else (float(max_change),)
        self.declared.watches.append(Watch(name, points, direction_inside, change, where))

    def world(self, **settings) -> None:
        """World settings by their Python names (``minimum_timestep``, ``maximum_timestep``,
        ``maximum_penetration``, ``break_time``, ...; see :class:`mbds.io.world.WorldSettings`)."""
        where = declared_here()
        known = set(WorldSettings.__dataclass_fields__) - {"number_of_coordinates"}
        for key in settings:
            if key not in known:
                raise ModelError(f"unknown world setting {key!r} (known: {', '.join(sorted(known))})", *where)
        self.declared.world.update(settings)

    # -- results -------------------------------------------------------------------------

    def derive(self) -> Equations:
        """The equations of motion: mass matrix, h vector, energy and dependent coordinates;
        ModelError at the faulty declaration."""
        return derive_equations(self.declared)

    def write(self, folder: str | Path, name: str) -> Path:
        """Derive the equations and write the complete model folder; returns the world file."""
        return write_model(self.declared, self.derive(), Path(folder), name)
