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
them in ``<campaign folder>/.cache`` instead. ``mbds-campaign run`` uses ``warm_up_first(plan)``:
the first variant's structure is made ready before the loop, the others' before their first
runs, from the structure each chain's prepare task found (:mod:`mbds.campaign.structures`).

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
from dataclasses import dataclass, field

from mbds.campaign.ledger import DONE, FAILED, PENDING, RUNNING, Ledger, utc_now
from mbds.campaign.plan import DAP_BC, RUN, Plan, done_count, ready_tasks
from mbds.campaign.priority import by_remaining_work
from mbds.campaign.structures import Structures

CACHE_FOLDER = ".cache"
LOOP_POLL = 0.001
"""Seconds the scheduling loop sleeps when nothing came back and nothing was handed out."""
SAVE_EVERY = 0.1
"""While tasks run, the ledger is written at most this often (s), and at most ``1 / SAVE_SHARE``
of the loop's time: writing it takes time proportional to the plan (9 ms for 528 tasks,
measured), and a result that comes back meanwhile waits. A task whose result was not yet
written when the scheduler is killed runs again and finds its outputs there
(:mod:`mbds.campaign.tasks`). Every change is written when the loop ends."""
SAVE_SHARE = 20.0
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
    and run its stepper for no time, and keep each variant's model record in the cache
    (:mod:`mbds.model.known`), as a campaign run before would leave it; the number of distinct
    structures. (Its imports are made here: rank 0 alone warms up, and a worker importing this
    module does not load sympy.)"""
    if plan.model == DAP_BC:
        from mbds.campaign.dapbc_plan import warm_up_dapbc

        return warm_up_dapbc(plan)
    structures = Structures(plan)
    for variant in plan.variants or [None]:
        structures.make_ready(variant)
        structures.keep_record(variant)
    return structures.count


def warm_up_first(plan: Plan):
    """The warm-up of ``mbds-campaign run``: the first variant's model structure made ready here,
    and the :class:`~mbds.campaign.structures.Structures` that make the others' ready as their
    runs come (``run_campaign``'s ``structures``), so the workers start at once; a DAP_BC plan
    (one compiled model for all variants) is warmed up whole, and None returned."""
    if plan.model == DAP_BC:
        warm_up(plan)
        return None
    structures = Structures(plan)
    structures.make_ready(plan.variants[0] if plan.variants else None)
    return structures


def run_campaign(plan: Plan, executor, stopping, progress=None, workers: int = 1, structures=None) -> Outcome:
    """Run the campaign's ready tasks on ``executor`` (:mod:`mbds.campaign.executors`, with
    ``workers`` processes running tasks) until none is left or ``stopping()``;
    ``progress(task_id, result, done, running)`` after each result and ``progress(None, None,
    done, running)`` after tasks are handed out, if given (``done``: tasks done in all). The run (host, workers, start, end)
    is added to the ledger's ``campaign["runs"]``. With ``structures``
    (:class:`mbds.campaign.structures.Structures`), each run's model structure is made ready
    in this process before the run is handed out (instead of :func:`warm_up` before the loop)."""
    ledger = Ledger.load(plan.folder)
    ledger.bind(plan)
    if structures is not None:
        for task_id, entry in ledger.tasks.items():
            structures.learn(task_id, entry)
    outcome = Outcome(start=utc_now())
    running: set[str] = set()
    told = False
    changed = True  # the ready tasks are looked for when results came in, and at the start
    unsaved, next_save = False, 0.0
    while True:
        handing_out = changed
        changed = False
        for task_id, result in executor.results():
            running.discard(task_id)
            ledger.mark(task_id, save=False, **result)
            if structures is not None:
                structures.learn(task_id, result)
            changed = True
            {DONE: outcome.done, FAILED: outcome.failed, PENDING: outcome.stopped}[result["state"]].append(task_id)
            if progress is not None:
                progress(task_id, result, done_count(plan, ledger), len(running))
        if stopping() and not told:
            told = outcome.interrupted = True
            executor.stop()
        if not told and (handing_out or changed) and executor.free() > 0:
            for task in by_remaining_work(plan, ledger, ready_tasks(plan, ledger)):
                if executor.free() <= 0 or stopping():
                    break
                if structures is not None and task.kind == RUN:
                    structures.make_ready(task.variant)
                running.add(task.id)
                ledger.mark(task.id, RUNNING, save=executor.inline, **executor.where())
                executor.submit(task)  # the ledger is saved after the tasks are handed out
                changed = True
        if changed:
            unsaved = True
            if progress is not None:
                progress(None, None, done_count(plan, ledger), len(running))
        # (with an inline executor, each task writes it as it starts: Ledger.mark above)
        if unsaved and time.monotonic() >= next_save:
            begun = time.monotonic()
            ledger.save()
            unsaved, next_save = False, begun + max(SAVE_EVERY, SAVE_SHARE * (time.monotonic() - begun))
        if not running:
            break
        if not changed:
            time.sleep(LOOP_POLL)
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

