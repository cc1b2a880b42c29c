"""Where a campaign's tasks run: in this process, in a process pool, or on MPI ranks.

The scheduling loop (:func:`mbds.campaign.run.run_campaign`) sees every executor the same way:

- ``free()``: how many more tasks it can take now;
- ``where() -> dict``: what to record in the ledger about where the next task will run
  (``{"rank": k}``);
- ``submit(task)``: start ``task`` (performed at once by :class:`Sequential`);
- ``results() -> list[(task id, result)]``: the tasks finished since the last call, each with
  the result of :func:`mbds.campaign.tasks.run_task`;
- ``stop()``: ask the running tasks to stop soon (their runs write what they have);
- ``close()``: release the workers;
- ``inline``: whether ``submit`` performs the task before it returns (the loop then saves the
  ledger before submitting, so that ``status`` shows the task running).

Only the scheduling process calls these, and only it writes the ledger. Each task is performed by
``run_task`` in one process, so a task's outputs do not depend on the executor or the number of
ranks.
"""

from __future__ import annotations

import gc
import multiprocessing
import os
import signal
import time
from concurrent.futures import Future, ProcessPoolExecutor

from mbds.campaign.plan import Task
from mbds.campaign.tasks import import_ahead, import_for, run_task

POLL = 0.001
"""The longest sleep between polls of an idle worker (s): MPI's blocking receive busy-waits. The
scheduler answers a result within a few ms (:data:`mbds.campaign.run.LOOP_POLL`)."""
TASK, RESULT, STOP, QUIT, PREPARE, LOAD = 1, 2, 3, 4, 5, 6  # MPI message tags


class Sequential:
    """One task at a time, in this process (tests, a laptop without MPI)."""

    inline = True

    def __init__(self, stopping):
        self._stopping = stopping
        self._done: list[tuple[str, dict]] = []

    def free(self) -> int:
        return 1

    def where(self) -> dict:
        return {"rank": 0}

    def submit(self, task: Task) -> None:
        self._done.append((task.id, run_task(task, self._stopping)))

    def results(self) -> list[tuple[str, dict]]:
        done, self._done = self._done, []
        return done

    def stop(self) -> None:
        """The stop flag is read by the task itself."""

    def close(self) -> None:
        """Nothing to release."""


class Pool:
    """``workers`` processes of a :class:`concurrent.futures.ProcessPoolExecutor`, each running
    one task at a time; a shared event tells their runs to stop."""

    inline = False

    def __init__(self, workers: int):
        context = multiprocessing.get_context("spawn")  # no forked copies of this process's state
        self._event = context.Event()
        self._executor = ProcessPoolExecutor(workers, mp_context=context, initializer=_pool_worker,
                                             initargs=(self._event,))
        self._workers = workers
        self._running: dict[str, Future] = {}

    def free(self) -> int:
        return self._workers - len(self._running)

    def where(self) -> dict:
        return {}

    def submit(self, task: Task) -> None:
        self._running[task.id] = self._executor.submit(_pool_task, task)

    def results(self) -> list[tuple[str, dict]]:
        finished = [task_id for task_id, future in self._running.items() if future.done()]
        return [(task_id, self._running.pop(task_id).result()) for task_id in finished]

    def stop(self) -> None:
        self._event.set()

    def close(self) -> None:
        self._executor.shutdown(wait=True)


_pool_event = None  # the pool's stop event, in a worker process


def _pool_worker(event) -> None:
    """Set up a pool process: Ctrl-C is the scheduler's to handle; ``event`` stops runs."""
    global _pool_event
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _pool_event = event


def _pool_task(task: Task) -> dict:
    return run_task(task, _pool_event.is_set)


class Ranks:
    """MPI ranks 1 ... size - 1 of ``comm``, each running one task at a time; this process
    (rank 0) only schedules. The workers run :func:`serve`."""

    inline = False

    def __init__(self, comm):
        self._comm = comm
        self._idle = list(range(comm.Get_size() - 1, 0, -1))
        self._busy: dict[int, str] = {}

    def free(self) -> int:
        return len(self._idle)

    def where(self) -> dict:
        return {"rank": self._idle[-1]}

    def submit(self, task: Task) -> None:
        rank = self._idle.pop()
        self._busy[rank] = task.id
        self._comm.send(task, dest=rank, tag=TASK)

    def results(self) -> list[tuple[str, dict]]:
        from mpi4py import MPI

        done = []
        status = MPI.Status()
        while _probe(self._comm, MPI.ANY_SOURCE, RESULT, status):
            rank = status.Get_source()
            task_id, result = self._comm.recv(source=rank, tag=RESULT)
            del self._busy[rank]
            self._idle.append(rank)
            done.append((task_id, result))
        return done

    def stop(self) -> None:
        for rank in self._busy:
            self._comm.send(None, dest=rank, tag=STOP)

    def prepare(self, kinds) -> None:
        """Let the workers import what tasks of ``kinds`` need while this process warms up, and
        use this process's compile cache (``MBDS_CACHE_DIR``, set by ``run --campaign-cache``
        after the workers started)."""
        for rank in range(1, self._comm.Get_size()):
            self._comm.send((sorted(kinds), os.environ.get("MBDS_CACHE_DIR")), dest=rank, tag=PREPARE)

    def load_first(self, plan) -> None:
        """Let the workers load the compiled model of the plan's first variant before their
        first task (after the warm-up: the cache holds it)."""
        first = (plan.job.world_path(), plan.variants[0] if plan.variants else None)
        for rank in range(1, self._comm.Get_size()):
            self._comm.send(first, dest=rank, tag=LOAD)

    def close(self) -> None:
        """Release the workers."""
        release(self._comm)


_released: set[int] = set()
"""The communicators (by handle) whose workers this process has told to quit."""


def release(comm) -> None:
    """Tell the workers (ranks > 0) of ``comm`` to quit, once: a later call does nothing. Rank 0
    calls it whenever it ends, so that workers never wait for a scheduler that is gone (a wrong
    option, say, stops rank 0 before it schedules anything)."""
    if comm.py2f() in _released:
        return
    _released.add(comm.py2f())
    for rank in range(1, comm.Get_size()):
        comm.send(None, dest=rank, tag=QUIT)


def serve(comm, stopping) -> None:
    """A worker rank: run the tasks rank 0 sends, one at a time, until it says to quit. A run
    stops early when ``stopping()`` is true (a signal to this process) or rank 0 says so. Until
    rank 0's first message comes, the worker gets ready for runs of MBDS models
    (:func:`mbds.campaign.tasks.import_ahead`)."""
    from mpi4py import MPI

    status = MPI.Status()

    def told_to_stop() -> bool:
        return stopping() or comm.Iprobe(source=0, tag=STOP)

    import_ahead(lambda: _probe(comm, 0, MPI.ANY_TAG, status))
    while True:
        delay = POLL / 16  # the next task usually comes within a few ms of the last result
        while not _probe(comm, 0, MPI.ANY_TAG, status):
            time.sleep(delay)
            delay = min(2 * delay, POLL)
        message = comm.recv(source=0, tag=status.Get_tag())
        if status.Get_tag() == QUIT:
            return
        if status.Get_tag() == PREPARE:
            prepare_worker(*message)
        elif status.Get_tag() == LOAD:
            _load_first(*message)
        elif status.Get_tag() == TASK:
            comm.send((message.id, run_task(message, told_to_stop)), dest=0, tag=RESULT)


def prepare_worker(kinds, cache_dir: str | None) -> None:
    """A worker told the plan's task ``kinds`` and rank 0's compile cache: use that cache, and
    import what the tasks need."""
    if cache_dir:
        os.environ["MBDS_CACHE_DIR"] = cache_dir
    import_for(kinds)


def _load_first(world, variant) -> None:
    """Load the first variant's compiled model in this worker (a model that fails to load is
    left to the tasks, which report why in the ledger); then leave the objects made so far out
    of the garbage collector's sweeps.

    A worker holds about 114,000 objects once numba has loaded a model, and each full sweep of
    them takes 0.07-0.1 s; one came in each worker's first or second task (measured on the
    README campaign). The imports' and the model's objects live as long as the worker, so they
    are frozen (:func:`gc.freeze`); the tasks' own objects are collected as before."""
    from mbds.campaign.structures import load_first

    try:
        load_first(world, variant)
    except Exception:  # noqa: BLE001  (the same error fails the variant's prepare task, recorded)
        pass
    gc.freeze()  # without a sweep first: that would cost what freezing saves


def _probe(comm, source: int, tag: int, status) -> bool:
    """Whether a message from ``source`` with ``tag`` is waiting (its envelope in ``status``).
    Probes twice: MPICH shows a message that has arrived to the probe after the one that moved it
    in, so one probe per poll would see it a poll late."""
    return comm.Iprobe(source=source, tag=tag, status=status) or comm.Iprobe(source=source, tag=tag, status=status)
