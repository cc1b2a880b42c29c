"""Figures of the woodpecker's limit cycle from a sampled trajectory q = (y, phi_M, phi_S).

Used by the physics tests (mbds' run of ``campaigns/woodpecker``) and by
``benchmarks/woodpecker_reference.py`` (the small-angle reference model), so that both are
measured the same way.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SWING = -0.05
"""Bird angle (rad) whose upward crossings start a period: the bird passes it once per swing
toward the pole, well away from the beak contact (0.12 rad) and the backward turn."""


@dataclass
class CycleFigures:
    """Periods (s) of the motion: each spans ``swings`` successive upward crossings of SWING by
    the bird angle (1 for a simple cycle, 2 when long and short swings alternate, ...); limits
    (min, max) of the sleeve and bird angles (rad); impacts per period; mean descent speed of
    the sleeve (m/s, positive downward)."""

    periods: np.ndarray
    swings: int
    ring_limits: tuple[float, float]
    bird_limits: tuple[float, float]
    impacts_per_period: float
    descent_speed: float

    @property
    def period(self) -> float:
        return float(np.mean(self.periods))

    def spread(self) -> float:
        """Largest relative deviation of a period from the mean period."""
        return float(np.max(np.abs(self.periods / self.period - 1.0))) if len(self.periods) else np.inf

    def lines(self) -> list[str]:
        return [
            f"period {self.period * 1e3:.2f} ms ({self.swings} swing{'s' if self.swings > 1 else ''}) "
            f"over {len(self.periods)} periods (spread {self.spread():.2%})",
            f"sleeve angle {self.ring_limits[0]:+.4f} .. {self.ring_limits[1]:+.4f} rad",
            f"bird angle {self.bird_limits[0]:+.4f} .. {self.bird_limits[1]:+.4f} rad",
            f"impacts per period {self.impacts_per_period:.2f}",
            f"mean descent speed {self.descent_speed * 1e3:.2f} mm/s",
        ]


def swings_per_period(swings: np.ndarray, tolerance: float = 0.01, most: int = 4) -> int:
    """The smallest m such that every swing lasts as long as the one m swings later, within
    ``tolerance`` (relative); 1 when there is none up to ``most``."""
    for m in range(1, most + 1):
        if len(swings) >= 2 * m and np.all(np.abs(swings[m:] / swings[:-m] - 1.0) <= tolerance):
            return m
    return 1


def cycle_figures(time: np.ndarray, q: np.ndarray, impact_times: np.ndarray, skip: float) -> CycleFigures:
    """Figures of the motion after ``skip`` (s), over whole periods only; a period starts where
    the bird angle, interpolated linearly between samples, crosses SWING upward."""
    bird = q[:, 2]
    up = np.flatnonzero((bird[:-1] < SWING) & (bird[1:] >= SWING))
    crossings = time[up] + (SWING - bird[up]) / (bird[up + 1] - bird[up]) * (time[up + 1] - time[up])
    starts = crossings[crossings >= skip]
    if len(starts) < 2:
        return CycleFigures(np.zeros(0), 1, (np.nan, np.nan), (np.nan, np.nan), np.nan, np.nan)
    swings = swings_per_period(np.diff(starts))
    starts = starts[: 1 + (len(starts) - 1) // swings * swings : swings]
    inside = (time >= starts[0]) & (time <= starts[-1])
    counted = np.count_nonzero((impact_times >= starts[0]) & (impact_times < starts[-1]))
    k0, k1 = np.flatnonzero(inside)[[0, -1]]
    return CycleFigures(
        periods=np.diff(starts),
        swings=swings,
        ring_limits=(float(q[inside, 1].min()), float(q[inside, 1].max())),
        bird_limits=(float(bird[inside].min()), float(bird[inside].max())),
        impacts_per_period=counted / (len(starts) - 1),
        descent_speed=float(-(q[k1, 0] - q[k0, 0]) / (time[k1] - time[k0])),
    )


def velocity_jumps(time: np.ndarray, u: np.ndarray, a: np.ndarray, lever: tuple, threshold: float) -> np.ndarray:
    """Times (s) between samples where the velocities jump by more than the sampled
    accelerations explain (impacts): the unexplained change of each generalized velocity,
    times ``lever`` (m per unit of the coordinate), summed in absolute value, exceeds
    ``threshold`` (m/s)."""
    dt = np.diff(time)[:, None]
    rest = np.diff(u, axis=0) - 0.5 * dt * (a[:-1] + a[1:])
    size = np.abs(rest) @ np.asarray(lever, dtype=float)
    return time[1:][size > threshold]
