"""``mbds job`` and ``mbds next``: run a job file version after version; make the next version."""

from __future__ import annotations

import threading
from pathlib import Path

from rich.console import Console
from rich.markup import escape
from rich.progress import Progress

from mbds.cli.run import (
    EXIT_INTERRUPTED,
    EXIT_STOPPED,
    exit_code,
    interrupt_flag,
    print_run_summary,
    progress_bar,
    track,
)
from mbds.data.record import RunRecord
from mbds.simulation.job import JobReport, next_version, run_job


def job_command(path: Path, console: Console) -> int:
    """Run the job file ``path`` (see :func:`run_job`); return the exit code."""
    with interrupt_flag() as interrupted, progress_bar(console) as bar:
        try:
            result = run_job(path, _Shown(console, bar, interrupted))
        except KeyboardInterrupt:
            console.print("job interrupted; run it again to resume", style="yellow")
            return EXIT_INTERRUPTED
    ran = f"{len(result.runs)} version(s) run, {len(result.created)} created"
    if result.stopped:
        console.print(f"[yellow]job stopped: {escape(result.stopped)}; {ran}[/yellow]", highlight=False)
        return exit_code(result.runs[-1][1]) if result.runs and not result.runs[-1][1].complete else EXIT_STOPPED
    if result.runs or result.created:
        console.print(f"job finished: {ran}", highlight=False)
    return 0


def next_command(folder: Path, console: Console) -> None:
    """Create the version after ``folder`` from its complete run."""
    created = next_version(folder)
    console.print(f"created {escape(str(created))} (changes in {escape(str(created / 'wear.nc'))})", highlight=False)


class _Shown(JobReport):
    """A job on the console: its news, a progress bar and a summary per version run."""

    def __init__(self, console: Console, bar: Progress, interrupted: threading.Event):
        self.console, self.bar, self.interrupted = console, bar, interrupted

    def note(self, text):
        self.console.print(escape(text), highlight=False)

    def start(self, folder, why):
        if self.interrupted.is_set():
            raise KeyboardInterrupt
        self.console.print(f"running {escape(str(folder))} ({escape(why)})", highlight=False)
        return track(self.bar, self.interrupted)

    def finish(self, folder: Path, record: RunRecord, wall: float):
        print_run_summary(record, folder, wall, self.console)
