"""Replaying a campaign's measured task times on N workers: what its scheduling loop would take.

A campaign run once (on the workers this machine has) leaves in its ledger every task's wall
time. :func:`replay` hands the same tasks out to ``workers`` simulated workers with the
scheduler's own rules (``ready_tasks``, and ``by_remaining_work`` or plan order), each task taking
its measured wall time plus the measured per-task round trip, and returns when the last task
ends and how many worker-seconds went idle (mostly at the end, the tail, when fewer tasks are
ready than workers). Each worker's first run takes ``first_run_extra`` seconds more (loading
the compiled model, when the worker did not load it before its first task). The start-up (interpreter,
imports, warm-up) and shut-down are added from the measured run: they do not shrink with more
workers. Used by ``benchmarks/campaign.py --scaling``.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

from mbds.campaign.ledger import DONE, RUNNING, Ledger
from mbds.campaign.plan import RUN, Plan, ready_tasks
from mbds.campaign.priority import by_remaining_work


@dataclass
class Replay:
    """``loop``: first task start to last task end (s); ``busy``: the sum of the task times and
    round trips (s); ``idle``: worker-seconds without a task, ``workers * loop - busy``."""

    loop: float
    busy: float
    idle: float


def replay(plan: Plan, walls: dict[str, float], workers: int, round_trip: float, longest_first: bool = True,
           first_run_extra: float = 0.0) -> Replay:
    """The scheduling loop of ``plan`` on ``workers`` workers, task ``k`` taking ``walls[k]`` +
    ``round_trip`` seconds, and ``first_run_extra`` more for each worker's first run."""
    ledger = Ledger(plan.folder)
    clock, running, busy = 0.0, [], 0.0
    free, has_run = list(range(workers)), set()
    while True:
        ready = ready_tasks(plan, ledger)
        if longest_first:
            ready = by_remaining_work(plan, ledger, ready)
        for task in ready[: len(free)]:
            worker = free.pop()
            ledger.mark(task.id, RUNNING, save=False)
            cost = walls[task.id] + round_trip
            if task.kind == RUN and worker not in has_run:
                has_run.add(worker)
                cost += first_run_extra
            busy += cost
            heapq.heappush(running, (clock + cost, task.id, worker))
        if not running:
            break
        clock, task_id, worker = heapq.heappop(running)
        free.append(worker)
        ledger.mark(task_id, DONE, save=False, wall=walls[task_id])
    return Replay(loop=clock, busy=busy, idle=workers * clock - busy)
