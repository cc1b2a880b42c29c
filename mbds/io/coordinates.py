"""Generalized (``.gc``) and dependent (``.dc``) coordinate files."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.ini import Located
from mbds.io.text import QUOTES, is_directive, significant_lines

BODY_COORDINATES = ("x", "y", "z", "Rx", "Ry", "Rz")
_Q = f"[{QUOTES}]"
_BODY = re.compile(rf"b{_Q}([^{QUOTES}\[\]\s]+){_Q}(x|y|z|Rx|Ry|Rz)(?:\[t\])?", re.IGNORECASE)
_FREE = re.compile(rf"g{_Q}([A-Za-z_]\w*)(?:\[t\])?")


@dataclass(frozen=True)
class CoordinateName:
    """A coordinate: ``kind`` ``b`` (a body's x, y, z, Rx, Ry or Rz) or ``g`` (a free one)."""

    kind: str
    name: str
    coordinate: str = ""

    def __str__(self) -> str:
        return f"b'{self.name}'{self.coordinate}[t]" if self.kind == "b" else f"g'{self.name}[t]"


def parse_coordinate_name(text: str, file=None, line=None) -> CoordinateName:
    """``b'body'x[t]`` or ``g'name[t]`` (either quote; ``[t]`` optional)."""
    token = text.strip()
    m = _BODY.fullmatch(token)
    if m:
        coordinate = next(c for c in BODY_COORDINATES if c.lower() == m.group(2).lower())
        return CoordinateName("b", m.group(1), coordinate)
    m = _FREE.fullmatch(token)
    if m:
        return CoordinateName("g", m.group(1))
    raise ModelError(f"'{token}' is not a coordinate like b'body'x[t] or g'name[t]", file, line)


@dataclass
class CoordinatesFile:
    """A ``.gc`` file: the generalized coordinates q in order."""

    coordinates: list[CoordinateName] = field(default_factory=list)
    lines: list[int] = field(default_factory=list, compare=False)
    path: Path | None = field(default=None, compare=False)


def parse_coordinates(text: str, path: str | Path | None = None) -> CoordinatesFile:
    names, numbers = [], []
    for line in significant_lines(text, path):
        name = parse_coordinate_name(line.text, path, line.number)
        if name in names:
            raise ModelError(f"coordinate {name} listed twice", path, line.number)
        names.append(name)
        numbers.append(line.number)
    return CoordinatesFile(names, numbers, Path(path) if path else None)


def format_coordinates(gc: CoordinatesFile) -> str:
    return "".join(f"{name}\n" for name in gc.coordinates)


@dataclass
class DependentCoordinate:
    """One ``%%%new%%%`` block of a ``.dc`` file.

    ``definition`` holds the position expression, optionally followed by the velocity and the
    acceleration expressions; ``jacobian`` (J, one expression per generalized coordinate) and
    ``jacobian_scalar`` (j, with c'' = J.q'' + j) are None when the block leaves them out.
    """

    coordinate: CoordinateName
    definition: list[Located]
    jacobian: list[Located] | None = None
    jacobian_scalar: Located | None = None
    line: int | None = field(default=None, compare=False)


@dataclass
class DependentCoordinatesFile:
    coordinates: list[DependentCoordinate] = field(default_factory=list)
    path: Path | None = field(default=None, compare=False)


def parse_dependent_coordinates(text: str, path: str | Path | None = None) -> DependentCoordinatesFile:
    """Blocks of ``%%%new%%%``, name, ``%%definition`` (1 or 3 lines), ``%%J``, ``%%j``."""
    blocks: list[dict] = []
    part = None
    for line in significant_lines(text, path):
        if is_directive(line, "%%%new%%%"):
            blocks.append({"line": line.number, "name": None, "definition": [], "J": None, "j": None})
            part = "name"
            continue
        if not blocks:
            raise ModelError(f"expected %%%new%%% before '{line.text}'", path, line.number)
        block = blocks[-1]
        for directive, key in (("%%definition", "definition"), ("%%J", "J"), ("%%j", "j")):
            if is_directive(line, directive):
                if block["name"] is None:
                    raise ModelError(f"{directive} before the coordinate's name", path, line.number)
                if key != "definition":
                    if block[key] is not None:
                        raise ModelError(f"{directive} given twice in one block", path, line.number)
                    block[key] = []
                part = key
                rest = line.text[len(directive) :].strip()
                if rest:
                    block[key].append(Located(rest, line.number))
                break
        else:
            if part == "name":
                if block["name"] is not None:
                    raise ModelError(f"expected %%definition after the coordinate's name, found '{line.text}'", path, line.number)
                block["name"] = (parse_coordinate_name(line.text, path, line.number), line.number)
            else:
                block[part].append(Located(line.text, line.number))
    coordinates = []
    for block in blocks:
        if block["name"] is None:
            raise ModelError("%%%new%%% block without a coordinate name", path, block["line"])
        name, name_line = block["name"]
        if len(block["definition"]) not in (1, 3):
            raise ModelError(
                f"%%definition of {name} needs 1 (position) or 3 (position, velocity, acceleration) "
                f"expressions, found {len(block['definition'])}",
                path,
                name_line,
            )
        if block["j"] is not None and len(block["j"]) != 1:
            raise ModelError(f"%%j of {name} needs exactly one expression, found {len(block['j'])}", path, name_line)
        if any(c.coordinate == name for c in coordinates):
            raise ModelError(f"dependent coordinate {name} defined twice", path, name_line)
        coordinates.append(
            DependentCoordinate(name, block["definition"], block["J"], block["j"][0] if block["j"] else None, name_line)
        )
    return DependentCoordinatesFile(coordinates, Path(path) if path else None)


def format_dependent_coordinates(dc: DependentCoordinatesFile) -> str:
    lines = []
    for c in dc.coordinates:
        lines += ["%%%new%%%", str(c.coordinate), "%%definition", *(e.text for e in c.definition)]
        if c.jacobian is not None:
            lines += ["%%J", *(e.text for e in c.jacobian)]
        if c.jacobian_scalar is not None:
            lines += ["%%j", c.jacobian_scalar.text]
    return "".join(f"{line}\n" for line in lines)
