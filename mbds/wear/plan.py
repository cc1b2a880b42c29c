"""What the next version of a model changes: reshaped bodies and updated constants.

The ``.wtc`` sections of the version that ran (``[body:k]`` with k = version mod
``reshapingCycles``, else ``[body]``) decide which points are watched and how they move; see
:mod:`mbds.wear.reshape` for the rule. Constants change in two ways, in this order:

- ``[constantsUpdate]``: constant k of the list moves by maxChange * W_k / max_j W_j, with W_k the
  total lost work of body k (the sum over its points of their losses, clipped by the reshape
  window computed jointly over the listed bodies);
- ``[changeConstants]``: each listed constant is incremented by its ``change``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mbds.errors import ModelError
from mbds.io.folder import ModelFiles
from mbds.io.text import QUOTES
from mbds.model.geometry import smooth_closed
from mbds.wear.reshape import (
    BodyWear,
    directions,
    displacements,
    loss_window,
    moved_shape,
)


@dataclass
class WearPlan:
    """The reshaped bodies and the constants before and after the update."""

    bodies: list[BodyWear] = field(default_factory=list)
    constants_before: dict[str, float] = field(default_factory=dict)
    constants_after: dict[str, float] = field(default_factory=dict)


def plan_wear(files: ModelFiles, losses: dict[str, np.ndarray], version: int) -> WearPlan:
    """The changes from version ``version`` to the next, given the lost work (J) accumulated
    at each distinct shape point of each body (``losses[name]``, length = points - 1)."""
    wtc = files.watches
    shapes = {b.main.name: s for b, s in zip(files.bodies, files.shapes)}
    for name, loss in losses.items():
        if name in shapes and len(loss) != len(shapes[name].points) - 1:
            raise ModelError(f"lost work of body '{name}' has {len(loss)} points, its shape {len(shapes[name].points) - 1}")
    smoothing = wtc.common.smooth_work_left_right
    balanced = set(wtc.body_balanced_update.bodies) if wtc.body_balanced_update else set()
    selected = {}
    for name in shapes:
        section = wtc.section_for(name, version)
        if section is None or not section.items:
            continue
        options = section.options
        moves = options.direction_inside != 0 or options.direction_x != 0 or options.direction_y != 0
        if not moves or (not any(options.max_change) and name not in balanced):
            continue
        count = len(shapes[name].points) - 1
        points = np.array(sorted({p for item in section.items for group in item.groups(count) for p in group}))
        loss = smooth_closed(losses.get(name, np.zeros(count)), smoothing)[points]
        selected[name] = (section, points, loss)
    plan = WearPlan()
    together = [name for name in selected if name in balanced]
    if together:
        window = loss_window(np.concatenate([selected[n][2] for n in together]), wtc.reshape_window)
        for name in together:
            plan.bodies.append(_wear(name, selected[name], window, [wtc.body_balanced_update.max_change], shapes))
    for name, entry in selected.items():
        if name not in balanced:
            window = loss_window(entry[2], wtc.reshape_window)
            plan.bodies.append(_wear(name, entry, window, entry[0].options.max_change, shapes))
    plan.constants_before = dict(files.constants.values)
    plan.constants_after = _updated_constants(files, losses, smoothing)
    return plan


def _wear(name, entry, window, max_change, shapes) -> BodyWear:
    section, points, loss = entry
    options = section.options
    clipped, moves = displacements(loss, window, max_change)
    shape = shapes[name]
    direction = directions(shape.points, points, options.direction_inside, (options.direction_x, options.direction_y))
    new = moved_shape(name, shape.points, points, moves, direction, shape.path)
    return BodyWear(name, points, clipped, moves, direction, new)


def _constant_name(text: str, files: ModelFiles) -> str:
    name = text.strip()
    if len(name) > 2 and name[0] == "c" and name[1] in QUOTES:
        name = name[2:]
    if name not in files.constants.values:
        raise ModelError(f"the watches file changes constant c'{name}, which the .cns file does not define", files.watches.path)
    return name


def _updated_constants(files: ModelFiles, losses: dict[str, np.ndarray], smoothing: int) -> dict[str, float]:
    wtc = files.watches
    values = dict(files.constants.values)
    update = wtc.constants_update
    if update is not None and update.bodies:
        for body in update.bodies:
            if body not in losses:
                raise ModelError(f"[constantsUpdate] names body '{body}', which has no recorded losses", wtc.path)
        point_losses = {body: smooth_closed(losses[body], smoothing) for body in update.bodies}
        window = loss_window(np.concatenate(list(point_losses.values())), wtc.reshape_window)
        totals = np.array([np.clip(point_losses[b], window.low, window.high).sum() for b in update.bodies])
        top = totals.max()
        for constant, total in zip(update.constants, totals):
            name = _constant_name(constant, files)
            values[name] += update.max_change * total / top if top > 0 else 0.0
    change = wtc.change_constants
    if change is not None:
        for constant, step in zip(change.constants, change.changes):
            values[_constant_name(constant, files)] += step
    return values
