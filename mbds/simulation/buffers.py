"""The arrays the kernel's stepper takes: model tuple, settings, state, workspace, outputs."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mbds.kernel import stepper as K
from mbds.kernel.lcp import lcp_workspace
from mbds.model.arrays import KernelArrays
from mbds.model.load import Model


def model_tuple(a: KernelArrays) -> tuple:
    """The ``model`` argument of the stepper, in its order."""
    return (
        a.binding, a.binding_index, a.start_pose, a.carrier, a.offset, a.points, a.point_start, a.skin,
        a.displacement_factor, a.radius, a.pair_bodies, a.pair_law, a.pair_resisting, a.pair_temperature,
        a.watch_start, a.watch_points, a.parameters,
    )


@dataclass
class RunSettings:
    """What a run takes beyond the model files: break time (s), the seed of the lexicographic
    tolerance draws and their range (none when the upper end is 0), and the LCP pivot limit."""

    break_time: float
    seed: int = 0
    lexico_range: tuple[float, float] = (0.0, 0.0)
    max_pivots: int = 100000


def settings_array(model: Model, run: RunSettings) -> np.ndarray:
    """The stepper's settings array from the world file and the run settings."""
    s = model.files.world.settings
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
    out[K.SAMPLE_EVERY] = s.history_multiple_of_maximum_timestep * s.maximum_timestep
    out[K.SAMPLE_AT_COLLISION] = float(s.history_at_collision)
    out[K.SAMPLE_EACH_STEP] = float(s.history_each_timestep)
    out[K.MAX_PIVOTS] = run.max_pivots
    return out


def workspace(n: int, m: int, nb: int, points: int, pairs: int, capacity: int) -> tuple:
    """Scratch arrays of the stepper, in the order it unpacks them, for n coordinates, m
    dependent coordinates, nb bodies, ``points`` shape points, ``pairs`` contact pairs and up to
    ``capacity`` simultaneous contacts (LCPs of size up to 3 * capacity)."""
    c, size = capacity, 3 * capacity
    fwork, iwork = lcp_workspace(size)
    f, i, b = np.float64, np.int64, np.bool_
    spec = [
        ("world", (points, 2), f), ("boxes", (nb, 4), f), ("pose", (nb, 3), f), ("vel", (nb, 3), f),
        ("B", (nb, 3, n), f), ("bhat", (nb, 3), f), ("beta", (nb, 3), f),
        ("dpos", (m,), f), ("dvel", (m,), f), ("dacc", (m,), f), ("djac", (m, n), f), ("dsc", (m,), f),
        ("zero", (n,), f), ("margin", (pairs,), f),
        ("c_pair", (c,), i), ("c_vb", (c,), i), ("c_vertex", (c,), i), ("c_eb", (c,), i), ("c_edge", (c,), i),
        ("c_xi", (c,), f), ("c_gap", (c,), f), ("c_normal", (c, 2), f), ("c_point", (c, 2), f),
        ("det_work", (3 * points + 2050,), i),
        ("WN", (c, n), f), ("WT", (c, n), f), ("what_n", (c,), f), ("what_t", (c,), f),
        ("wbar_n", (c,), f), ("wbar_t", (c,), f), ("gd_n", (c,), f), ("gd_t", (c,), f), ("laws", (c, 4), f),
        ("M", (n, n), f), ("L", (n, n), f), ("hv", (n,), f), ("minv_h", (n,), f),
        ("YN", (c, n), f), ("YT", (c, n), f), ("column", (c, n), f), ("hrow", (c,), i), ("active", (c,), i),
        ("stick", (c,), b), ("sign", (c,), f),
        ("A_flat", (size * size,), f), ("bvec", (size,), f), ("z", (size,), f), ("w", (size,), f),
        ("fwork", None, None), ("iwork", None, None),
        ("lam_n", (c,), f), ("lam_t", (c,), f), ("lam_n1", (c,), f), ("lam_t1", (c,), f),
        ("imp_n", (c,), f), ("imp_t", (c,), f), ("gam_n", (c,), f), ("gam_t", (c,), f),
        ("compression_loss", (c,), f), ("a1", (n,), f), ("a2", (n,), f), ("q_star", (n,), f), ("u_star", (n,), f),
        ("backup_q", (2, n), f), ("backup_u", (2, n), f), ("backup_clock", (2, K.CLOCK), f),
        ("records_int", (2, 2 * c, 3), i), ("records_float", (2, 2 * c, K.RECORD_COLUMNS), f),
        ("record_count", (2,), i), ("last_sample", (1,), f), ("law_out", (4,), f),
    ]
    lcp = {"fwork": fwork, "iwork": iwork}
    arrays = {name: lcp[name] if name in lcp else np.zeros(shape, dtype=dtype) for name, shape, dtype in spec}
    arrays["record_count"][:] = -1  # no step to go back to
    arrays["a2"][:] = np.nan  # accelerations at the current time not known yet
    arrays["last_sample"][:] = -np.inf
    return tuple(arrays.values())


def history_buffers(n: int, watches: int, length: int) -> tuple:
    """History arrays for ``length`` samples: time, q, u, q'', energy, lost, drive, watches, count."""
    return (
        np.zeros(length), np.zeros((length, n)), np.zeros((length, n)), np.zeros((length, n)),
        np.zeros(length), np.zeros(length), np.zeros(length), np.zeros((length, watches, K.POINT_COLUMNS)),
        np.zeros(1, dtype=np.int64),
    )
