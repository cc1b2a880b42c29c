"""``mbds run``: run one version of a model with a progress bar, Ctrl-C handling and a summary."""

from __future__ import annotations

import contextlib
import signal
import threading
import time
from pathlib import Path

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

from mbds.data.history import FILE_NAME as HISTORY
from mbds.data.history import read_attributes
from mbds.data.record import RunRecord
from mbds.errors import ModelError
from mbds.io.lock import folder_lock
from mbds.simulation.version_run import RunOptions, run_version
from mbds.simulation.versions import run_folder

EXIT_STOPPED = 1
EXIT_INTERRUPTED = 130
OUTPUTS = "history.nc data.txt watches.txt log.txt"


def run_command(path: Path, options: RunOptions, console: Console, force: bool = False) -> int:
    """Run the version that ``path`` names (see :func:`run_folder`); return the exit code. A
    version with a complete run, or whose copies differ from the model folder's files, is run
    again only with ``force``."""
    folder = run_folder(path, options.start_from, force)
    history = folder / HISTORY
    if not force and history.is_file() and read_attributes(history).get("complete"):
        raise ModelError("has a complete run: run with --force to replace it (its outputs are overwritten)", folder)
    console.print(f"running {escape(str(folder))}", highlight=False)
    wall = time.perf_counter()
    with folder_lock(folder, "mbds run"), interrupt_flag() as interrupted, progress_bar(console) as bar:
        try:
            record = run_version(folder, options, track(bar, interrupted))
        except KeyboardInterrupt:  # a second Ctrl-C
            console.print("interrupted; nothing written", style="yellow")
            return EXIT_INTERRUPTED
    print_run_summary(record, folder, time.perf_counter() - wall, console)
    return exit_code(record)


def exit_code(record: RunRecord) -> int:
    """0 when the run reached its break time, 130 when Ctrl-C stopped it, else 1."""
    if record.complete:
        return 0
    return EXIT_INTERRUPTED if record.stopped == "interrupted" else EXIT_STOPPED


def track(bar: Progress, interrupted: threading.Event):
    """A progress callback for :func:`run_version` that shows the run as a new task of ``bar``
    (simulated time, steps per second of wall time) and stops it once ``interrupted`` is set."""
    wall = time.perf_counter()
    task = bar.add_task("", total=None, now=0.0, end=0.0, rate=0.0)

    def progress(start, now, end, steps):
        elapsed = max(time.perf_counter() - wall, 1e-9)
        bar.update(task, total=end - start, completed=now - start, now=now, end=end, rate=steps / elapsed)
        if interrupted.is_set():
            raise KeyboardInterrupt

    return progress


def progress_bar(console: Console) -> Progress:
    """Simulated time against end time and steps per second; silent when not on a terminal."""
    return Progress(
        TextColumn("t = {task.fields[now]:.6g} / {task.fields[end]:.6g} s"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TextColumn("{task.fields[rate]:,.0f} steps/s"),
        TimeElapsedColumn(),
        console=console,
        disable=not console.is_terminal,
    )


@contextlib.contextmanager
def interrupt_flag():
    """A flag set by the first Ctrl-C or SIGTERM (a second one acts at once, as without it)."""
    flag = threading.Event()
    if threading.current_thread() is not threading.main_thread():
        yield flag
        return
    previous = {}

    def handler(signum, frame):
        flag.set()
        for number, action in previous.items():
            signal.signal(number, action)

    for number in (signal.SIGINT, signal.SIGTERM):
        previous[number] = signal.signal(number, handler)
    try:
        yield flag
    finally:
        for number, action in previous.items():
            signal.signal(number, action)


def print_run_summary(r: RunRecord, folder: Path, wall: float, console: Console) -> None:
    """Where the run ended, its counts, energies and wall time (s)."""
    c = r.counters
    if r.complete:
        console.print(f"break time reached at t = {r.end_time:.9g} s", highlight=False)
    else:
        stop = f"stopped at t = {r.end_time:.9g} s ({escape(r.stopped)}): results are incomplete"
        console.print(f"[yellow]{stop}[/yellow]", highlight=False)
    console.print(
        f"steps {c['steps']} ({c['rejected_steps']} rejected), impacts {c['impacts']}, "
        f"LCP failures {c['lcp_failures']}, over-penetrations {c['over_penetrations']}",
        highlight=False,
    )
    console.print(
        f"mechanical energy {r.start_energy:.6g} J -> {r.end_energy:.6g} J, lost work {r.run_lost_work:.6g} J, "
        f"driver work {r.run_driver_work:.6g} J, energy balance residual {r.energy_residual:.3g} J",
        highlight=False,
    )
    console.print(f"wall time {wall:.3g} s; wrote {OUTPUTS} in {escape(str(folder))}", highlight=False)
