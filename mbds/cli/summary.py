"""The readable summary of a model that ``mbds check`` prints."""

from __future__ import annotations

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from mbds.model.bodies import BINDING_NAMES, POSE
from mbds.model.load import Model


def print_summary(model: Model, console: Console) -> None:
    """Bodies, coordinates, dependent coordinates, contact pairs and watches of ``model``."""
    s = model.settings
    console.print(f"[bold]model[/bold] {escape(str(model.world_path))}")
    console.print(
        f"break time {model.break_time:g} s, time step {s.minimum_timestep:g} .. {s.maximum_timestep:g} s, "
        f"maximum penetration {s.maximum_penetration:g} m"
    )
    bodies = Table(title="bodies", title_justify="left")
    for column in ("body", "mass [kg]", "Jzz [kg m^2]", "points", "x", "y", "Rz", "notes"):
        bodies.add_column(column)
    for b in model.bodies:
        if b.virtual:
            moves = ["virtual"] * 3
            notes = f"moves with {model.bodies[b.carrier].name}"
        else:
            moves = [_binding(b, axis, model) for axis in range(len(POSE))]
            derived = [name for name, flag in (("mass", b.mass_derived), ("Jzz", b.inertia_derived)) if flag]
            notes = f"{' and '.join(derived)} from shape" if derived else ""
        bodies.add_row(escape(b.name), f"{b.mass:.6g}", f"{b.inertia:.6g}", str(b.point_count), *moves, notes)
    console.print(bodies)
    coords = Table(title=f"generalized coordinates ({len(model.coordinates)})", title_justify="left")
    for column in ("q", "coordinate", "start", "start velocity"):
        coords.add_column(column)
    for k, c in enumerate(model.coordinates):
        coords.add_row(str(k), str(c), f"{model.q0[k]:.6g}", f"{model.qd0[k]:.6g}")
    console.print(coords)
    if model.dependent:
        console.print("dependent coordinates: " + ", ".join(str(c) for c in model.dependent))
    pairs = Table(title=f"contact pairs ({len(model.pairs)})", title_justify="left")
    for column in ("pair", "friction", "restitution n", "restitution t", "parameterNi", "resisting", "from"):
        pairs.add_column(column)
    for p in model.pairs:
        law = model.laws[p.law]
        resisting = ":".join("T" if r else "F" for r in p.resisting)
        pairs.add_row(
            f"{model.bodies[p.first].name}-{model.bodies[p.second].name}",
            law.friction.text,
            law.restitution_normal.text,
            law.restitution_tangent.text,
            law.parameter_ni.text,
            resisting,
            escape(", ".join(f"[{t}]" for t in p.sections)),
        )
    console.print(pairs)
    labels = [w.label for w in model.watches]
    shown = ", ".join(labels[:12]) + (f", ... ({len(labels)} in all)" if len(labels) > 12 else "")
    console.print(f"watches ({len(labels)}): {escape(shown) or 'none'}")
    if model.source.missing:
        console.print("optional files absent: " + ", ".join(model.source.missing))
    if model.compiled is not None:
        console.print(f"compiled functions: {model.compiled.source_path}")


def _binding(body, axis: int, model: Model) -> str:
    kind = body.binding[axis]
    index = body.binding_index[axis]
    if BINDING_NAMES[kind] == "generalized":
        return f"q{index}"
    if BINDING_NAMES[kind] == "dependent":
        return "dependent"
    return f"fixed {body.start_position[axis]:g}"
