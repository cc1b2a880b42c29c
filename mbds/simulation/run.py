"""The run loop: call the compiled stepper until the break time, collecting its outputs."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from mbds.data.run_result import RunResult, RunState, Samples
from mbds.kernel import layout as K
from mbds.kernel.random import seeded_state
from mbds.model.arrays import KernelArrays, flatten
from mbds.model.load import Model
from mbds.simulation.buffers import (
    RunSettings,
    event_buffer,
    grown,
    model_tuple,
    settings_array,
    workspace,
)

HISTORY_CHUNK = 4096
EVENT_CHUNK = 1024
CONTACT_CAPACITY = 16
"""Simultaneous contacts a run's workspace holds at its start; it doubles whenever detection finds
more."""


class RunStopped(Exception):
    """Raised by a callback of :func:`simulate` to end the run early; its message says why."""


def initial_state(model: Model, seed: int) -> RunState:
    """The state at t = 0 from the model's start values."""
    arrays = flatten(model)
    clock = np.zeros(K.CLOCK)
    clock[K.DT] = model.settings.maximum_timestep
    return RunState(
        clock=clock,
        q=arrays.q0.copy(),
        u=arrays.qd0.copy(),
        rng=seeded_state(seed),
        point_loss=np.zeros(len(arrays.points)),
        point_interval=initial_point_values(arrays),
    )


def initial_point_values(arrays: KernelArrays) -> np.ndarray:
    """The per-point values at the start: nothing summed yet, the temperature of points with a
    heat model at its ambient, NaN elsewhere."""
    values = np.zeros((len(arrays.points), K.POINT_COLUMNS))
    heated = arrays.point_heat[:, K.HEATING] > 0.0
    values[:, K.TEMP] = np.where(heated, arrays.point_heat[:, K.AMBIENT], np.nan)
    return values


def continue_from(state: RunState) -> None:
    """Make ``state`` (the end state of a run) start a continued run: its first history sample
    is taken at once, at the start time, as a run from the model's start takes one at t = 0."""
    state.clock[K.NEXT_SAMPLE] = state.clock[K.T]


def simulate(
    model: Model, run: RunSettings, state: RunState | None = None, progress=None, *, on_events=None,
    on_samples: Callable[[Samples], None] | None = None, chunk: int = HISTORY_CHUNK, capacity: int = CONTACT_CAPACITY,
) -> RunResult:
    """Run ``model`` from ``state`` (default: its start) to ``run.break_time``.

    Between calls of the stepper (every ``chunk`` samples or ``run.passes_per_call`` passes of
    its step loop at most, or when its event buffer is full) ``on_samples(samples)`` gets the
    samples taken since the last call (which the result then does not hold: memory does not
    grow with the run's length), ``on_events(rows)`` the event rows and ``progress(t)`` the time
    reached (s), if given. ``on_events`` or ``progress`` may raise :class:`RunStopped` or
    KeyboardInterrupt to end the run there (unless it already reached its break time): the
    samples and events so far are returned, with ``stopped`` set. Without ``on_samples`` the
    result holds the samples, written by the stepper into one buffer sized for the run (a new
    one, twice as long, when samples at collisions or at every step fill it). The result does
    not depend on ``chunk``, ``run.passes_per_call`` or the contact ``capacity`` it starts with
    (the workspace grows, keeping what it holds). A state that
    stops being finite (or a mass matrix that is not positive definite) also ends the run, with
    ``stopped`` saying so.
    """
    compiled = model.compile()
    arrays = flatten(model)
    state = state or initial_state(model, run.seed)
    mt = model_tuple(arrays)
    settings = settings_array(model, run)
    n, m, nb = len(arrays.q0), len(model.dependent), len(model.bodies)
    ws = workspace(n, m, nb, len(arrays.points), len(arrays.pair_law), capacity)
    chunks: list[Samples] = []
    collect = on_samples is None  # the result holds the samples: fill one buffer, no copies
    events: list[np.ndarray] = []
    watches = len(model.watches)
    history = K.history_buffers(n, watches, _collected_length(settings, run, state, n, watches) if collect else chunk)
    events_out = event_buffer(EVENT_CHUNK)
    stopped = ""
    while True:
        status = compiled.advance(
            mt, settings, run.break_time, state.clock, state.q, state.u, state.rng, state.point_loss,
            state.point_interval, history, events_out, ws,
        )
        if status == K.CAPACITY:
            capacity *= 2
            ws = grown(ws, workspace(n, m, nb, len(arrays.points), len(arrays.pair_law), capacity))
            continue
        if not collect:
            if history.count[0]:
                on_samples(Samples(*(a.copy() for a in _filled(history))))
            history.count[0] = 0
        elif status == K.HISTORY_FULL:
            chunks.append(_filled(history))
            history = K.history_buffers(n, watches, 2 * len(history.time))
        events.append(events_out.data[: events_out.count[0]].copy())
        events_out.count[0] = 0
        if status == K.NOT_FINITE:
            stopped = f"the state is not finite at t = {state.clock[K.T]:.9g} s"
            break
        try:
            if on_events is not None and len(events[-1]):
                on_events(events[-1])
            if progress is not None:
                progress(float(state.clock[K.T]))
        except (RunStopped, KeyboardInterrupt) as exc:
            if status != K.REACHED:
                stopped = (str(exc) or "stopped") if isinstance(exc, RunStopped) else "interrupted"
        if stopped or status == K.REACHED:
            break
    chunks.append(_filled(history))  # empty unless collecting
    samples = chunks[-1] if len(chunks) == 1 else Samples(*(np.concatenate(c) for c in zip(*chunks)))
    return RunResult(samples, np.concatenate(events), state, capacity=capacity, stopped=stopped)


COLLECTED_BYTES = 1 << 28
"""Largest history buffer (bytes) a run that keeps its samples in memory starts with."""


def _collected_length(settings: np.ndarray, run: RunSettings, state: RunState, n: int, watches: int) -> int:
    """Samples of the history buffer of a run that keeps them in memory: one per sample
    interval up to the break time and HISTORY_CHUNK more (samples at collisions or at every
    step make the buffer grow), at most COLLECTED_BYTES."""
    per_sample = 8 * (4 + 3 * n + watches * K.POINT_COLUMNS)
    expected = HISTORY_CHUNK
    if settings[K.SAMPLE_EACH_STEP] == 0.0:
        expected += int(max(run.break_time - state.clock[K.T], 0.0) / settings[K.SAMPLE_EVERY]) + 1
    return max(HISTORY_CHUNK, min(expected, COLLECTED_BYTES // per_sample))


def _filled(history: K.History) -> Samples:
    """Views of the samples written into ``history``."""
    count = int(history.count[0])
    return Samples(*(a[:count] for a in history[:-1]))
