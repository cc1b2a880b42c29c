"""Outlines of bodies from primitives (the manual's Figure 2.8 helpers), as (N, 2) arrays in m.

Lists of points follow Mathematica's conventions where the manual uses them: ``circle(r, n)``
and ``ellipse(a, b, n)`` give the n + 1 points i = 0..n of the parametrisation (the last one
repeats the first), ``take(points, (first, last))`` counts from 1 and includes both ends.
A finished outline must be closed (last point = first) and run counter-clockwise (the body on
the left): :func:`check_shape` says what is wrong, :func:`closed` appends the closing point.
"""

from __future__ import annotations

import numpy as np

from mbds.model.geometry import polygon_problems


def ellipse(a: float, b: float, n: int, *, center: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The n + 1 points (a cos 2πi/n, b sin 2πi/n), i = 0..n, counter-clockwise and closed (m)."""
    if n < 3:
        raise ValueError(f"an ellipse needs at least 3 segments, not {n}")
    if a <= 0 or b <= 0:
        raise ValueError(f"the semi-axes must be positive, not {a} and {b}")
    angle = 2.0 * np.pi * np.arange(n + 1) / n
    points = np.column_stack([a * np.cos(angle), b * np.sin(angle)])
    points[-1] = points[0]  # cos and sin of 2π are not exactly those of 0
    return points + np.asarray(center, dtype=float)


def circle(r: float, n: int, *, center: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The n + 1 points of a circle of radius r (m), as :func:`ellipse` with a = b = r."""
    return ellipse(r, r, n, center=center)


def polygon(points) -> np.ndarray:
    """An (N, 2) array of the given (x, y) points (m), closed if it is not yet."""
    array = np.asarray(points, dtype=float)
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"points must be (x, y) pairs, not an array of shape {array.shape}")
    return closed(array)


def take(points: np.ndarray, span: tuple[int, int]) -> np.ndarray:
    """Points ``first`` to ``last`` of ``points``, counted from 1, both included (Mathematica's
    ``Take[data, {first, last}]``)."""
    first, last = span
    if not 1 <= first <= last <= len(points):
        raise ValueError(f"take {span}: needs 1 <= first <= last <= {len(points)}")
    return np.array(points[first - 1 : last], dtype=float)


def translate(points: np.ndarray, dx: float, dy: float) -> np.ndarray:
    """``points`` moved by (dx, dy) (m) (the manual's ``TranslateData``)."""
    return np.asarray(points, dtype=float) + np.array([dx, dy])


def rotate(points: np.ndarray, angle: float, about: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """``points`` turned counter-clockwise by ``angle`` (rad) about the point ``about`` (m)."""
    c, s = np.cos(angle), np.sin(angle)
    pivot = np.asarray(about, dtype=float)
    return (np.asarray(points, dtype=float) - pivot) @ np.array([[c, s], [-s, c]]) + pivot


def join(*parts: np.ndarray) -> np.ndarray:
    """The parts one after another (Mathematica's ``Join``); not closed by itself."""
    return np.vstack([np.asarray(p, dtype=float).reshape(-1, 2) for p in parts])


def closed(points: np.ndarray) -> np.ndarray:
    """``points`` with the first point appended at the end unless it is there already."""
    points = np.asarray(points, dtype=float)
    if len(points) and np.array_equal(points[0], points[-1]):
        return points.copy()
    return np.vstack([points, points[:1]])


def check_shape(points: np.ndarray) -> list[str]:
    """What keeps ``points`` from being an MBDS outline (empty when it is one): not closed,
    clockwise, repeated or crossing points (see :func:`mbds.model.geometry.polygon_problems`)."""
    return polygon_problems(np.asarray(points, dtype=float))
