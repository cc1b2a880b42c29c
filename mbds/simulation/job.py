"""Jobs (``.job`` files): the listed versions of a model run one after the other in one process,
each complete version followed, with ``createNextVersionAtEnd = 1``, by its worn successor.

A job resumes: a version whose run is complete (see :func:`incomplete`) is not run again, an
incomplete one is run again in full, and a complete version without its successor gets one.
The rules are stated in docs/wear.md ("Jobs").
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mbds.data.history import FILE_NAME as HISTORY
from mbds.data.history import read_attributes, read_point_losses
from mbds.data.record import RunRecord
from mbds.errors import ModelError, ModelWarning
from mbds.io.folder import version_name, version_number
from mbds.io.job import JobFile, JobSettings, read_checked_job, version_exists
from mbds.io.lock import folder_lock
from mbds.model.load import model_break_time
from mbds.simulation.run import RunStopped
from mbds.simulation.version_run import Progress, RunOptions, run_version
from mbds.simulation.versions import ensure_version
from mbds.wear.version import create_next_version


def incomplete(folder: str | Path) -> str:
    """Why the version in ``folder`` has no complete run ("" when it has one: its ``history.nc``
    says the run reached its break time, and the run lasted the world file's ``breakTime``)."""
    folder = Path(folder)
    path = folder / HISTORY
    if not path.is_file():
        return "not run yet"
    attrs = read_attributes(path)
    if not attrs.get("complete"):
        return f"its run stopped at t = {attrs['end_time']:.9g} s ({attrs['stop_reason']})"
    if continuation(folder) is not None:  # a continued run is complete at the length asked of it
        return ""
    length = float(attrs["break_time"] - attrs["start_time"])
    with warnings.catch_warnings():  # the run of the version repeats any warning
        warnings.simplefilter("ignore", ModelWarning)
        full = model_break_time(folder)
    if not math.isclose(length, full, rel_tol=1e-9):
        return f"its run lasted {length:.9g} s, not the world file's breakTime of {full:.9g} s"
    return ""


def continuation(folder: str | Path) -> tuple[int, float] | None:
    """For a version whose run continues another version's end state (``mbds run --from``):
    that version's number and the length of the run (s); None for a run from the model's start
    or a version not run yet."""
    path = Path(folder) / HISTORY
    if not path.is_file():
        return None
    attrs = read_attributes(path)
    source = int(attrs.get("continued_from", -1))
    if source < 0:
        return None
    return source, float(attrs["break_time"] - attrs["start_time"])


def next_version(folder: str | Path, runs: Sequence[str | Path] = ()) -> Path:
    """Create version N + 1 from the complete run of version N in ``folder``: its shapes worn
    by the lost work (J) at each shape point (docs/wear.md); return the new folder. With
    ``runs`` (run folders of replicates of version N, campaigns in ensemble mode) the shapes
    are worn by the mean over those runs of the lost work at each point."""
    folder = Path(folder)
    if version_number(folder) is None:
        raise ModelError("not a version folder (000, 001, ...)", folder)
    if not folder.is_dir():
        raise ModelError("no such version folder", folder)
    runs = [Path(run) for run in runs] or [folder]
    for run in runs:
        reason = incomplete(run)
        if reason:
            raise ModelError(f"{reason}; the next version needs a complete run of this one", run / HISTORY)
    return create_next_version(folder, mean_point_losses([run / HISTORY for run in runs]))


def mean_point_losses(paths: Sequence[Path]) -> dict[str, np.ndarray]:
    """The lost work (J) at each shape point by body, averaged over the runs of the
    ``history.nc`` files at ``paths`` (runs of one model)."""
    losses = [read_point_losses(path) for path in paths]
    for path, loss in zip(paths[1:], losses[1:]):
        if {b: v.shape for b, v in loss.items()} != {b: v.shape for b, v in losses[0].items()}:
            raise ModelError(f"its bodies or shape points differ from those of {paths[0]}", path)
    return {body: np.mean([loss[body] for loss in losses], axis=0) for body in losses[0]}


class JobReport:
    """What a job tells as it goes; this one says nothing. ``start`` may raise
    KeyboardInterrupt to stop the job before a version, its progress callback to stop the run
    (which is then written, incomplete)."""

    def note(self, text: str) -> None:
        """News of the job: a version skipped or created, nothing to do."""

    def start(self, folder: Path, why: str) -> Progress | None:
        """Version ``folder`` starts running (``why``: why it had no complete run); the
        progress callback of its run."""
        return None

    def finish(self, folder: Path, record: RunRecord, wall: float) -> None:
        """The run of version ``folder`` ended after ``wall`` s."""


@dataclass
class JobResult:
    """What a job did: the runs (version, record, wall time in s) and the versions created, in
    order; ``stopped`` says why it ended before its last version ("" when it did not)."""

    runs: list[tuple[int, RunRecord, float]] = field(default_factory=list)
    created: list[int] = field(default_factory=list)
    stopped: str = ""


def run_job(path: str | Path, report: JobReport | None = None) -> JobResult:
    """Run the job file at ``path``: every listed version without a complete run is run in full
    from the model's start (a version continuing another's run, from that run's end) and, with ``createNextVersionAtEnd = 1``, every complete one without
    a successor gets one. The job stops at the first run that does not complete (Ctrl-C,
    ``maxMinutesForJob``, ``maxMinutesForJobs``, ``maxLinesInLog``, a state that is not
    finite); bad input raises ModelError."""
    report = report or JobReport()
    job = read_checked_job(path)
    with folder_lock(job.path.parent, "mbds job"):
        return _run_job(job, report)


def _run_job(job: JobFile, report: JobReport) -> JobResult:
    folder, settings = job.path.parent, job.settings
    result = JobResult()
    listed = f"{job.path.name} ({_listing(job.versions)})"
    if all(_done(folder / version_name(n), settings.create_next_version_at_end) for n in job.versions):
        report.note(f"nothing to do: every version of {listed} has a complete run")
        return result
    if settings.delay_start_minutes:
        report.note(f"waiting {settings.delay_start_minutes:g} min (delayStartMinutes)")
        time.sleep(60.0 * settings.delay_start_minutes)
    deadline = time.monotonic() + 60.0 * settings.max_minutes_for_jobs
    for number in job.versions:
        version = folder / version_name(number)
        if number == 0:
            ensure_version(folder, 0, job.world_path())
        why = incomplete(version)
        if not why:
            report.note(f"{version}: complete, not run again")
        elif time.monotonic() >= deadline:
            result.stopped = f"maxMinutesForJobs = {settings.max_minutes_for_jobs:g} min reached before {version}"
            return result
        else:
            record, wall = _run(version, why, job, report, deadline)
            result.runs.append((number, record, wall))
            if not record.complete:
                result.stopped = f"{version} stopped ({record.stopped})"
                return result
        if settings.create_next_version_at_end and not version_exists(folder / version_name(number + 1)):
            created = next_version(version)
            result.created.append(number + 1)
            report.note(f"created {created}, worn by the losses of {version_name(number)}")
    return result


def _run(version: Path, why: str, job: JobFile, report: JobReport, deadline: float) -> tuple[RunRecord, float]:
    """Run ``version`` in full under the job's time limits; its record and wall time (s). A
    version that continues another's run (``mbds run --from``) is run again from that run's end
    state for the same length, so that its start is kept."""
    begun = time.monotonic()
    options = RunOptions(job=job.settings)
    continued = continuation(version)
    if continued is not None:
        options.start_from, options.duration = continued
        why += f"; it continues the run of {version_name(continued[0])}, from whose end it runs again"
    shown = report.start(version, why)
    with folder_lock(version, "mbds job"):
        record = run_version(version, options, time_limits(job.settings, deadline, shown))
    wall = time.monotonic() - begun
    report.finish(version, record, wall)
    return record, wall


def time_limits(settings: JobSettings, deadline: float = math.inf, shown: Progress | None = None) -> Progress:
    """The progress callback of a run started now: it stops the run past ``maxMinutesForJob``
    or past ``deadline`` (``time.monotonic()`` s, from ``maxMinutesForJobs``), and passes the
    progress on to ``shown``."""
    own_deadline = time.monotonic() + 60.0 * settings.max_minutes_for_job

    def progress(start, now, end, steps):
        clock = time.monotonic()
        if clock > own_deadline:
            raise RunStopped(f"maxMinutesForJob = {settings.max_minutes_for_job:g} min exceeded")
        if clock > deadline:
            raise RunStopped(f"maxMinutesForJobs = {settings.max_minutes_for_jobs:g} min exceeded")
        if shown is not None:
            shown(start, now, end, steps)

    return progress


def _done(version: Path, successor_needed: bool) -> bool:
    """Whether a job has nothing left to do for ``version``."""
    if successor_needed and not version_exists(version.parent / version_name(version_number(version) + 1)):
        return False
    return version_exists(version) and not incomplete(version)


def _listing(versions: list[int]) -> str:
    """``000-003, 007``: the versions, runs of consecutive numbers as ranges."""
    parts, first = [], 0
    for i in range(1, len(versions) + 1):
        if i == len(versions) or versions[i] != versions[i - 1] + 1:
            a, b = versions[first], versions[i - 1]
            parts.append(version_name(a) if a == b else f"{version_name(a)}-{version_name(b)}")
            first = i
    return ", ".join(parts)
