"""Run-in wear: moving shape points in proportion to the mechanical energy lost at them.

For each reshaped body, with E_i the lost work (J) accumulated at its watched points:

1. ``smoothWorkLeftRight = k`` replaces the loss of every point by the mean over the 2k + 1
   points around it (the closed shape wraps around);
2. statistics are taken over the body's watched points, or jointly over all bodies listed in
   ``[bodyBalancedUpdate]``: ``cutHiLowValues`` percent of the values are left out at each end,
   and the mean and standard deviation of the rest give the window
   [mean + lo sigma, mean + hi sigma] (``standardDeviationRange = lo, hi``);
3. each E_i is clipped to the window intersected with the range of the values kept, so that a
   few points carrying most of the load do not dominate (the filter the manual describes);
4. displacement (m): with one ``maxChange`` m, d_i = m E_i / max E (the point of highest loss
   moves by exactly m, points without loss stay); with a range ``maxChange = a, b``, points
   above the mean move by a (E_i - mean) / (max E - mean) and points below by
   b (mean - E_i) / (mean - min E), so ``directionInside = 1`` with (1e-6, -1e-6) wears the
   high-loss points and grows the unloaded ones;
5. direction: with ``directionInside = +1/-1`` the inward/outward unit normal from the two
   neighbouring points, E (r_{i+1} - r_{i-1}) / |...| with E the rotation by +90 degrees (the
   interior of a counter-clockwise shape is on the left); otherwise the body-frame direction
   (``directionX``, ``directionY``), normalised.

All watched points move at once; the closing point follows the first. A result that would cross
itself or turn clockwise is refused with a :class:`ModelError` naming the body and points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mbds.errors import ModelError
from mbds.io.watches import ReshapeWindow
from mbds.model.geometry import polygon_problems


@dataclass
class Window:
    """Clipping bounds of loss values (J) and the mean used by a ``maxChange`` range."""

    low: float
    high: float
    mean: float


@dataclass
class BodyWear:
    """The reshaping of one body: watched point numbers, their loss after smoothing and
    clipping (J), displacement (m, positive along ``direction``), unit directions (k, 2) and
    the new closed shape (N, 2)."""

    body: str
    points: np.ndarray
    loss: np.ndarray
    displacement: np.ndarray
    direction: np.ndarray
    shape: np.ndarray


def loss_window(values: np.ndarray, window: ReshapeWindow) -> Window:
    """The clipping window of a set of loss values under ``[reshapeWindow]``."""
    ordered = np.sort(values)
    cut = int(np.floor(window.cut_hi_low_values / 100.0 * len(ordered)))
    kept = ordered[cut : len(ordered) - cut] if len(ordered) > 2 * cut else ordered
    mean = float(kept.mean()) if len(kept) else 0.0
    sigma = float(kept.std()) if len(kept) else 0.0
    low_k, high_k = window.standard_deviation_range
    low = max(mean + low_k * sigma, float(kept.min()) if len(kept) else 0.0)
    high = min(mean + high_k * sigma, float(kept.max()) if len(kept) else 0.0)
    return Window(low, max(high, low), mean)


def displacements(loss: np.ndarray, window: Window, max_change: list[float]) -> tuple[np.ndarray, np.ndarray]:
    """Clipped losses and displacements (m) for one ``maxChange`` value or a range (a, b);
    the extremes are those of the clipped values of the whole group the window came from."""
    clipped = np.clip(loss, window.low, window.high)
    return clipped, _scale(clipped, window, max_change, float(window.high), float(window.low))


def _scale(clipped, window: Window, max_change, top: float, bottom: float) -> np.ndarray:
    if len(max_change) == 1:
        return max_change[0] * clipped / top if top > 0 else np.zeros_like(clipped)
    above, below = max_change
    out = np.zeros_like(clipped)
    high = clipped > window.mean
    low = clipped < window.mean
    if top > window.mean:
        out[high] = above * (clipped[high] - window.mean) / (top - window.mean)
    if window.mean > bottom:
        out[low] = below * (window.mean - clipped[low]) / (window.mean - bottom)
    return out


def directions(shape: np.ndarray, points: np.ndarray, inside: int, axis: tuple[float, float]) -> np.ndarray:
    """Unit directions (k, 2) of the points ``points`` of a closed ``shape`` (N, 2)."""
    ring = shape[:-1]
    count = len(ring)
    if inside:
        chord = ring[(points + 1) % count] - ring[(points - 1) % count]
        normal = np.column_stack([-chord[:, 1], chord[:, 0]]) * float(np.sign(inside))
        return normal / np.linalg.norm(normal, axis=1, keepdims=True)
    vector = np.asarray(axis, dtype=float)
    length = np.linalg.norm(vector)
    if length == 0:
        return np.zeros((len(points), 2))
    return np.tile(vector / length, (len(points), 1))


def moved_shape(body: str, shape: np.ndarray, points: np.ndarray, displacement: np.ndarray,
                direction: np.ndarray, source=None) -> np.ndarray:
    """``shape`` with ``points`` moved by ``displacement`` along ``direction``; refused with a
    ModelError when the result is no longer a valid (simple, counter-clockwise) polygon."""
    new = shape.copy()
    new[points] += displacement[:, None] * direction
    new[-1] = new[0]
    problems = polygon_problems(new)
    if problems:
        raise ModelError(f"reshaping body '{body}' would break its shape: {'; '.join(problems)}", source)
    return new
