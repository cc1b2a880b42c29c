"""What the scheduling rank shows while a campaign runs.

On a terminal: a rich bar with the tasks done, the running count, failures, elapsed time and
ETA. Elsewhere (a batch job's log, a pipe): one line per phase and one line per finished or
failed task, flushed at once, so that a Slurm output file shows progress as it happens.
"""

from __future__ import annotations

import sys
import time

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)


class CampaignProgress:
    """Reports phases and task results on stderr; use as a context manager around the run."""

    def __init__(self, total: int, done: int, console: Console | None = None):
        self.console = console or Console(stderr=True)
        self.terminal = self.console.is_terminal
        self.total, self.done, self.failed, self.running = total, done, 0, 0
        self._bar = Progress(
            TextColumn("tasks"), BarColumn(), MofNCompleteColumn(),
            TextColumn("{task.fields[running]} running, {task.fields[failed]} failed"),
            TimeElapsedColumn(), TextColumn("ETA"), TimeRemainingColumn(),
            console=self.console, disable=not self.terminal,
        )
        self._shown = None
        self._phase_start = time.monotonic()

    def phase(self, text: str) -> None:
        """Start a phase (warm-up, running): a line in logs, a printed line above the bar."""
        self._phase_start = time.monotonic()
        self._line(text)

    def phase_done(self, text: str) -> None:
        """End a phase with its duration."""
        self._line(f"{text} ({time.monotonic() - self._phase_start:.1f} s)")

    def started(self, running: int) -> None:
        """The number of tasks running now."""
        self.running = running
        self._refresh()

    def finished(self, task_id: str, result: dict, done: int, running: int) -> None:
        """A task came back with ``result`` (the ledger entry); ``done`` tasks are done in all."""
        self.done, self.running = done, running
        state = result.get("state")
        if state == "failed":
            self.failed += 1
            self._line(f"task {task_id} failed: {result.get('reason', '')}")
        elif not self.terminal:
            self._line(f"task {task_id} {state} in {result.get('wall', 0):.1f} s ({done}/{self.total})")
        self._refresh()

    def __enter__(self):
        self._bar.__enter__()
        self._shown = self._bar.add_task("tasks", total=self.total, completed=self.done, running=0, failed=0)
        return self

    def __exit__(self, *exc):
        return self._bar.__exit__(*exc)

    def _refresh(self) -> None:
        if self._shown is not None:
            self._bar.update(self._shown, completed=self.done, running=self.running, failed=self.failed)

    def _line(self, text: str) -> None:
        if self.terminal:
            self.console.print(text)
        else:
            print(text, file=sys.stderr, flush=True)
