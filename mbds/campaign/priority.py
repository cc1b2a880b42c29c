"""The order in which a campaign's ready tasks start: the chain with the most work left first.

Handing tasks out in plan order runs chains in waves, and the last wave can leave most workers
idle while a few chains finish. Starting, among the ready tasks, the one whose chain has the
most work left (longest-processing-time first) keeps every worker busy until the end, so the
tail is at most about one task long. A chain's work left is the sum, over its tasks not done yet,
of the mean wall time of the done tasks of the same kind (run, wear, prepare); before any task of
a kind is done, :data:`FIRST_GUESS` stands in. The order changes when tasks run, never what they
compute: results do not depend on it.
"""

from __future__ import annotations

from collections import defaultdict

from mbds.campaign.ledger import DONE, PENDING, RUNNING, Ledger
from mbds.campaign.plan import PREPARE, RUN, WEAR, Plan, Task, task_states

FIRST_GUESS = {RUN: 1.0, WEAR: 0.1, PREPARE: 0.01}
"""Relative cost of a task kind before one of that kind has finished (s)."""


def mean_walls(plan: Plan, ledger: Ledger) -> dict[str, float]:
    """Mean wall time (s) of the done tasks of each kind, :data:`FIRST_GUESS` for a kind with
    none done yet."""
    total: dict[str, float] = defaultdict(float)
    count: dict[str, int] = defaultdict(int)
    for task in plan.tasks:
        entry = ledger.tasks.get(task.id, {})
        if entry.get("state") == DONE and "wall" in entry:
            total[task.kind] += float(entry["wall"])
            count[task.kind] += 1
    kinds = {task.kind for task in plan.tasks}
    return {k: total[k] / count[k] if count[k] else FIRST_GUESS.get(k, 1.0) for k in kinds}


def by_remaining_work(plan: Plan, ledger: Ledger, ready: list[Task]) -> list[Task]:
    """``ready`` reordered: tasks of the chains with the most work left first, plan order
    among equals."""
    states = task_states(plan, ledger)
    means = mean_walls(plan, ledger)
    left: dict[str, float] = defaultdict(float)
    for task in plan.tasks:
        if states[task.id] in (PENDING, RUNNING):
            left[task.chain] += means[task.kind]
    position = {task.id: k for k, task in enumerate(plan.tasks)}
    return sorted(ready, key=lambda task: (-left[task.chain], position[task.id]))
