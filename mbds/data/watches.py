"""Watch outputs: the kernel's per-interval sums turned into what the ``.wtc`` ``[common]``
options ask for, and the lost work per shape point.

The kernel reports, for every history sample k and watch, the impulses (N s) and lost work (J)
summed over the interval since the previous sample, and the last contact-normal angle (rad).
The options act on these series in this order, each run on its own:

- ``convertImpulseToForce``: impulses divided by the interval length (N; 0 for an empty interval);
- ``timeConstant`` tau > 0: y_k = y_{k-1} exp(-dt_k / tau) + x_k (a decaying sensor);
- ``cummulativeWork``: work summed from the start of the run;
- ``absoluteAngleInsteadOfWork``: the angle replaces the work;
- ``writeAveragedTDivN``: running ratio of summed impulses, sum(T) / sum(N), in the
  normal-tangential frame whatever frame the watch writes its impulses in (the ratio of
  friction to normal impulse does not depend on the frame); 0 until the first normal impulse.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mbds.kernel.layout import ANGLE, IMP_N, IMP_T, IMP_X, IMP_Y, TEMP, WORK
from mbds.model.geometry import smooth_closed
from mbds.model.system import WatchOptions

IMPULSE_COLUMNS = {"normal": IMP_N, "tangential": IMP_T, "x": IMP_X, "y": IMP_Y}


@dataclass
class WatchSeries:
    """Watch outputs over (sample, watch): ``impulse`` per direction (normal, tangential, x, y;
    N s, or N for forces), ``work`` (J) or ``angle`` (rad), ``t_div_n`` and ``temperature``
    (deg C, the hottest watched point; None when not asked, or when no contact pair has a
    temperature model)."""

    impulse: dict[str, np.ndarray]
    work: np.ndarray | None
    angle: np.ndarray | None
    t_div_n: np.ndarray | None
    force: bool
    temperature: np.ndarray | None = None


@dataclass
class WatchCarry:
    """What the options that run over samples hold at the end of one part of a run, to go on
    with the next: the decayed impulses by direction, the work summed and the summed T and N
    impulses (each per watch; absent before the first part)."""

    decayed: dict[str, np.ndarray] = field(default_factory=dict)
    sums: dict[str, np.ndarray] = field(default_factory=dict)


def watch_series(sums: np.ndarray, intervals: np.ndarray, options: WatchOptions,
                 carry: WatchCarry | None = None, heated: bool = False) -> WatchSeries:
    """Apply ``options`` to ``sums`` (samples, watches, POINT_COLUMNS); ``intervals`` (samples,)
    are the sample intervals (s). With ``carry``, the samples continue those of the parts of the
    run that ``carry`` went through (and ``carry`` goes on to their end): a run's series are the
    same whether made whole or in parts. ``heated``: the model has contact temperatures."""
    carry = carry if carry is not None else WatchCarry()
    impulse = {}
    for name, column in IMPULSE_COLUMNS.items():
        values = sums[:, :, column]
        if options.convert_impulse_to_force:
            values = per_time(values, intervals)
        if options.time_constant > 0:
            values = decay(values, intervals, options.time_constant, carry.decayed.get(name))
            if len(values):
                carry.decayed[name] = values[-1].copy()
        impulse[name] = values
    work = angle = t_div_n = None
    if options.absolute_angle_instead_of_work:
        angle = sums[:, :, ANGLE].copy()
    else:
        work = sums[:, :, WORK]
        work = _running_sum(work, carry, "work") if options.cumulative_work else work.copy()
    if options.write_averaged_t_div_n:
        t_div_n = running_ratio(_running_sum(sums[:, :, IMP_T], carry, "T"), _running_sum(sums[:, :, IMP_N], carry, "N"))
    temperature = sums[:, :, TEMP].copy() if heated else None
    return WatchSeries(impulse, work, angle, t_div_n, options.convert_impulse_to_force, temperature)


def _running_sum(values: np.ndarray, carry: WatchCarry, name: str) -> np.ndarray:
    """Sums of ``values`` along the first axis from the start of the run (``carry.sums[name]``
    holds the sum before them and goes on to the sum at their end); added one sample after the
    other in every case, so the sums do not depend on where the parts begin."""
    before = carry.sums.get(name)
    total = np.cumsum(values, axis=0) if before is None else np.cumsum(np.concatenate([before[None], values]), axis=0)[1:]
    if len(total):
        carry.sums[name] = total[-1].copy()
    return total


def per_time(values: np.ndarray, intervals: np.ndarray) -> np.ndarray:
    """``values`` (samples, ...) divided by their intervals (s); 0 where an interval is empty."""
    dt = intervals.reshape((-1,) + (1,) * (values.ndim - 1))
    return np.divide(values, dt, out=np.zeros_like(values), where=dt > 0)


def decay(values: np.ndarray, intervals: np.ndarray, tau: float, previous: np.ndarray | None = None) -> np.ndarray:
    """y_k = y_{k-1} exp(-dt_k / tau) + x_k along the first axis, from y_{-1} = ``previous``
    (default 0)."""
    factors = np.exp(-intervals / tau)
    out = np.empty_like(values)
    if previous is None and len(values):
        previous = np.zeros_like(values[0])
    for k in range(len(values)):
        previous = previous * factors[k] + values[k]
        out[k] = previous
    return out


def running_ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num / den, running sums up to each sample; 0 where the sum of the denominator is 0 (no
    contact yet)."""
    return np.divide(num, den, out=np.zeros_like(num), where=den != 0)


def distinct_points(values: np.ndarray, point_start: np.ndarray) -> np.ndarray:
    """Per-point values of all bodies (closing repeats included, ``point_start`` offsets)
    without the closing repeats (the kernel books an edge ending there on the body's point 0)."""
    keep = np.ones(len(values), dtype=bool)
    keep[point_start[1:] - 1] = False
    return values[keep]


def smooth_points(values: np.ndarray, starts: np.ndarray, half_width: int) -> np.ndarray:
    """:func:`smooth_closed` applied to each body of distinct-point ``values`` (offsets ``starts``)."""
    parts = [smooth_closed(values[starts[b] : starts[b + 1]], half_width) for b in range(len(starts) - 1)]
    return np.concatenate(parts) if parts else values.copy()
