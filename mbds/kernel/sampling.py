"""History samples of the stepper's state and of the per-point accumulators."""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit
from mbds.kernel.layout import ANGLE, DRIVE_WORK, LOST, POINT_COLUMNS, TEMP


@jit(inline="always")
def sample(mechanical_energy, q, u, a, t, p, clock, point_interval, watch_start, watch_points, history):
    """Write a history sample at time t (s) and start a new interval of the per-point
    accumulators; watched points get the sums of their points' impulses and work, the last
    angle and the highest temperature (NaN where none of them has a heat model)."""
    k = history.count[0]
    history.time[k] = t
    for j in range(q.shape[0]):
        history.q[k, j] = q[j]
        history.u[k, j] = u[j]
        history.a[k, j] = a[j]
    history.energy[k] = mechanical_energy(q, u, t, p)
    history.lost[k] = clock[LOST]
    history.drive[k] = clock[DRIVE_WORK]
    watch = history.watch
    for wi in range(watch_start.shape[0] - 1):
        for c in range(POINT_COLUMNS):
            watch[k, wi, c] = 0.0
        hottest = np.nan
        for m in range(watch_start[wi], watch_start[wi + 1]):
            pt = watch_points[m]
            for c in range(ANGLE):
                watch[k, wi, c] += point_interval[pt, c]
            watch[k, wi, ANGLE] = point_interval[pt, ANGLE]
            temperature = point_interval[pt, TEMP]
            if not np.isnan(temperature) and (np.isnan(hottest) or temperature > hottest):
                hottest = temperature
        watch[k, wi, TEMP] = hottest
    for pt in range(point_interval.shape[0]):
        for c in range(ANGLE):
            point_interval[pt, c] = 0.0
    history.count[0] = k + 1
