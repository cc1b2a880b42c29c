"""The neutral description of a system that the front-ends build (mbds.model.load for MBDS
model folders, mbds.model.dapbc for DAP_BC folders) and everything below them reads: where it
came from, and its settings in SI units. Nothing below the front-ends reads a file object."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class SystemSource:
    """Where a system came from: its ``name``, the ``path`` of its description (world file or
    model folder), the ``inputs`` read (kept as provenance) and the optional files found absent."""

    name: str
    path: Path
    inputs: tuple[Path, ...]
    missing: tuple[str, ...] = ()


@dataclass(frozen=True)
class StepSettings:
    """Settings of the contact time stepper (s, m, m/s): time-step range, largest penetration,
    zero-velocity and LCP pivot tolerances, going back two steps, when history samples are
    taken (every ``sample_interval`` s, at collisions, at each step) and which LCP troubles
    are logged. The names are those of the world file's settings (mbds.io.world)."""

    minimum_timestep: float
    maximum_timestep: float
    maximum_penetration: float
    zero_velocity_tolerance: float
    lcp_pivot_tolerance_min: float
    lcp_pivot_tolerance_max: float
    lcp_lexico_zero_tolerance: float
    try_to_solve_by_going_back: bool
    sample_interval: float
    history_at_collision: bool
    history_each_timestep: bool
    log_lcp_unbounded_ray: bool
    log_lcp_max_iterations: bool


@dataclass(frozen=True)
class WatchOptions:
    """What the watch outputs report (mbds.data.watches): ``time_constant`` (s) of the decaying
    sensor (0: none), impulses as forces, work summed from the start, the running T/N ratio,
    the contact angle instead of the work, and the half-width (points) of the lost-work
    smoothing."""

    time_constant: float = 0.0
    convert_impulse_to_force: bool = False
    cumulative_work: bool = False
    write_averaged_t_div_n: bool = False
    absolute_angle_instead_of_work: bool = False
    smooth_work_left_right: int = 0


@dataclass
class Parameters:
    """Names (sympy symbols; empty for a model assembled from the cache's record,
    :mod:`mbds.model.known`) and values of the parameter array ``p`` (constants, masses, fixed
    coordinates, contact-law numbers), of which the first ``constant_count`` are the constants."""

    symbols: list
    values: np.ndarray
    constant_count: int
