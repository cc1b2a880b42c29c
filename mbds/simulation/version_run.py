"""One run of a model version: its start state, the run, and its outputs in the version folder."""

from __future__ import annotations

import contextlib
import copy
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from mbds.data.history import FILE_NAME, HistoryStream, read_final_state
from mbds.data.legacy import (
    HEADER_LINES,
    TableStreams,
    end_alert,
    event_alerts,
    write_log,
)
from mbds.data.record import RunRecord, SeriesMaker, make_header, make_record
from mbds.data.run_result import RunState, Samples
from mbds.errors import ModelError
from mbds.io.folder import run_number, version_name
from mbds.io.text import atomic_path
from mbds.kernel import layout as K
from mbds.model.arrays import flatten
from mbds.model.load import Model, load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.options import RunOptions
from mbds.simulation.run import (
    RunStopped,
    continue_from,
    initial_point_values,
    initial_state,
    simulate,
)
from mbds.simulation.versions import job_settings

PROGRESS_CHUNK = 256
"""History samples per call of the stepper at most (each call also ends after a bounded number of
passes of its step loop): how often progress, Ctrl-C and the limits are looked at, and how many
samples are held in memory before they go to the files."""


Progress = Callable[[float, float, float, float], None]
"""progress(start, now, end, steps): times in s and the steps taken so far in this run."""


def run_version(folder: str | Path, options: RunOptions, progress: Progress | None = None) -> RunRecord:
    """Run the version in ``folder`` (or one replicate of it, ``NNN/rK``) and write history.nc, data.txt, watches.txt and log.txt
    there. ``progress`` may raise KeyboardInterrupt to stop the run: what was computed is
    written, marked incomplete, as when the state stops being finite. Raises ModelError on bad
    input."""
    folder = Path(folder)
    number = run_number(folder)
    if number is None:
        raise ModelError("not a version folder (000, 001, ...) or a replicate folder in one (000/r0)", folder)
    model = load_model(folder, version=number, from_record=True)
    job = options.job if options.job is not None else job_settings(folder.parent, model.world_path.stem)
    state, seed = _start_state(model, folder, options)
    start = copy.deepcopy(state)
    t0 = float(state.clock[K.T])
    end = t0 + (options.duration if options.duration is not None else model.break_time)
    alerts: list[str] = []
    limit = job.max_lines_in_log

    def check_log():
        """maxLinesInLog counts every line of the log: its fixed lines and the alerts so far."""
        if limit > 0 and HEADER_LINES + len(alerts) > limit:
            del alerts[max(limit - HEADER_LINES, 0) :]
            raise RunStopped(f"the log exceeded maxLinesInLog = {limit} lines")

    def on_events(rows):
        alerts.extend(event_alerts(rows, model))
        check_log()

    def report(t):
        check_log()
        if progress is not None:
            progress(t0, t, end, state.clock[K.STEPS] - start.clock[K.STEPS])

    settings = RunSettings(end, seed, tuple(job.lexico_randomization_range))
    header = make_header(model, start, seed=seed, break_time=end, continued_from=options.start_from, folder=folder)
    for stale in folder.glob(".*.tmp"):  # left by a run that was killed while writing
        stale.unlink(missing_ok=True)
    wall = time.perf_counter()
    with contextlib.ExitStack() as files:
        history_path, data_path, watches_path = (
            files.enter_context(atomic_path(folder / name)) for name in (FILE_NAME, "data.txt", "watches.txt"))
        history = HistoryStream(history_path, header)
        files.callback(history.close)
        tables = TableStreams(header, *(files.enter_context(open(p, "w", encoding="utf-8"))
                                        for p in (data_path, watches_path)))
        outputs = StreamedOutputs(SeriesMaker(model, start), (history, tables))
        result = simulate(model, settings, state, report, on_events=on_events, on_samples=outputs.append,
                          chunk=PROGRESS_CHUNK)
        record = make_record(header, model, result, start, outputs.sampled)
        record.wall_time = time.perf_counter() - wall
        record.alerts = alerts + [end_alert(record)]
        history.finish(record)
    write_log(folder, record)
    return record


class StreamedOutputs:
    """Where a run's samples go as it makes them: turned into series by ``maker``, appended to
    every one of ``sinks``; ``sampled`` holds the first and last sample times (s) and the count."""

    def __init__(self, maker: SeriesMaker, sinks):
        self.maker, self.sinks = maker, sinks
        self.sampled = (float("nan"), float("nan"), 0)

    def append(self, samples: Samples) -> None:
        series = self.maker(samples)
        for sink in self.sinks:
            sink.append(series)
        first, _, count = self.sampled
        self.sampled = (first if count else float(samples.time[0]), float(samples.time[-1]), count + len(samples.time))


def _start_state(model: Model, folder: Path, options: RunOptions) -> tuple[RunState, int]:
    """The state to start from and the seed of the chain of runs it belongs to."""
    if options.start_from is None:
        return initial_state(model, options.seed), options.seed
    path = folder.parent / version_name(options.start_from) / FILE_NAME
    state, attrs = read_final_state(path)
    continue_from(state)
    if state.q.shape != model.q0.shape:
        raise ModelError(f"its run has {len(state.q)} coordinates, this model {len(model.q0)}", path)
    points = sum(len(b.points) for b in model.bodies)
    if state.point_loss.shape != (points,):
        raise ModelError(f"its run has {len(state.point_loss)} shape points, this model {points}", path)
    start = initial_point_values(flatten(model))[:, K.TEMP]  # points heated now but not then start at ambient
    unknown = np.isnan(state.point_interval[:, K.TEMP])
    state.point_interval[unknown, K.TEMP] = start[unknown]
    return state, int(attrs.get("seed", options.seed))
