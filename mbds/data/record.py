"""Everything the output files of one run hold, computed once from the run's result."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mbds.data.poses import body_poses, dependent_series
from mbds.data.watches import WatchSeries, distinct_points, smooth_points, watch_series
from mbds.io.coordinates import CoordinateName
from mbds.kernel import layout as K
from mbds.model.arrays import flatten
from mbds.model.bodies import FIXED, Body
from mbds.model.load import Model
from mbds.simulation.run import RunResult, RunState

COUNTERS = {
    "steps": K.STEPS,
    "impacts": K.IMPACTS,
    "rejected_steps": K.REJECTED,
    "lcp_failures": K.LCP_FAILURES,
    "over_penetrations": K.OVER_PENETRATIONS,
}
LENGTH_COORDINATES = ("x", "y", "z")


@dataclass
class RunRecord:
    """One run of a model version, ready to be written.

    Times in s; ``lost_work``/``driver_work`` (J) count from the start of this run, as do the
    per-point losses (J, distinct shape points of all bodies, see ``point_body``) and the
    ``counters``; ``max_penetration`` (m) is the largest since the chain of runs began;
    ``final_state`` is the exact kernel state at ``end_time``. ``dependent_position`` (samples,
    dependent) holds the ``.dc`` coordinates, ``pose`` (samples, bodies, 3) every body's x, y (m)
    and Rz (rad); ``watch_body``/``watch_points`` the body and first and last point of each watch;
    ``body_kind`` is moving, fixed or virtual and ``body_color`` its RGBColor (0-1); ``wall_time`` (s) how long the run took.
    """

    model: str
    version: int
    seed: int
    coordinates: list[str]
    coordinate_units: list[str]
    time: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    energy: np.ndarray
    lost_work: np.ndarray
    driver_work: np.ndarray
    watch_labels: list[str]
    watch_absolute: np.ndarray
    watches: WatchSeries
    bodies: list[str]
    point_body: np.ndarray
    point_number: np.ndarray
    shape: np.ndarray
    point_lost_work: np.ndarray
    point_lost_work_smoothed: np.ndarray
    start_time: float
    end_time: float
    break_time: float
    stopped: str
    start_energy: float
    end_energy: float
    run_lost_work: float
    run_driver_work: float
    counters: dict[str, int]
    max_penetration: float
    final_state: RunState
    options: dict[str, float]
    watch_body: list[str] = field(default_factory=list)
    watch_points: list[tuple[int, int]] = field(default_factory=list)
    dependent: list[str] = field(default_factory=list)
    dependent_units: list[str] = field(default_factory=list)
    dependent_position: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    pose: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 3)))
    body_kind: list[str] = field(default_factory=list)
    body_color: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    inputs: dict[str, str] = field(default_factory=dict)
    wall_time: float = float("nan")
    continued_from: int | None = None
    alerts: list[str] = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return not self.stopped

    @property
    def energy_residual(self) -> float:
        """E(end) - E(start) + lost work - driver work (J); 0 up to integration error."""
        return self.end_energy - self.start_energy + self.run_lost_work - self.run_driver_work


def coordinate_label(name: CoordinateName) -> str:
    """``b'mass1'x`` (the .gc name without ``[t]``)."""
    return str(name).removesuffix("[t]")


def coordinate_unit(name: CoordinateName) -> str:
    """m or rad for body coordinates; 1 for free ``g'`` coordinates (the model sets what they mean)."""
    if name.kind != "b":
        return "1"
    return "m" if name.coordinate in LENGTH_COORDINATES else "rad"


def make_record(
    model: Model, result: RunResult, start: RunState, *, seed: int, break_time: float,
    continued_from: int | None = None, folder: Path | None = None,
) -> RunRecord:
    """The record of ``result``, a run of ``model`` from ``start`` (a copy of the state it
    started from) to ``break_time`` (s); ``folder`` holds the input files to keep."""
    arrays = flatten(model)
    compiled = model.compile()
    end = result.state
    counts = np.diff(arrays.point_start) - 1
    starts = np.concatenate([[0], np.cumsum(counts)])
    point_loss = distinct_points(end.point_loss - start.point_loss, arrays.point_start)
    common = model.files.watches.common
    t0 = float(start.clock[K.T])
    intervals = np.diff(result.time, prepend=t0)

    def energy(state: RunState) -> float:
        return float(compiled.mechanical_energy(state.q, state.u, state.clock[K.T], arrays.parameters))

    dependent = dependent_series(compiled, arrays.parameters, result.time, result.q, result.u, result.a)
    return RunRecord(
        model=model.name,
        version=model.version,
        seed=seed,
        coordinates=[coordinate_label(c) for c in model.coordinates],
        coordinate_units=[coordinate_unit(c) for c in model.coordinates],
        time=result.time,
        q=result.q,
        qd=result.u,
        qdd=result.a,
        energy=result.energy,
        lost_work=result.lost - start.clock[K.LOST],
        driver_work=result.drive - start.clock[K.DRIVE_WORK],
        watch_labels=[w.label for w in model.watches],
        watch_absolute=np.array([w.absolute for w in model.watches], dtype=bool),
        watches=watch_series(result.watches, intervals, common),
        bodies=[b.name for b in model.bodies],
        point_body=np.repeat(np.arange(len(counts)), counts),
        point_number=np.concatenate([np.arange(c) for c in counts]) if len(counts) else np.zeros(0, int),
        shape=np.concatenate([b.points[:-1] for b in model.bodies]),
        point_lost_work=point_loss,
        point_lost_work_smoothed=smooth_points(point_loss, starts, common.smooth_work_left_right),
        start_time=t0,
        end_time=float(end.clock[K.T]),
        break_time=break_time,
        stopped=result.stopped,
        start_energy=energy(start),
        end_energy=energy(end),
        run_lost_work=float(end.clock[K.LOST] - start.clock[K.LOST]),
        run_driver_work=float(end.clock[K.DRIVE_WORK] - start.clock[K.DRIVE_WORK]),
        counters={name: int(end.clock[i] - start.clock[i]) for name, i in COUNTERS.items()},
        max_penetration=float(end.clock[K.MAX_PENETRATION]),
        final_state=end,
        options={
            "time_constant": common.time_constant,
            "convert_impulse_to_force": int(common.convert_impulse_to_force),
            "cumulative_work": int(common.cumulative_work),
            "averaged_t_div_n": int(common.write_averaged_t_div_n),
            "angle_instead_of_work": int(common.absolute_angle_instead_of_work),
            "smooth_work_left_right": common.smooth_work_left_right,
        },
        watch_body=[model.bodies[w.body].name for w in model.watches],
        watch_points=[(w.points[0], w.points[-1]) for w in model.watches],
        dependent=[coordinate_label(c) for c in model.dependent],
        dependent_units=[coordinate_unit(c) for c in model.dependent],
        dependent_position=dependent.position,
        pose=body_poses(arrays, result.q, dependent.position),
        body_kind=[body_kind(b) for b in model.bodies],
        body_color=np.array([body_color(f.main.rgb_color) for f in model.files.bodies]).reshape(-1, 3),
        inputs=_inputs(model, folder),
        continued_from=continued_from,
    )


def body_kind(body: Body) -> str:
    """virtual (moves with its carrier), fixed (no coordinate moves it) or moving."""
    if body.virtual:
        return "virtual"
    return "fixed" if all(kind == FIXED for kind in body.binding) else "moving"


def body_color(text: str) -> tuple[float, float, float]:
    """The ``RGBColor`` of a ``.bdy`` file (three numbers 0-1); green, the default, when unreadable."""
    try:
        red, green, blue = (min(max(float(v), 0.0), 1.0) for v in text.split())
    except ValueError:
        return (0.0, 1.0, 0.0)
    return (red, green, blue)


def _inputs(model: Model, folder: Path | None) -> dict[str, str]:
    """Text of every model file, by path relative to ``folder`` (or by name)."""
    out = {}
    for path in model.files.paths():
        name = path.relative_to(folder).as_posix() if folder and path.is_relative_to(folder) else path.name
        out[name] = path.read_text(encoding="utf-8", errors="replace")
    return out
