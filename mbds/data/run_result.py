"""What a run of the contact stepper gives back: its samples, events and final state (the
types mbds.simulation.run fills and the output writers of mbds.data read)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np


@dataclass
class RunState:
    """Everything that changes during a run (enough to continue it exactly)."""

    clock: np.ndarray
    q: np.ndarray
    u: np.ndarray
    rng: np.ndarray
    point_loss: np.ndarray
    point_interval: np.ndarray


class Samples(NamedTuple):
    """History samples of part of a run: time (s), q, u, q'' (samples, n), mechanical energy,
    lost work and drive work (J, cumulative), watch interval sums (samples, watches,
    POINT_COLUMNS)."""

    time: np.ndarray
    q: np.ndarray
    u: np.ndarray
    a: np.ndarray
    energy: np.ndarray
    lost: np.ndarray
    drive: np.ndarray
    watches: np.ndarray


@dataclass
class RunResult:
    """A run: its samples (also read as ``result.time``, ``result.q``, ...; with no row when
    they went to an ``on_samples`` callback of :func:`simulate`), its events (rows: time, code,
    value, value) and its final state."""

    samples: Samples
    events: np.ndarray
    state: RunState
    capacity: int = field(default=0)
    stopped: str = ""  # why the run ended before its break time ("" when it reached it)

    @property
    def complete(self) -> bool:
        return not self.stopped

    def __getattr__(self, name: str):
        if name in Samples._fields:
            return getattr(self.samples, name)
        raise AttributeError(name)
