"""One run of a model version: its start state, the run, and its outputs in the version folder."""

from __future__ import annotations

import copy
import time
from collections.abc import Callable
from pathlib import Path

from mbds.data.history import FILE_NAME, read_final_state, write_history
from mbds.data.legacy import HEADER_LINES, end_alert, event_alerts, write_legacy
from mbds.data.record import RunRecord, make_record
from mbds.errors import ModelError
from mbds.io.folder import run_number, version_name
from mbds.kernel import layout as K
from mbds.model.load import Model, load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.options import RunOptions
from mbds.simulation.run import RunState, RunStopped, continue_from, initial_state, simulate
from mbds.simulation.versions import job_settings

PROGRESS_CHUNK = 256
"""History samples per call of the stepper: how often progress and Ctrl-C are looked at."""


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
    model = load_model(folder, version=number)
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
    wall = time.perf_counter()
    result = simulate(model, settings, state, report, on_events=on_events, chunk=PROGRESS_CHUNK)
    record = make_record(
        model, result, start, seed=seed, break_time=end, continued_from=options.start_from, folder=folder
    )
    record.wall_time = time.perf_counter() - wall
    record.alerts = alerts + [end_alert(record)]
    for stale in folder.glob(".*.tmp"):  # left by a run that was killed while writing
        stale.unlink(missing_ok=True)
    write_history(folder / FILE_NAME, record)
    write_legacy(folder, record)
    return record


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
    return state, int(attrs.get("seed", options.seed))
