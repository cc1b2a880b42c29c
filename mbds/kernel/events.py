"""The kernel's event log: rows (time, code, value, value) with codes from mbds.kernel.layout."""

from __future__ import annotations

from mbds.kernel.jit import jit


@jit(refcount=False)
def log_event(events, t, code, a, b):
    """Append an event at time t (s) while the buffer has room."""
    data, count = events
    k = count[0]
    if k < data.shape[0]:
        data[k, 0] = t
        data[k, 1] = code
        data[k, 2] = a
        data[k, 3] = b
        count[0] = k + 1
