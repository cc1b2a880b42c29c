"""The text outputs of the original program: ``data.txt``, ``watches.txt`` and ``log.txt``.

``data.txt`` and ``watches.txt`` hold numbers only, one sample a line, separated by spaces;
their column headers are lines 1 and 5 of ``log.txt``. The layout of ``log.txt``:

1. header of ``data.txt``: ``time mechanicalEnergy`` then ``q q' q"`` of every coordinate;
2. empty;
3. time of the first sample, 4. time of the last sample (s);
5. header of ``watches.txt``: ``time`` then the columns of every watch;
6. ``***********``;
7. and on: alerts, one a line, ``[Alert] ...``.
"""

from __future__ import annotations

from pathlib import Path
from typing import TextIO

import numpy as np

from mbds.data.record import RunHeader, RunRecord, SampleSeries, empty_series
from mbds.data.watches import WatchSeries
from mbds.io.text import write_atomic
from mbds.kernel import layout as K
from mbds.model.load import Model

NUMBER = "%.10g"
SEPARATOR_LINE = "*" * 11
HEADER_LINES = 6


def data_header(header: RunHeader) -> list[str]:
    columns = ["time", "mechanicalEnergy"]
    for name in header.coordinates:
        columns += [name, f"{name}'", f'{name}"']
    return columns


def data_table(s: SampleSeries) -> np.ndarray:
    parts = [s.time[:, None], s.energy[:, None]]
    parts += [np.stack([s.q[:, k], s.qd[:, k], s.qdd[:, k]], axis=1) for k in range(s.q.shape[1])]
    return np.concatenate(parts, axis=1)


def watch_columns(header: RunHeader, w: WatchSeries) -> list[tuple[str, np.ndarray]]:
    """(header, values over samples) of every watch column, in watches.txt order."""
    prefix = "force" if header.force else "imp"
    out = []
    for k, label in enumerate(header.watch_labels):
        pair = (("X", "x"), ("Y", "y")) if header.watch_absolute[k] else (("N", "normal"), ("T", "tangential"))
        out += [(f"{label}-{prefix}{short}", w.impulse[name][:, k]) for short, name in pair]
        out.append((f"{label}-angle", w.angle[:, k]) if w.work is None else (f"{label}-work", w.work[:, k]))
        if w.t_div_n is not None:
            out.append((f"{label}-TdivN", w.t_div_n[:, k]))
        if w.temperature is not None:
            out.append((f"{label}-temperature", w.temperature[:, k]))
    return out


def watch_table(header: RunHeader, s: SampleSeries) -> np.ndarray:
    return np.stack([s.time] + [values for _, values in watch_columns(header, s.watches)], axis=1)


def log_lines(record: RunRecord) -> list[str]:
    """The lines of ``log.txt`` (alerts from ``record.alerts``)."""
    first = record.first_sample if record.samples else record.start_time
    last = record.last_sample if record.samples else record.start_time
    watches = ["time"] + [name for name, _ in watch_columns(record, empty_series(record).watches)]
    return [
        " ".join(data_header(record)), "", NUMBER % first, NUMBER % last, " ".join(watches), SEPARATOR_LINE,
        *record.alerts,
    ]


class TableStreams:
    """``data.txt`` and ``watches.txt`` written while the run goes, into the open files
    ``data`` and ``watches`` (temporary files, renamed by the caller when the run has ended)."""

    def __init__(self, header: RunHeader, data: TextIO, watches: TextIO):
        self.header, self.data, self.watches = header, data, watches

    def append(self, series: SampleSeries) -> None:
        self.data.write(_table(data_table(series)))
        self.watches.write(_table(watch_table(self.header, series)))


def write_log(folder: str | Path, record: RunRecord) -> None:
    """Write log.txt into ``folder`` (atomically)."""
    write_atomic(Path(folder) / "log.txt", "\n".join(log_lines(record)) + "\n")


def _table(values: np.ndarray) -> str:
    """Rows of ``NUMBER``-formatted values joined by spaces (what ``numpy.savetxt`` writes), with
    exact zeros, most of a watch table, written as ``0`` without formatting them."""
    cells = np.full(values.shape, "0", dtype=object)
    formatted = (values != 0) | np.signbit(values)  # -0.0 is written "-0", as %g does
    cells[formatted] = [NUMBER % v for v in values[formatted].tolist()]
    return "".join(" ".join(row) + "\n" for row in cells.tolist())


def event_alerts(events: np.ndarray, model: Model) -> list[str]:
    """Alerts of kernel events (rows: time, code, value, value). LCP unbounded rays and
    iteration limits are logged only when the world's ``logLCPUnboundedRay`` /
    ``logLCPMaxNumberOfIterations`` ask for them."""
    s = model.settings
    out = []
    for t, code, a, b in events:
        code = int(code)
        if code == K.EVENT_LCP_RAY and s.log_lcp_unbounded_ray:
            text = f"LCP unbounded ray (size {a:.0f}, {b:.0f} pivots)."
        elif code == K.EVENT_LCP_MAX_PIVOTS and s.log_lcp_max_iterations:
            text = f"LCP maximum number of iterations reached (size {a:.0f}, {b:.0f} pivots)."
        elif code == K.EVENT_LCP_FAILURE:
            text = f"LCP not solved, no acceptable pivot (size {a:.0f})."
        elif code == K.EVENT_OVER_PENETRATION:
            text = f"penetration {a:.4g} m exceeds maximumPenetration {b:.4g} m at the minimum time step."
        elif code == K.EVENT_BAD_LAW:
            pair = model.pairs[int(a)]
            names = f"{model.bodies[pair.first].name}-{model.bodies[pair.second].name}"
            text = f"contact law of {names} gave a value out of range at vRel = {b:.4g} m/s (corrected)."
        elif code == K.EVENT_SINGULAR_MASS:
            text = "the mass matrix is not positive definite."
        else:
            continue
        out.append(f"[Alert] t = {t:.9g} s: {text}")
    return out


def end_alert(record: RunRecord) -> str:
    """The last alert: break time reached, or why the run stopped before it."""
    if record.complete:
        return f"[Alert] Break time of {record.end_time:.9g} s reached."
    return f"[Alert] Run stopped at {record.end_time:.9g} s ({record.stopped}): the results are incomplete."
