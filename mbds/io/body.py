"""Body files (``.bdy``): name, shape, mass properties, start position and velocity."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.ini import POSITIVE, check_rules, find_section, format_settings, parse_ini, read_settings, setting

NOT_SET = None


@dataclass
class BodyMain:
    """The ``[main]`` section of a body file (SI units: kg/m^3, m)."""

    name: str = setting("name", "text", "")
    virtual_to_body: str = setting("virtualToBody", "text", "")
    rgb_color: str = setting("RGBColor", "text", "0 1 0")
    shape_type: str = setting("shapeType", "text", "extrusionSolid")
    shape_file: str = setting("shapeFile", "text", "")
    density: float | None = setting("density", "number", NOT_SET)
    thickness: float | None = setting("thickness", "number", NOT_SET)
    maximum_displacement_factor: float | None = setting("maximumDisplacementFactor", "number", NOT_SET)
    skin_thickness: float | None = setting("skinThickness", "number", NOT_SET)
    correct_origin: bool = setting("correctOrigin", "flag", False)


@dataclass
class MassProperties:
    """The optional ``[Mass properties]`` section (kg, kg m^2); unset values are derived."""

    mass: float | None = setting("mass", "number", NOT_SET)
    inertia_xx: float | None = setting("InertiaXX", "number", NOT_SET)
    inertia_xy: float | None = setting("InertiaXY", "number", NOT_SET)
    inertia_xz: float | None = setting("InertiaXZ", "number", NOT_SET)
    inertia_yy: float | None = setting("InertiaYY", "number", NOT_SET)
    inertia_yz: float | None = setting("InertiaYZ", "number", NOT_SET)
    inertia_zz: float | None = setting("InertiaZZ", "number", NOT_SET)


@dataclass
class Pose:
    """``[startPosition]`` (m, rad) or ``[startVelocity]`` (m/s, rad/s); planar use: x, y, Rz."""

    x: float = setting("x", "number", 0.0)
    y: float = setting("y", "number", 0.0)
    z: float = setting("z", "number", 0.0)
    rx: float = setting("Rx", "number", 0.0)
    ry: float = setting("Ry", "number", 0.0)
    rz: float = setting("Rz", "number", 0.0)


SECTIONS = {"main": "main", "mass properties": "mass", "startposition": "position", "startvelocity": "velocity"}


@dataclass
class BodyFile:
    main: BodyMain = field(default_factory=BodyMain)
    mass: MassProperties | None = None
    position: Pose = field(default_factory=Pose)
    velocity: Pose = field(default_factory=Pose)
    path: Path | None = field(default=None, compare=False)
    name_line: int | None = field(default=None, compare=False)
    lines: dict[str, int] = field(default_factory=dict, compare=False)  # [main] key (lower case) -> line


MAIN_RULES = {name: POSITIVE for name in ("density", "thickness", "maximum_displacement_factor", "skin_thickness")}
MASS_RULES = {name: POSITIVE for name in ("mass", "inertia_zz")}


def parse_body(text: str, path: str | Path | None = None, separator: str = ".") -> BodyFile:
    """A :class:`BodyFile` from the text of a ``.bdy`` file."""
    sections = parse_ini(text, path)
    for s in sections:
        if s.name.lower() not in SECTIONS:
            warn(f"unknown section [{s.name}] (ignored)", path, s.line)
    main_section = find_section(sections, "main")
    if main_section is None:
        raise ModelError("no [main] section", path, 1)
    main = read_settings(BodyMain, main_section, path, separator)
    name_line = next((e.line for e in main_section.entries if e.key.lower() == "name"), main_section.line)
    if not main.name:
        raise ModelError("the body has no name (name = ...)", path, name_line)
    if any(ch in main.name for ch in "`'\u2018\u2019[]-: \t,"):
        raise ModelError(f"body name '{main.name}' contains a quote, bracket, '-', ':', ',' or space", path, name_line)
    if main.shape_type.lower() != "extrusionsolid":
        raise ModelError(f"shapeType '{main.shape_type}' is not supported (use extrusionSolid)", path, main_section.line)
    check_rules(main, MAIN_RULES, main_section, path)
    mass_section = find_section(sections, "mass properties")
    mass = read_settings(MassProperties, mass_section, path, separator) if mass_section else None
    if mass is not None:
        check_rules(mass, MASS_RULES, mass_section, path)
    position = read_settings(Pose, find_section(sections, "startPosition"), path, separator)
    velocity = read_settings(Pose, find_section(sections, "startVelocity"), path, separator)
    for title, pose in (("startPosition", position), ("startVelocity", velocity)):
        if pose.z or pose.rx or pose.ry:
            warn(f"[{title}] z, Rx and Ry are not used by a planar model", path)
    lines = {e.key.lower(): e.line for e in main_section.entries}
    return BodyFile(main, mass, position, velocity, Path(path) if path else None, name_line, lines)


def format_body(body: BodyFile, separator: str = ".") -> str:
    """The text of a ``.bdy`` file."""
    lines = ["[main]", *format_settings(body.main, separator, skip_defaults=True)]
    if body.mass is not None:
        lines += ["[Mass properties]", *format_settings(body.mass, separator, skip_defaults=True)]
    lines += ["[startPosition]", *format_settings(body.position, separator)]
    lines += ["[startVelocity]", *format_settings(body.velocity, separator)]
    return "\n".join(lines) + "\n"
