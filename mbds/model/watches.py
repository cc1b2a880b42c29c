"""Watches of an assembled model: which shape points are reported, singly or summed."""

from __future__ import annotations

from dataclasses import dataclass

from mbds.errors import ModelError, warn
from mbds.io.folder import ModelFiles
from mbds.model.bodies import Body


@dataclass(frozen=True)
class Watch:
    """Points (0-based) of body ``body`` (index) summed into one watch; ``absolute`` reports
    impulses in x-y instead of normal-tangential. ``label`` names it in outputs, as in
    ``mass1#0`` (point 0), ``mass1#1:3`` (points 1 to 3 summed) or ``mass1#[1:3]`` (x-y)."""

    body: int
    points: tuple[int, ...]
    absolute: bool
    label: str


def assemble_watches(files: ModelFiles, bodies: list[Body], version: int = 0) -> list[Watch]:
    """The watches of ``version`` (its ``[body:k]`` sections chosen by ``reshapingCycles``)."""
    wtc = files.watches
    index = {b.name: i for i, b in enumerate(bodies)}
    watches: list[Watch] = []
    for section in wtc.bodies:
        if section.body not in index:
            raise ModelError(f"[{section.title}] names no body (bodies: {', '.join(index)})", wtc.path, section.line)
    for name, i in index.items():
        section = wtc.section_for(name, version)
        if section is None:
            continue
        count = bodies[i].point_count
        for item in section.items:
            if item.last is not None and item.last >= count:
                raise ModelError(
                    f"contactWatch point {item.last} of body '{name}' does not exist (points 0 to {count - 1})",
                    wtc.path,
                    section.line,
                )
            for group in item.groups(count):
                text = str(group[0]) if len(group) == 1 else f"{group[0]}:{group[-1]}"
                label = f"{name}#[{text}]" if item.absolute else f"{name}#{text}"
                watch = Watch(i, tuple(group), item.absolute, label)
                if any(w.label == label for w in watches):
                    warn(f"watch {label} is listed twice (kept once)", wtc.path, section.line)
                    continue
                watches.append(watch)
    return watches
