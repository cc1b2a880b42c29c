"""What the output files of one run hold: its header, known when it starts; its samples, turned
into series part after part as the run makes them; its summary, made when it ends."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mbds.data.poses import body_poses, dependent_series
from mbds.data.run_result import RunResult, RunState, Samples
from mbds.data.watches import (
    IMPULSE_COLUMNS,
    WatchCarry,
    WatchSeries,
    distinct_points,
    smooth_points,
    watch_series,
)
from mbds.io.coordinates import CoordinateName
from mbds.kernel import layout as K
from mbds.model.arrays import flatten
from mbds.model.bodies import FIXED, Body

if TYPE_CHECKING:  # the loader imports sympy: reading outputs does not need it
    from mbds.model.load import Model

COUNTERS = {
    "steps": K.STEPS,
    "impacts": K.IMPACTS,
    "rejected_steps": K.REJECTED,
    "lcp_failures": K.LCP_FAILURES,
    "over_penetrations": K.OVER_PENETRATIONS,
}
LENGTH_COORDINATES = ("x", "y", "z")


@dataclass(kw_only=True)
class RunHeader:
    """What the outputs of one run of a model version hold that is known before it starts.

    ``coordinates``/``dependent`` with their UDUNITS units; ``watch_body``/``watch_points`` the
    body and first and last point of each watch; ``body_kind`` is moving, fixed or virtual and
    ``body_color`` its RGBColor (0-1); ``point_body``/``point_number``/``shape`` (m) the distinct
    shape points of all bodies; ``options`` the watch options; ``inputs`` the model files' text;
    ``start_time``/``break_time`` (s).
    """

    model: str
    version: int
    seed: int
    coordinates: list[str]
    coordinate_units: list[str]
    dependent: list[str]
    dependent_units: list[str]
    watch_labels: list[str]
    watch_absolute: np.ndarray
    watch_body: list[str]
    watch_points: list[tuple[int, int]]
    bodies: list[str]
    body_kind: list[str]
    body_color: np.ndarray
    point_body: np.ndarray
    point_number: np.ndarray
    shape: np.ndarray
    options: dict[str, float]
    inputs: dict[str, str]
    start_time: float
    break_time: float
    continued_from: int | None = None

    @property
    def force(self) -> bool:
        """Whether the watches write forces (N) rather than impulses (N s)."""
        return bool(self.options["convert_impulse_to_force"])


@dataclass(kw_only=True)
class RunRecord(RunHeader):
    """One run of a model version, ended: its header and its summary. (The samples went to the
    output files as the run made them.)

    Times in s; ``run_lost_work``/``run_driver_work`` (J) and the ``counters`` count from the
    start of this run, as do the per-point losses (J, distinct shape points of all bodies);
    ``max_penetration`` (m) is the largest since the chain of runs began; ``final_state`` is the
    exact kernel state at ``end_time``; ``first_sample``/``last_sample`` the times of the first
    and last history samples and ``samples`` their number; ``wall_time`` (s) how long the run
    took.
    """

    end_time: float
    stopped: str
    start_energy: float
    end_energy: float
    run_lost_work: float
    run_driver_work: float
    counters: dict[str, int]
    max_penetration: float
    final_state: RunState
    point_lost_work: np.ndarray
    point_lost_work_smoothed: np.ndarray
    first_sample: float
    last_sample: float
    samples: int
    wall_time: float = float("nan")
    alerts: list[str] = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return not self.stopped

    @property
    def energy_residual(self) -> float:
        """E(end) - E(start) + lost work - driver work (J); 0 up to integration error."""
        return self.end_energy - self.start_energy + self.run_lost_work - self.run_driver_work


@dataclass
class SampleSeries:
    """The history samples of part of a run: time (s), q, qd, qdd (samples, coordinates),
    mechanical energy, lost and driver work since the run's start (J), the watch outputs, the
    dependent coordinates (samples, dependent) and every body's pose (samples, bodies, x m,
    y m, Rz rad)."""

    time: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    energy: np.ndarray
    lost_work: np.ndarray
    driver_work: np.ndarray
    watches: WatchSeries
    dependent_position: np.ndarray
    pose: np.ndarray


def empty_series(header: RunHeader) -> SampleSeries:
    """Series of no sample, with the columns of ``header``'s run."""
    n, m, nb, nw = len(header.coordinates), len(header.dependent), len(header.bodies), len(header.watch_labels)
    z = np.zeros
    options = header.options
    watches = WatchSeries(
        {name: z((0, nw)) for name in IMPULSE_COLUMNS},
        None if options["angle_instead_of_work"] else z((0, nw)),
        z((0, nw)) if options["angle_instead_of_work"] else None,
        z((0, nw)) if options["averaged_t_div_n"] else None,
        header.force,
        z((0, nw)) if options["temperature"] else None,
    )
    return SampleSeries(z(0), z((0, n)), z((0, n)), z((0, n)), z(0), z(0), z(0), watches, z((0, m)), z((0, nb, 3)))


def coordinate_label(name: CoordinateName) -> str:
    """``b'mass1'x`` (the .gc name without ``[t]``)."""
    return str(name).removesuffix("[t]")


def coordinate_unit(name: CoordinateName) -> str:
    """m or rad for body coordinates; 1 for free ``g'`` coordinates (the model sets what they mean)."""
    if name.kind != "b":
        return "1"
    return "m" if name.coordinate in LENGTH_COORDINATES else "rad"


def make_header(model: Model, start: RunState, *, seed: int, break_time: float,
                continued_from: int | None = None, folder: Path | None = None) -> RunHeader:
    """The header of a run of ``model`` from ``start`` to ``break_time`` (s); ``folder`` holds
    the input files to keep."""
    arrays = flatten(model)
    counts = np.diff(arrays.point_start) - 1
    common = model.watch_options
    return RunHeader(
        model=model.name,
        version=model.version,
        seed=seed,
        coordinates=[coordinate_label(c) for c in model.coordinates],
        coordinate_units=[coordinate_unit(c) for c in model.coordinates],
        dependent=[coordinate_label(c) for c in model.dependent],
        dependent_units=[coordinate_unit(c) for c in model.dependent],
        watch_labels=[w.label for w in model.watches],
        watch_absolute=np.array([w.absolute for w in model.watches], dtype=bool),
        watch_body=[model.bodies[w.body].name for w in model.watches],
        watch_points=[(w.points[0], w.points[-1]) for w in model.watches],
        bodies=[b.name for b in model.bodies],
        body_kind=[body_kind(b) for b in model.bodies],
        body_color=np.array([b.color for b in model.bodies], dtype=float).reshape(-1, 3),
        point_body=np.repeat(np.arange(len(counts)), counts),
        point_number=np.concatenate([np.arange(c) for c in counts]) if len(counts) else np.zeros(0, int),
        shape=np.concatenate([b.points[:-1] for b in model.bodies]),
        options={
            "time_constant": common.time_constant,
            "convert_impulse_to_force": int(common.convert_impulse_to_force),
            "cumulative_work": int(common.cumulative_work),
            "averaged_t_div_n": int(common.write_averaged_t_div_n),
            "angle_instead_of_work": int(common.absolute_angle_instead_of_work),
            "smooth_work_left_right": common.smooth_work_left_right,
            "temperature": int(any(p.heated for p in model.pairs)),
        },
        inputs=_inputs(model, folder),
        start_time=float(start.clock[K.T]),
        break_time=break_time,
        continued_from=continued_from,
    )


class SeriesMaker:
    """Turns the kernel's samples of a run of ``model`` from ``start``, part after part, into
    :class:`SampleSeries`; the watch options that run over samples (decay, cumulative work,
    T/N ratio) carry on from one part to the next, so the series do not depend on the parts."""

    def __init__(self, model: Model, start: RunState):
        self.arrays = flatten(model)
        self.compiled = model.compile()
        self.common = model.watch_options
        self.start = start
        self.previous_time = float(start.clock[K.T])
        self.carry = WatchCarry()
        self.heated = any(p.heated for p in model.pairs)

    def __call__(self, samples: Samples) -> SampleSeries:
        intervals = np.diff(samples.time, prepend=self.previous_time)
        if len(samples.time):
            self.previous_time = float(samples.time[-1])
        dependent = dependent_series(self.compiled, self.arrays.parameters, samples.time, samples.q, samples.u,
                                     samples.a)
        return SampleSeries(
            time=samples.time, q=samples.q, qd=samples.u, qdd=samples.a, energy=samples.energy,
            lost_work=samples.lost - self.start.clock[K.LOST],
            driver_work=samples.drive - self.start.clock[K.DRIVE_WORK],
            watches=watch_series(samples.watches, intervals, self.common, self.carry, self.heated),
            dependent_position=dependent.position,
            pose=body_poses(self.arrays, samples.q, dependent.position),
        )


def make_record(header: RunHeader, model: Model, result: RunResult, start: RunState, sampled: tuple[float, float, int]
                ) -> RunRecord:
    """The record of ``result``, the run of ``model`` from ``start`` (a copy of the state it
    started from) that ``header`` describes; ``sampled``: the times of its first and last
    samples (s) and their number."""
    arrays = flatten(model)
    compiled = model.compile()
    end = result.state
    counts = np.diff(arrays.point_start) - 1
    starts = np.concatenate([[0], np.cumsum(counts)])
    point_loss = distinct_points(end.point_loss - start.point_loss, arrays.point_start)

    def energy(state: RunState) -> float:
        return float(compiled.mechanical_energy(state.q, state.u, state.clock[K.T], arrays.parameters))

    first, last, samples = sampled
    return RunRecord(
        **vars(header),
        end_time=float(end.clock[K.T]),
        stopped=result.stopped,
        start_energy=energy(start),
        end_energy=energy(end),
        run_lost_work=float(end.clock[K.LOST] - start.clock[K.LOST]),
        run_driver_work=float(end.clock[K.DRIVE_WORK] - start.clock[K.DRIVE_WORK]),
        counters={name: int(end.clock[i] - start.clock[i]) for name, i in COUNTERS.items()},
        max_penetration=float(end.clock[K.MAX_PENETRATION]),
        final_state=end,
        point_lost_work=point_loss,
        point_lost_work_smoothed=smooth_points(point_loss, starts, header.options["smooth_work_left_right"]),
        first_sample=first,
        last_sample=last,
        samples=samples,
    )


def body_kind(body: Body) -> str:
    """virtual (moves with its carrier), fixed (no coordinate moves it) or moving."""
    if body.virtual:
        return "virtual"
    return "fixed" if all(kind == FIXED for kind in body.binding) else "moving"


def _inputs(model: Model, folder: Path | None) -> dict[str, str]:
    """Text of every model file, by path relative to ``folder`` (or by name)."""
    out = {}
    for path in model.source.inputs:
        name = path.relative_to(folder).as_posix() if folder and path.is_relative_to(folder) else path.name
        out[name] = path.read_text(encoding="utf-8", errors="replace")
    return out
