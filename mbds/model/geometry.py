"""Polygon shapes: validation and mass properties (numpy; SI units).

A shape is a closed polygon given as an (N, 2) array whose last point repeats the first; the
body's interior lies on the left when walking the points in order (counter-clockwise).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PolygonProperties:
    """Area (m^2), centroid (m, body frame) and polar second moment of area about the
    centroid (m^4); multiply by density x thickness for mass (kg) and Jzz (kg m^2)."""

    area: float
    centroid: np.ndarray
    second_moment: float


def polygon_properties(points: np.ndarray) -> PolygonProperties:
    """Signed area, centroid and centroidal polar moment of a closed polygon.

    With c_i = x_i y_{i+1} - x_{i+1} y_i: A = sum(c_i)/2; centroid = sum((p_i + p_{i+1}) c_i)/(6A);
    J_O = sum(c_i (x_i^2 + x_i x_{i+1} + x_{i+1}^2 + y_i^2 + y_i y_{i+1} + y_{i+1}^2))/12,
    moved to the centroid by the parallel-axis rule.
    """
    x0, y0 = points[:-1, 0], points[:-1, 1]
    x1, y1 = points[1:, 0], points[1:, 1]
    c = x0 * y1 - x1 * y0
    area = c.sum() / 2.0
    if area == 0.0:
        return PolygonProperties(0.0, points[:-1].mean(axis=0), 0.0)
    centroid = np.array([((x0 + x1) * c).sum(), ((y0 + y1) * c).sum()]) / (6.0 * area)
    j_origin = (c * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1)).sum() / 12.0
    return PolygonProperties(area, centroid, j_origin - area * float(centroid @ centroid))


def polygon_problems(points: np.ndarray, tolerance: float = 0.0) -> list[str]:
    """What is wrong with a shape (empty when valid), naming 0-based point numbers.

    Checks: closed (last point == first), no repeated consecutive points, interior on the left
    (positive area), and no two non-adjacent edges that touch or cross.
    """
    problems = []
    if len(points) < 4:
        return [f"a closed polygon needs at least 4 points, has {len(points)}"]
    if not np.all(np.isfinite(points)):
        return ["a point coordinate is not finite"]
    if not np.allclose(points[0], points[-1], rtol=0.0, atol=tolerance):
        last = len(points) - 1
        problems.append(f"not closed: point 0 {tuple(points[0].tolist())} differs from point {last} {tuple(points[-1].tolist())}")
        return problems
    edges = np.diff(points, axis=0)
    short = np.flatnonzero(np.hypot(edges[:, 0], edges[:, 1]) <= tolerance)
    if short.size:
        problems.append(f"repeated point: points {short[0]} and {short[0] + 1} coincide")
        return problems
    crossing = _first_crossing(points)
    if crossing is not None:
        a, b = crossing
        m = len(points) - 1
        problems.append(
            f"self-intersecting: edge {a}-{(a + 1) % m} crosses edge {b}-{(b + 1) % m} "
            f"(near {tuple(np.round(points[b], 12).tolist())})"
        )
    area = polygon_properties(points).area
    if area <= 0.0:
        problems.append(
            "the interior is on the right (points run clockwise); list them counter-clockwise"
            if area < 0
            else "the polygon has zero area"
        )
    return problems


def _first_crossing(points: np.ndarray) -> tuple[int, int] | None:
    """The first pair of non-adjacent edges that intersect, by a sweep over x-sorted edges."""
    m = len(points) - 1
    p, q = points[:-1], points[1:]
    lo = np.minimum(p[:, 0], q[:, 0])
    hi = np.maximum(p[:, 0], q[:, 0])
    order = np.argsort(lo, kind="stable")
    active: list[int] = []
    for i in order:
        active = [j for j in active if hi[j] >= lo[i]]
        for j in active:
            a, b = (i, j) if i < j else (j, i)
            if b - a == 1 or (a == 0 and b == m - 1):
                continue
            if _segments_intersect(p[a], q[a], p[b], q[b]):
                return a, b
        active.append(i)
    return None


def _segments_intersect(a0, a1, b0, b1) -> bool:
    def orient(o, u, v):
        return (u[0] - o[0]) * (v[1] - o[1]) - (u[1] - o[1]) * (v[0] - o[0])

    d1, d2 = orient(b0, b1, a0), orient(b0, b1, a1)
    d3, d4 = orient(a0, a1, b0), orient(a0, a1, b1)
    if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and d1 * d2 < 0 and d3 * d4 < 0:
        return True

    def on_segment(o, u, v, d):
        return d == 0 and min(o[0], u[0]) <= v[0] <= max(o[0], u[0]) and min(o[1], u[1]) <= v[1] <= max(o[1], u[1])

    return on_segment(b0, b1, a0, d1) or on_segment(b0, b1, a1, d2) or on_segment(a0, a1, b0, d3) or on_segment(a0, a1, b1, d4)


def smooth_closed(values: np.ndarray, half_width: int) -> np.ndarray:
    """Centred moving average over 2 * half_width + 1 neighbours of the points of one closed
    shape (wrapping around); every point gets the mean when the window covers the shape."""
    count = len(values)
    if half_width <= 0 or count == 0:
        return values.copy()
    if 2 * half_width + 1 >= count:
        return np.full_like(values, values.mean())
    total = sum(np.roll(values, shift) for shift in range(-half_width, half_width + 1))
    return total / (2 * half_width + 1)
