"""Writing a derived model as an MBDS model folder: ``.wld``, ``.bdy``, ``.exs``, ``.gc``,
``.dc``, ``.cns``, ``.mmx``, ``.hv``, ``.me``, ``.cop`` and ``.wtc`` (every file atomically,
through the readers' own writers in :mod:`mbds.io`)."""

from __future__ import annotations

from pathlib import Path

import sympy

from mbds.build.declarations import Body, Contact, Declarations
from mbds.build.lagrange import Equations
from mbds.errors import ModelError
from mbds.expr import symbols as S
from mbds.expr.printer import mbds_text
from mbds.io.body import BodyFile, BodyMain, MassProperties, Pose
from mbds.io.constants import ConstantsFile
from mbds.io.contacts import ContactLaw, ContactSection, ContactsFile
from mbds.io.coordinates import (
    CoordinateName,
    CoordinatesFile,
    DependentCoordinate,
    DependentCoordinatesFile,
)
from mbds.io.equations import ExpressionsFile, MatrixFile
from mbds.io.folder import ModelFiles, write_model_files
from mbds.io.ini import Located
from mbds.io.shape import ShapeFile
from mbds.io.watches import BodyWatch, BodyWatchOptions, WatchesFile, parse_contact_watch
from mbds.io.world import WorldFile, WorldSettings
from mbds.io.text import format_number


def write_model(d: Declarations, eq: Equations, folder: Path, name: str) -> Path:
    """Write the model ``name`` into ``folder`` (created); returns the world file's path."""
    return write_model_files(model_files(d, eq, folder / f"{name}.wld"), folder, name)


def model_files(d: Declarations, eq: Equations, world_path: Path) -> ModelFiles:
    """The :class:`ModelFiles` of a derived model, as :func:`mbds.io.folder.read_model_files`
    would return them for the written folder."""
    world_settings = {"dependent_coordinates_file": "current.dc", **d.world}
    if "break_time" in world_settings:
        world_settings["break_time"] = Located(text(world_settings["break_time"], "breakTime"))
    settings = WorldSettings(number_of_coordinates=len(eq.coordinates), **world_settings)
    starts = {S.display(dep.coordinate): dep.start for dep in eq.dependent}
    bodies = list(d.bodies.values())
    generalized_start = [
        (f"g'{n}", Located(f"{format_number(p)}, {format_number(v)}"))
        for n, (p, v, _) in d.free.items()
        if (p or v) and any(S.reference(c).name == n for c in eq.coordinates)
    ]
    return ModelFiles(
        world=WorldFile(settings, [Located(f"{b.name}.bdy") for b in bodies], world_path, generalized_start),
        bodies=[_body_file(b, starts) for b in bodies],
        shapes=[ShapeFile(b.shape + 0.0) for b in bodies],  # + 0.0: no negative zeros in the files
        coordinates=CoordinatesFile([_name(c) for c in eq.coordinates]),
        dependent=DependentCoordinatesFile([
            DependentCoordinate(
                _name(dep.coordinate),
                [Located(text(e)) for e in (dep.position, dep.velocity, dep.acceleration)],
                [Located(text(e)) for e in dep.jacobian],
                Located(text(dep.scalar)),
            )
            for dep in eq.dependent
        ]),
        constants=ConstantsFile({n: v for n, (v, _) in d.constants.items()}),
        mass_matrix=MatrixFile([[Located(text(e)) for e in row] for row in eq.mass_matrix]),
        h_vector=ExpressionsFile([Located(text(e)) for e in eq.h_vector]),
        energy=ExpressionsFile([Located(text(eq.energy))]),
        contacts=ContactsFile([_contact(c) for c in d.contacts]),
        watches=WatchesFile(bodies=[
            BodyWatch(
                w.body,
                None,
                BodyWatchOptions(contact_watch=w.points, direction_inside=w.direction_inside,
                                 max_change=list(w.max_change)),
                parse_contact_watch(w.points, *w.where),
            )
            for w in d.watches
        ]),
    )


def text(value, what: str = "expression") -> str:
    """MBDS text of a number or an expression; ModelError naming what cannot be written."""
    expr = sympy.sympify(value)
    if expr.is_Number:
        return format_number(float(expr))
    try:
        return mbds_text(expr)
    except ValueError as error:
        raise ModelError(f"{what} cannot be written to an MBDS file: {error}") from None


def _name(c: sympy.Expr) -> CoordinateName:
    ref = S.reference(c)
    return CoordinateName("g", ref.name) if ref.kind == "generalized" else CoordinateName("b", ref.body, ref.name)


def _pose(values) -> Pose:
    x, y, rz = values
    return Pose(x=x, y=y, rz=rz)


def _body_file(b: Body, starts: dict[str, tuple[float, float]]) -> BodyFile:
    """A body file; a dependent coordinate's start value is its definition's at the start state."""
    position, velocity = list(b.position), list(b.velocity)
    for axis, coordinate in enumerate(("x", "y", "Rz")):
        start = starts.get(f"b'{b.name}'{coordinate}[t]")
        if start is not None:
            position[axis], velocity[axis] = start
    main = BodyMain(
        name=b.name,
        virtual_to_body=b.virtual_to or "",
        rgb_color=" ".join(format_number(c) for c in b.color),
        shape_file=f"{b.name}.exs",
        density=b.density,
        thickness=b.thickness,
        maximum_displacement_factor=b.displacement_factor,
        skin_thickness=b.skin_thickness,
        correct_origin=b.correct_origin,
    )
    given = b.mass is not None or b.inertia is not None
    mass = MassProperties(mass=b.mass, inertia_zz=b.inertia) if given else None
    return BodyFile(main, mass, _pose(position), _pose(velocity))


def _contact(c: Contact) -> ContactSection:
    laws = c.laws
    law = ContactLaw(
        resisting_penetration=laws["resistingPenetration"],
        friction=Located(text(laws["friction"], "friction")),
        restitution_normal=Located(text(laws["restitutionNormal"], "restitutionNormal")),
        restitution_tangent=Located(text(laws["restitutionTangent"], "restitutionTangent")),
        parameter_ni=Located(text(laws["parameterNi"], "parameterNi")),
        initial_temperature=float(laws["initialTemperature"]),
    )
    return ContactSection(c.first, c.second, law)
