"""Counting numba compilations in this process: a campaign's workers should find all machine
code in the cache that the warm-up filled, and each task records how often they did not."""

from __future__ import annotations

import contextlib


@contextlib.contextmanager
def counted_compiles():
    """A counter whose ``count`` is the number of numba compilations in this process while in
    the block (numba, and the scipy it loads, are imported here: on the first task, not when a
    worker starts)."""
    from numba.core import event

    class Counter(event.Listener):
        """Counts the ends of ``numba:compile`` events (one per function compiled, cache loads
        do not count)."""

        def __init__(self):
            self.count = 0

        def on_start(self, event_):
            """Counted at the end."""

        def on_end(self, event_):
            self.count += 1

    counter = Counter()
    with event.install_listener("numba:compile", counter):
        yield counter
