"""The run loop: call the compiled stepper until the break time, collecting its outputs."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mbds.kernel import stepper as K
from mbds.kernel.random import seeded_state
from mbds.model.arrays import flatten
from mbds.model.load import Model
from mbds.simulation.buffers import RunSettings, history_buffers, model_tuple, settings_array, workspace

HISTORY_CHUNK = 4096
EVENT_CHUNK = 1024


@dataclass
class RunState:
    """Everything that changes during a run (enough to continue it exactly)."""

    clock: np.ndarray
    q: np.ndarray
    u: np.ndarray
    rng: np.ndarray
    point_loss: np.ndarray
    point_interval: np.ndarray


@dataclass
class RunResult:
    """Samples of a run: time (s), q, u, q'' (n columns), mechanical energy (J), lost work and
    drive work (J, cumulative), watch interval sums (samples, watches, POINT_COLUMNS); events
    (rows: time, code, value, value); the final state."""

    time: np.ndarray
    q: np.ndarray
    u: np.ndarray
    a: np.ndarray
    energy: np.ndarray
    lost: np.ndarray
    drive: np.ndarray
    watches: np.ndarray
    events: np.ndarray
    state: RunState
    capacity: int = field(default=0)


def initial_state(model: Model, seed: int) -> RunState:
    """The state at t = 0 from the model's start values."""
    arrays = flatten(model)
    clock = np.zeros(K.CLOCK)
    clock[K.DT] = model.files.world.settings.maximum_timestep
    return RunState(
        clock=clock,
        q=arrays.q0.copy(),
        u=arrays.qd0.copy(),
        rng=seeded_state(seed),
        point_loss=np.zeros(len(arrays.points)),
        point_interval=np.zeros((len(arrays.points), K.POINT_COLUMNS)),
    )


def simulate(model: Model, run: RunSettings, state: RunState | None = None, progress=None) -> RunResult:
    """Run ``model`` from ``state`` (default: its start) to ``run.break_time``.

    ``progress(t)`` is called between chunks, if given. Raises RuntimeError when the state
    stops being finite.
    """
    compiled = model.compile()
    arrays = flatten(model)
    state = state or initial_state(model, run.seed)
    mt = model_tuple(arrays)
    settings = settings_array(model, run)
    n, m, nb = len(arrays.q0), len(model.dependent), len(model.bodies)
    capacity = 16
    ws = workspace(n, m, nb, len(arrays.points), len(arrays.pair_law), capacity)
    chunks: list[tuple] = []
    events: list[np.ndarray] = []
    history = history_buffers(n, len(model.watches), HISTORY_CHUNK)
    event_buffer = (np.zeros((EVENT_CHUNK, 4)), np.zeros(1, dtype=np.int64))
    while True:
        status = compiled.advance(
            mt, settings, run.break_time, state.clock, state.q, state.u, state.rng, state.point_loss,
            state.point_interval, history, event_buffer, ws,
        )
        if status == K.CAPACITY:
            capacity *= 2
            ws = workspace(n, m, nb, len(arrays.points), len(arrays.pair_law), capacity)
            continue
        if status in (K.HISTORY_FULL, K.REACHED):
            count = int(history[-1][0])
            chunks.append(tuple(a[:count].copy() for a in history[:-1]))
            history[-1][0] = 0
        if status in (K.EVENTS_FULL, K.REACHED, K.HISTORY_FULL, K.NOT_FINITE):
            events.append(event_buffer[0][: event_buffer[1][0]].copy())
            event_buffer[1][0] = 0
        if progress is not None:
            progress(float(state.clock[K.T]))
        if status == K.REACHED:
            break
        if status == K.NOT_FINITE:
            raise RuntimeError(f"the state is not finite at t = {state.clock[K.T]:.9g} s")
    columns = [np.concatenate([c[j] for c in chunks]) for j in range(8)]
    return RunResult(*columns, events=np.concatenate(events) if events else np.zeros((0, 4)), state=state, capacity=capacity)
