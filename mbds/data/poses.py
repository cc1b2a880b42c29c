"""Dependent coordinates and body poses over a run, computed from its samples of q with the model's
compiled ``dependent_state`` and its coordinate bindings, for ``history.nc``."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from mbds.model.arrays import KernelArrays
from mbds.model.bodies import DEPENDENT, GENERALIZED


class DependentSeries(NamedTuple):
    """Position, velocity and acceleration of the dependent coordinates, each (samples, m)."""

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


def dependent_series(compiled, parameters: np.ndarray, time, q, qd, qdd) -> DependentSeries:
    """The dependent coordinates at every sample (time (s), q, qd, qdd each (samples, n))."""
    samples, m = len(time), compiled.m
    out = DependentSeries(*(np.zeros((samples, m)) for _ in range(3)))
    for i in range(samples if m else 0):
        compiled.dependent_state(
            np.ascontiguousarray(q[i]), np.ascontiguousarray(qd[i]), np.ascontiguousarray(qdd[i]),
            float(time[i]), parameters, out.position[i], out.velocity[i], out.acceleration[i],
        )
    return out


def body_poses(arrays: KernelArrays, q: np.ndarray, dependent: np.ndarray) -> np.ndarray:
    """Pose (x m, y m, Rz rad) of every body at every sample, (samples, bodies, 3): a generalized
    or dependent coordinate, else the start value (fixed); a virtual body moves rigidly with its
    carrier at its offset."""
    samples, nb = len(q), len(arrays.binding)
    pose = np.repeat(arrays.start_pose[None], samples, axis=0)
    for b in range(nb):
        for a in range(3):
            kind, k = arrays.binding[b, a], arrays.binding_index[b, a]
            if kind == GENERALIZED:
                pose[:, b, a] = q[:, k]
            elif kind == DEPENDENT:
                pose[:, b, a] = dependent[:, k]
    for b in np.flatnonzero(arrays.carrier >= 0):
        carrier, (ox, oy, orz) = pose[:, arrays.carrier[b]], arrays.offset[b]
        cs, sn = np.cos(carrier[:, 2]), np.sin(carrier[:, 2])
        pose[:, b, 0] = carrier[:, 0] + cs * ox - sn * oy
        pose[:, b, 1] = carrier[:, 1] + sn * ox + cs * oy
        pose[:, b, 2] = carrier[:, 2] + orz
    return pose
