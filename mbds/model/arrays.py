"""The model flattened into the plain arrays the kernel takes (SI units throughout)."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import TYPE_CHECKING

import numpy as np

from mbds.kernel.layout import AMBIENT, COOLING, HEAT_COLUMNS, HEATING

if TYPE_CHECKING:  # the loader imports sympy; reading outputs needs only these arrays
    from mbds.model.load import Model


@dataclass
class KernelArrays:
    """Everything model-specific the kernel needs, as numpy arrays.

    Bodies (``nb``): ``binding`` (nb, 3) int64 kinds of x, y, Rz (0 fixed, 1 generalized,
    2 dependent) and ``binding_index`` (nb, 3) the q or dependent index (-1 when fixed);
    ``start_pose``/``start_velocity`` (nb, 3); ``carrier`` (nb,) the body a virtual body moves
    with (-1 if none) and ``offset`` (nb, 3) its pose in the carrier frame; ``mass`` (kg),
    ``inertia`` (kg m^2), ``displacement_factor``, ``skin`` (m), ``radius`` (m, largest vertex
    distance from the body origin). Shapes: ``points`` (P, 2) body-frame points of all bodies
    (closing point included) with ``point_start`` (nb + 1,) offsets, and ``point_reflex`` (P,)
    whether the outline turns clockwise at each point (a concave corner), ``concave`` (nb,)
    whether a body's outline has any.
    Pairs (``np``): ``pair_bodies`` (np, 2), ``pair_law`` (np,), ``pair_resisting`` (np, 2)
    booleans, ``pair_temperature`` (np,) initial contact temperature (deg C), ``pair_heated``
    (np,) whether the pair has a temperature model, ``point_heat`` (P, HEAT_COLUMNS) each
    point's heating (deg C per J), cooling rate (1/s) and ambient temperature (deg C) from its
    body's heated pairs (0 where none).
    Watches (``nw``): ``watch_body`` (nw,), ``watch_absolute`` (nw,), indices into ``points``
    ``watch_points`` with ``watch_start`` (nw + 1,) offsets.
    State and parameters: ``q0``, ``qd0`` (n,), ``parameters`` (p,).
    """

    binding: np.ndarray
    binding_index: np.ndarray
    start_pose: np.ndarray
    start_velocity: np.ndarray
    carrier: np.ndarray
    offset: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    displacement_factor: np.ndarray
    skin: np.ndarray
    radius: np.ndarray
    points: np.ndarray
    point_start: np.ndarray
    point_reflex: np.ndarray
    concave: np.ndarray
    pair_bodies: np.ndarray
    pair_law: np.ndarray
    pair_resisting: np.ndarray
    pair_temperature: np.ndarray
    pair_heated: np.ndarray
    point_heat: np.ndarray
    watch_body: np.ndarray
    watch_absolute: np.ndarray
    watch_points: np.ndarray
    watch_start: np.ndarray
    q0: np.ndarray
    qd0: np.ndarray
    parameters: np.ndarray

    def as_dict(self) -> dict[str, np.ndarray]:
        return {f.name: getattr(self, f.name) for f in fields(self)}


def flatten(model: Model) -> KernelArrays:
    """The kernel arrays of ``model`` (contiguous, float64 or int64)."""
    bodies = model.bodies
    counts = [len(b.points) for b in bodies]
    watches = model.watches
    start = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    watch_points = [[start[w.body] + p for p in w.points] for w in watches]
    reflex = [concave_corners(b.points) for b in bodies]
    return KernelArrays(
        binding=np.array([b.binding for b in bodies], dtype=np.int64).reshape(-1, 3),
        binding_index=np.array([b.binding_index for b in bodies], dtype=np.int64).reshape(-1, 3),
        start_pose=np.array([b.start_position for b in bodies], dtype=float).reshape(-1, 3),
        start_velocity=np.array([b.start_velocity for b in bodies], dtype=float).reshape(-1, 3),
        carrier=np.array([-1 if b.carrier is None else b.carrier for b in bodies], dtype=np.int64),
        offset=np.array([b.offset for b in bodies], dtype=float).reshape(-1, 3),
        mass=np.array([b.mass for b in bodies], dtype=float),
        inertia=np.array([b.inertia for b in bodies], dtype=float),
        displacement_factor=np.array([b.maximum_displacement_factor for b in bodies], dtype=float),
        skin=np.array([b.skin_thickness for b in bodies], dtype=float),
        radius=np.array([np.hypot(b.points[:, 0], b.points[:, 1]).max() for b in bodies], dtype=float),
        points=np.ascontiguousarray(np.concatenate([b.points for b in bodies]) if bodies else np.zeros((0, 2))),
        point_start=start,
        point_reflex=np.concatenate(reflex or [np.zeros(0, dtype=np.bool_)]),
        concave=np.array([r.any() for r in reflex], dtype=np.bool_),
        pair_bodies=np.array([(p.first, p.second) for p in model.pairs], dtype=np.int64).reshape(-1, 2),
        pair_law=np.array([p.law for p in model.pairs], dtype=np.int64),
        pair_resisting=np.array([p.resisting for p in model.pairs], dtype=np.bool_).reshape(-1, 2),
        pair_temperature=np.array([p.initial_temperature for p in model.pairs], dtype=float),
        pair_heated=np.array([p.heated for p in model.pairs], dtype=np.bool_),
        point_heat=point_heat(model, start),
        watch_body=np.array([w.body for w in watches], dtype=np.int64),
        watch_absolute=np.array([w.absolute for w in watches], dtype=np.bool_),
        watch_points=np.array([p for group in watch_points for p in group], dtype=np.int64),
        watch_start=np.concatenate([[0], np.cumsum([len(g) for g in watch_points])]).astype(np.int64),
        q0=model.q0.copy(),
        qd0=model.qd0.copy(),
        parameters=model.parameters.values.copy(),
    )



def concave_corners(points: np.ndarray) -> np.ndarray:
    """Whether a closed counter-clockwise outline (k, 2), its last point repeating the first,
    turns clockwise at each of its points (k,): the concave corners, where the bands of the two
    edges that meet leave a gap (mbds.kernel.detection)."""
    if len(points) < 4:
        return np.zeros(len(points), dtype=np.bool_)
    corners = points[:-1]
    before = corners - np.roll(corners, 1, axis=0)
    after = np.roll(corners, -1, axis=0) - corners
    turn = before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0]
    concave = turn < 0.0
    return np.append(concave, concave[:1])


def point_heat(model: Model, point_start: np.ndarray) -> np.ndarray:
    """(P, HEAT_COLUMNS): the heat model of every point, from its body's heated pairs (see
    mbds.kernel.heat). Each of the two touching points takes half of the energy lost, so a
    point warms by 1 / (2 heatCapacity) deg C per J booked on it."""
    heat = np.zeros((int(point_start[-1]), HEAT_COLUMNS))
    for pair in (p for p in model.pairs if p.heated):
        for body in (pair.first, pair.second):
            rows = heat[point_start[body] : point_start[body + 1]]
            rows[:, HEATING] = 0.5 / pair.heat_capacity
            rows[:, COOLING] = 1.0 / pair.cooling_time if pair.cooling_time > 0.0 else 0.0
            rows[:, AMBIENT] = pair.initial_temperature
    return heat
