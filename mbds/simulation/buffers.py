"""The arrays the kernel's stepper takes: model tuple, settings, state, workspace, outputs."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mbds.kernel import layout as K
from mbds.kernel.lcp import lcp_workspace
from mbds.model.arrays import KernelArrays
from mbds.model.load import Model


def model_tuple(a: KernelArrays) -> K.ModelArrays:
    """The ``model`` argument of the stepper."""
    return K.ModelArrays(
        a.binding, a.binding_index, a.start_pose, a.carrier, a.offset, a.points, a.point_start, a.point_reflex,
        a.concave, a.skin, a.displacement_factor, a.radius, a.pair_bodies, a.pair_law, a.pair_resisting,
        a.pair_temperature, a.pair_heated, a.point_heat, a.watch_start, a.watch_points, a.parameters,
    )


@dataclass
class RunSettings:
    """What a run takes beyond the model: break time (s), the seed of the lexicographic
    tolerance draws and their range (none when the upper end is 0), the LCP pivot limit, and the
    passes of the step loop after which the stepper returns to its caller (who looks at Ctrl-C,
    time limits and progress then: 2000 passes take well under a second)."""

    break_time: float
    seed: int = 0
    lexico_range: tuple[float, float] = (0.0, 0.0)
    max_pivots: int = 100000
    passes_per_call: int = 2000


def settings_array(model: Model, run: RunSettings) -> np.ndarray:
    """The stepper's settings array from the model's and the run's settings."""
    s = model.settings
    out = np.zeros(K.SETTINGS)
    out[K.DT_MIN] = s.minimum_timestep
    out[K.DT_MAX] = s.maximum_timestep
    out[K.MAX_PEN] = s.maximum_penetration
    out[K.ZERO_VELOCITY] = s.zero_velocity_tolerance
    out[K.PIVOT_MIN] = s.lcp_pivot_tolerance_min
    out[K.PIVOT_MAX] = s.lcp_pivot_tolerance_max
    out[K.LEXICO] = s.lcp_lexico_zero_tolerance
    out[K.LEXICO_LOW], out[K.LEXICO_HIGH] = run.lexico_range
    out[K.GO_BACK] = float(s.try_to_solve_by_going_back)
    out[K.SAMPLE_EVERY] = s.sample_interval
    out[K.SAMPLE_AT_COLLISION] = float(s.history_at_collision)
    out[K.SAMPLE_EACH_STEP] = float(s.history_each_timestep)
    out[K.MAX_PIVOTS] = run.max_pivots
    out[K.PASSES_PER_CALL] = run.passes_per_call
    return out


def workspace(n: int, m: int, nb: int, points: int, pairs: int, capacity: int) -> K.Workspace:
    """Scratch arrays of the stepper (see mbds.kernel.layout.workspace)."""
    fwork, iwork = lcp_workspace(3 * capacity)
    return K.workspace(n, m, nb, points, pairs, capacity, fwork, iwork)


def grown(ws: K.Workspace, bigger: K.Workspace) -> K.Workspace:
    """``bigger``, a workspace for more contacts, holding what ``ws`` holds: each array copied
    into the leading part of its larger twin. The run then goes on as if it had had the room
    from its start: the steps it may go back to, the tracked contacts and the remembered contact
    states stay."""
    for old_bundle, new_bundle in zip(ws, bigger):
        for old, new in zip(old_bundle, new_bundle):
            part = tuple(slice(0, min(a, b)) for a, b in zip(old.shape, new.shape))
            new[part] = old[part]
    return bigger


def event_buffer(length: int) -> K.Events:
    """Room for ``length`` kernel events."""
    return K.Events(np.zeros((length, 4)), np.zeros(1, dtype=np.int64))

