"""Several independent figures drawn and saved at once, each in a process of its own.

Drawing a figure is matplotlib's work in Python, one core per figure. Where the platform forks
and more than one core is free, :func:`save_figures` forks a process per figure (at most one per
core at a time); each process draws its figure from the data already in memory and saves it, as
:func:`mbds.plot.save` does in this process. A figure whose process did not end well is drawn
again here, so an error is raised as if everything had been drawn in this process. Elsewhere
the figures are drawn one after the other. Either way the files are the same."""

from __future__ import annotations

import multiprocessing
import os
import sys
from collections.abc import Callable
from multiprocessing.connection import wait
from pathlib import Path

from matplotlib.figure import Figure

from mbds.plot.figure import save

Drawing = tuple[Callable[[], Figure], Path]
"""A function that makes a figure, and the file to save it to (png, svg or pdf)."""


def save_figures(drawings: list[Drawing], dpi: int = 100) -> list[Path]:
    """Make and save each figure of ``drawings``; the paths written, in order. The functions
    must read data already in memory (a forked process must not share an open file with this
    one)."""
    workers = min(len(drawings), free_cores())
    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return [save(make(), path, dpi=dpi) for make, path in drawings]
    context = multiprocessing.get_context("fork")
    sys.stdout.flush()  # what is buffered here would otherwise be written again by each process
    sys.stderr.flush()
    waiting, running, failed = list(drawings), {}, []
    while waiting or running:
        while waiting and len(running) < workers:
            make, path = waiting.pop(0)
            process = context.Process(target=_draw_and_exit, args=(make, path, dpi), daemon=True)
            process.start()
            running[process.sentinel] = (process, (make, path))
        for sentinel in wait(list(running)):
            process, drawing = running.pop(sentinel)
            process.join()
            if process.exitcode != 0:
                failed.append(drawing)
    for make, path in failed:  # drawn here, where an error is raised as usual
        save(make(), path, dpi=dpi)
    return [path for _, path in drawings]


def free_cores() -> int:
    """The cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def _draw_and_exit(make: Callable[[], Figure], path: Path, dpi: int) -> None:
    """A forked process's work: the figure saved, exit code 0; any error, exit code 1 and no
    message (the figure is drawn again in the parent, which reports it)."""
    try:
        save(make(), path, dpi=dpi)
    except BaseException:  # noqa: BLE001 - reported by the parent, which draws the figure again
        sys.exit(1)
