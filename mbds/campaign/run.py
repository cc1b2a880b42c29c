"""Running a campaign: the scheduling loop, the compile warm-up and the stop signals.

``run_campaign(plan, executor, stopping)`` is the loop of the scheduling process: it takes the
ledger over (tasks left ``running`` by a killed run are pending again), hands every ready task
to the executor while it has room, records each result, and ends when nothing is running and
nothing more can start (all done, or only failed and blocked chains left), or once
``stopping()`` is true and the running tasks have come back. A failed task blocks its own chain
only.

``warm_up(plan)`` compiles each distinct model structure of the campaign once, in this process,
before any task starts, so that no worker compiles. Compiled models live in the user's cache
(:func:`mbds.expr.cache.default_cache_dir`, keyed by the generated source's hash), so a new
campaign of models compiled before starts warm; ``campaign_cache(plan, private=True)`` keeps
them in ``<campaign folder>/.cache`` instead.

``stop_signals()`` turns SIGTERM and SIGUSR1 (Slurm's warning before the time limit) and Ctrl-C
into a flag: the campaign stops taking tasks and the running ones stop, write what they have and
are recorded as pending.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import threading
import time
import warnings
from dataclasses import dataclass, field

from mbds.campaign.executors import POLL
from mbds.campaign.ledger import DONE, FAILED, PENDING, RUNNING, Ledger, utc_now
from mbds.campaign.plan import DAP_BC, Plan, done_count, ready_tasks
from mbds.campaign.priority import by_remaining_work
from mbds.errors import ModelWarning

CACHE_FOLDER = ".cache"
STOP_SIGNALS = ("SIGTERM", "SIGUSR1", "SIGINT")


@dataclass
class Outcome:
    """What a call of :func:`run_campaign` did: task ids ``done``, ``failed`` and ``stopped``
    (sent back to pending) by it, whether it was told to stop, and its ``start`` and ``end``
    (UTC, ISO 8601)."""

    done: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    stopped: list[str] = field(default_factory=list)
    interrupted: bool = False
    start: str = ""
    end: str = ""


def campaign_cache(plan: Plan, private: bool = False) -> None:
    """With ``private``, set ``MBDS_CACHE_DIR`` to the campaign's cache folder unless it is set
    already (before the workers start, which inherit it); else the user's shared cache is used."""
    if private:
        os.environ.setdefault("MBDS_CACHE_DIR", str((plan.folder / CACHE_FOLDER).resolve()))


def warm_up(plan: Plan) -> int:
    """Compile (or load from the cache) each distinct model structure of the campaign's variants
    and run its stepper for no time; the number of distinct structures. (Its imports are made
    here: rank 0 alone warms up, and a worker importing this module does not load sympy.)"""
    if plan.model == DAP_BC:
        from mbds.campaign.dapbc_plan import warm_up_dapbc

        return warm_up_dapbc(plan)
    from mbds.campaign.variants import variant_files
    from mbds.expr.cache import source_hash
    from mbds.expr.codegen import generate_source
    from mbds.io.folder import read_model_files
    from mbds.model.load import assemble_model
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate

    base = read_model_files(plan.job.world_path())
    seen = set()
    with warnings.catch_warnings():  # the runs report the model's warnings
        warnings.simplefilter("ignore", ModelWarning)
        for variant in plan.variants or [None]:
            files = base if variant is None else variant_files(base, variant)[0]
            model = assemble_model(files)
            key = source_hash(generate_source(model.expressions))
            if key not in seen:
                seen.add(key)
                simulate(model, RunSettings(break_time=0.0))
    return len(seen)


def run_campaign(plan: Plan, executor, stopping, progress=None, workers: int = 1) -> Outcome:
    """Run the campaign's ready tasks on ``executor`` (:mod:`mbds.campaign.executors`, with
    ``workers`` processes running tasks) until none is left or ``stopping()``;
    ``progress(task_id, result, done, running)`` after each result and ``progress(None, None,
    done, running)`` after tasks are handed out, if given (``done``: tasks done in all). The run (host, workers, start, end)
    is added to the ledger's ``campaign["runs"]``."""
    ledger = Ledger.load(plan.folder)
    ledger.bind(plan)
    outcome = Outcome(start=utc_now())
    running: set[str] = set()
    told = False
    while True:
        changed = False
        for task_id, result in executor.results():
            running.discard(task_id)
            ledger.mark(task_id, save=False, **result)
            changed = True
            {DONE: outcome.done, FAILED: outcome.failed, PENDING: outcome.stopped}[result["state"]].append(task_id)
            if progress is not None:
                progress(task_id, result, done_count(plan, ledger), len(running))
        if stopping() and not told:
            told = outcome.interrupted = True
            executor.stop()
        if not told:
            for task in by_remaining_work(plan, ledger, ready_tasks(plan, ledger)):
                if executor.free() <= 0 or stopping():
                    break
                running.add(task.id)
                ledger.mark(task.id, RUNNING, save=executor.inline, **executor.where())
                executor.submit(task)  # the ledger is saved after the tasks are handed out
                changed = True
        if changed:
            ledger.save()
            if progress is not None:
                progress(None, None, done_count(plan, ledger), len(running))
        if not running:
            break
        time.sleep(POLL)
    outcome.end = utc_now()
    ledger.campaign.setdefault("runs", []).append(
        {"host": socket.gethostname(), "workers": workers, "start": outcome.start, "end": outcome.end})
    ledger.save()
    return outcome


@contextlib.contextmanager
def stop_signals():
    """A flag (a callable: is it set?) set by SIGTERM, SIGUSR1 or SIGINT while in the block; the
    previous handlers are restored after it."""
    flag = threading.Event()

    def handler(signum, frame):
        flag.set()

    names = [name for name in STOP_SIGNALS if hasattr(signal, name)]
    previous = {name: signal.signal(getattr(signal, name), handler) for name in names}
    try:
        yield flag.is_set
    finally:
        for name, old in previous.items():
            signal.signal(getattr(signal, name), old)

