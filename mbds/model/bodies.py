"""Bodies of an assembled model: shapes, mass properties, and how each pose coordinate moves.

Binding rule (per body, for each of x, y and Rz):

1. listed in the ``.gc`` file -> the generalized coordinate q_k (start values from the body's
   ``[startPosition]``/``[startVelocity]``);
2. else defined in the ``.dc`` file -> that dependent coordinate (start values from its
   position and velocity expressions; the ``.bdy`` start values are not used);
3. else fixed at its ``[startPosition]`` value for the whole run (ground, walls).

A body with ``virtualToBody`` has no coordinates of its own: it moves rigidly with the body it
names, at the offset their start positions give, and lends it its shape for contacts only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mbds.errors import ModelError, warn
from mbds.io.coordinates import CoordinateName
from mbds.io.folder import ModelFiles
from mbds.model.geometry import polygon_problems, polygon_properties

POSE = ("x", "y", "Rz")
FIXED, GENERALIZED, DEPENDENT = 0, 1, 2
BINDING_NAMES = {FIXED: "fixed", GENERALIZED: "generalized", DEPENDENT: "dependent"}


@dataclass
class Body:
    """One body. ``points`` (N, 2) in the body frame (m); ``mass`` (kg) and ``inertia`` (Jzz
    about the centroid, kg m^2) are 0 for a virtual body; ``binding`` and ``binding_index`` give,
    for x, y and Rz, the kind (FIXED, GENERALIZED, DEPENDENT) and the q or dependent index."""

    name: str
    points: np.ndarray
    mass: float
    inertia: float
    centroid: np.ndarray
    start_position: np.ndarray
    start_velocity: np.ndarray
    binding: tuple[int, int, int]
    binding_index: tuple[int, int, int]
    carrier: int | None
    offset: np.ndarray
    maximum_displacement_factor: float
    skin_thickness: float
    mass_derived: bool
    inertia_derived: bool
    color: tuple[float, float, float] = (0.0, 1.0, 0.0)

    @property
    def virtual(self) -> bool:
        return self.carrier is not None

    @property
    def point_count(self) -> int:
        """Distinct points of the shape (the closing repeat not counted)."""
        return len(self.points) - 1


def assemble_bodies(files: ModelFiles) -> list[Body]:
    """Bodies with validated shapes, mass properties and coordinate bindings."""
    world = files.world
    names: dict[str, int] = {}
    for i, body in enumerate(files.bodies):
        if body.main.name in names:
            raise ModelError(f"body name '{body.main.name}' is used by two body files", body.path, body.name_line)
        names[body.main.name] = i
    gc = {c: k for k, c in enumerate(files.coordinates.coordinates)}
    dc = {c.coordinate: d for d, c in enumerate(files.dependent.coordinates)}
    _check_coordinates_name_bodies(files, names)
    bodies = []
    for body_file, shape in zip(files.bodies, files.shapes):
        main = body_file.main
        problems = polygon_problems(shape.points)
        if problems:
            raise ModelError(f"shape of body '{main.name}': {'; '.join(problems)}", shape.path, shape.data_line)
        props = polygon_properties(shape.points)
        points = shape.points.copy()
        if main.correct_origin:
            points = points - props.centroid
            centroid = np.zeros(2)
        else:
            centroid = props.centroid
        carrier = None
        if main.virtual_to_body:
            if main.virtual_to_body not in names:
                raise ModelError(f"virtualToBody names no body: '{main.virtual_to_body}'", body_file.path, body_file.name_line)
            carrier = names[main.virtual_to_body]
            if files.bodies[carrier].main.virtual_to_body:
                raise ModelError("virtualToBody must name a body that is not virtual itself", body_file.path, body_file.name_line)
        mass, inertia, mass_derived, inertia_derived = _mass_properties(body_file, props, carrier is not None)
        binding, index = _binding(main.name, gc, dc, carrier is not None, files)
        if carrier is None and not main.correct_origin and (mass_derived or inertia_derived):
            size = float(np.ptp(points, axis=0).max())
            if np.hypot(*centroid) > 1e-6 * size and GENERALIZED in binding:
                warn(
                    f"body '{main.name}': its origin is {np.hypot(*centroid):.3g} m from the centroid of its shape; "
                    "mass properties derived from the shape refer to the centroid "
                    "(correctOrigin = 1 moves the origin there)",
                    body_file.path,
                    body_file.name_line,
                )
        pos, vel = body_file.position, body_file.velocity
        bodies.append(
            Body(
                name=main.name,
                points=points,
                mass=mass,
                inertia=inertia,
                centroid=centroid,
                start_position=np.array([pos.x, pos.y, pos.rz]),
                start_velocity=np.array([vel.x, vel.y, vel.rz]),
                binding=binding,
                binding_index=index,
                carrier=carrier,
                offset=np.zeros(3),
                maximum_displacement_factor=(
                    main.maximum_displacement_factor
                    if main.maximum_displacement_factor is not None
                    else world.settings.maximum_displacement_factor
                ),
                skin_thickness=(
                    main.skin_thickness if main.skin_thickness is not None else 100.0 * world.settings.maximum_penetration
                ),
                mass_derived=mass_derived,
                inertia_derived=inertia_derived,
                color=body_color(main.rgb_color),
            )
        )
    for body in bodies:
        if body.carrier is not None:
            body.offset = relative_pose(bodies[body.carrier].start_position, body.start_position)
    return bodies


def body_color(text: str) -> tuple[float, float, float]:
    """The ``RGBColor`` of a ``.bdy`` file (three numbers 0-1); green, the default, when unreadable."""
    try:
        red, green, blue = (min(max(float(v), 0.0), 1.0) for v in text.split())
    except ValueError:
        return (0.0, 1.0, 0.0)
    return (red, green, blue)


def relative_pose(carrier: np.ndarray, pose: np.ndarray) -> np.ndarray:
    """``pose`` (x, y, Rz) expressed in the frame of ``carrier`` (x, y, Rz)."""
    c, s = np.cos(carrier[2]), np.sin(carrier[2])
    d = pose[:2] - carrier[:2]
    return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1], pose[2] - carrier[2]])


def _mass_properties(body_file, props, virtual: bool):
    main, given = body_file.main, body_file.mass
    if virtual:
        if given is not None and (given.mass or given.inertia_zz):
            warn("a virtual body's mass properties are not used", body_file.path, body_file.name_line)
        return 0.0, 0.0, False, False
    mass = given.mass if given else None
    inertia = given.inertia_zz if given else None
    if mass is not None and inertia is None:
        inertia = mass * props.second_moment / props.area
        warn(f"body '{main.name}': mass given without InertiaZZ; Jzz = {inertia:.6g} kg m^2, the shape's "
             "inertia scaled to the given mass (give InertiaZZ to set it)", body_file.path, body_file.name_line)
        return mass, inertia, False, True
    if mass is None or inertia is None:
        missing = [k for k, v in (("density", main.density), ("thickness", main.thickness)) if v is None]
        if missing:
            raise ModelError(
                f"body '{main.name}' needs {' and '.join(missing)} to derive its "
                f"{'mass' if mass is None else 'InertiaZZ'} from its shape (or give [Mass properties])",
                body_file.path,
                body_file.name_line,
            )
        rho_t = main.density * main.thickness
    return (
        mass if mass is not None else rho_t * props.area,
        inertia if inertia is not None else rho_t * props.second_moment,
        mass is None,
        inertia is None,
    )


def _binding(name: str, gc: dict, dc: dict, virtual: bool, files: ModelFiles):
    kinds, indices = [], []
    for coordinate in POSE:
        key = CoordinateName("b", name, coordinate)
        if virtual and (key in gc or key in dc):
            where = files.coordinates.path if key in gc else files.dependent.path
            raise ModelError(f"{key} belongs to a virtual body and cannot be a coordinate", where)
        if key in gc:
            kinds.append(GENERALIZED)
            indices.append(gc[key])
        elif key in dc:
            kinds.append(DEPENDENT)
            indices.append(dc[key])
        else:
            kinds.append(FIXED)
            indices.append(-1)
    return tuple(kinds), tuple(indices)


def _check_coordinates_name_bodies(files: ModelFiles, names: dict) -> None:
    gc = files.coordinates
    for name, line in zip(gc.coordinates, gc.lines):
        _check_pose_coordinate(name, names, gc.path, line)
    for c in files.dependent.coordinates:
        _check_pose_coordinate(c.coordinate, names, files.dependent.path, c.line)
        if c.coordinate in gc.coordinates:
            raise ModelError(f"{c.coordinate} is both generalized (.gc) and dependent (.dc)", files.dependent.path, c.line)


def _check_pose_coordinate(name: CoordinateName, names: dict, path, line) -> None:
    if name.kind != "b":
        return
    if name.name not in names:
        raise ModelError(f"{name} names no body (bodies: {', '.join(names)})", path, line)
    if name.coordinate not in POSE:
        raise ModelError(f"{name}: a planar model moves bodies in x, y and Rz only", path, line)
