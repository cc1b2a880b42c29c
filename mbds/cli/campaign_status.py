"""``mbds-campaign status``: a table of chains and versions with their states, and progress."""

from __future__ import annotations

from collections import Counter, defaultdict

from rich import box
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from mbds.campaign.ledger import BLOCKED, DONE, FAILED, PENDING, RUNNING, Ledger
from mbds.campaign.plan import Plan, task_states
from mbds.campaign.replicates import identical_replicates
from mbds.io.folder import version_name

STYLES = {DONE: "green", RUNNING: "cyan", FAILED: "bold red", BLOCKED: "yellow", PENDING: "dim"}


ROWS_SHOWN = 100
"""The most variants, chains and failures listed one per line; the summary counts them all."""


def print_status(plan: Plan, ledger: Ledger, console: Console) -> None:
    """Variants, one row per chain with the state of each version (its tasks taken together:
    ``k/n`` when k of its n tasks are done), the failures and a summary; long lists are cut at
    :data:`ROWS_SHOWN` lines with a count of the rest."""
    states = task_states(plan, ledger)
    table_box = box.SIMPLE if console.is_terminal else None
    if plan.variants and plan.variants[0].parameters:
        variants = Table(title="variants", box=table_box, title_justify="left")
        variants.add_column("variant")
        for key in plan.variants[0].values:
            variants.add_column(escape(key))
        for v in plan.variants[:ROWS_SHOWN]:
            variants.add_row(v.id, *map(escape, v.values.values()))
        console.print(variants)
        _more(console, len(plan.variants), "variants")
    versions = plan.job.versions
    console.print(f"campaign of {escape(plan.job.path.name)} in {escape(str(plan.folder))}", highlight=False)
    by_cell: dict[tuple[str, int], list[str]] = defaultdict(list)
    for task in plan.tasks:
        by_cell[task.chain, task.version].append(states[task.id])
    chains = Table(box=table_box)
    chains.add_column("chain")
    for number in versions:
        chains.add_column(version_name(number))
    for chain in plan.chains[:ROWS_SHOWN]:
        chains.add_row(chain.id, *(_version_cell(by_cell[chain.id, n]) for n in versions))
    console.print(chains)
    _more(console, len(plan.chains), "chains")
    failed = [task for task in plan.tasks if states[task.id] == FAILED]
    for task in failed[:ROWS_SHOWN]:
        reason = ledger.entry(task.id).get("reason", "")
        console.print(f"[red]failed[/red] {task.id}: {escape(reason)}", highlight=False)
    _more(console, len(failed), "failed tasks")
    counts = Counter(states.values())
    parts = [f"{counts[s]} {s}" for s in (RUNNING, FAILED, BLOCKED, PENDING) if counts[s]]
    console.print(f"{counts[DONE]} of {len(states)} tasks done" + "".join(f", {p}" for p in parts), highlight=False)
    same, complete = identical_replicates(plan, ledger)
    if complete:
        console.print(f"replicates bit-identical in {len(same)} of {complete} versions run in full"
                      + (f" ({', '.join(same[:8])}{', ...' if len(same) > 8 else ''}): the lexicographic "
                         "randomisation decided no pivot there" if same else ""), highlight=False)
    for job in ledger.submissions:
        what = f"requeued (requeue {job['requeue']})" if "requeue" in job else "submitted"
        console.print(f"Slurm job {job['job_id']} {what} {job['time']}", highlight=False)


def _more(console: Console, count: int, what: str) -> None:
    """A line saying how many of ``count`` items were left out of a list cut at ROWS_SHOWN."""
    if count > ROWS_SHOWN:
        console.print(f"... and {count - ROWS_SHOWN} more {what} (first {ROWS_SHOWN} shown)", highlight=False)


def _version_cell(states: list[str]) -> str:
    """The state of a version from those of its tasks."""
    for state in (FAILED, RUNNING, BLOCKED):
        if state in states:
            return f"[{STYLES[state]}]{state}[/]"
    done = states.count(DONE)
    if done == len(states):
        return f"[{STYLES[DONE]}]{DONE}[/]"
    return f"{done}/{len(states)}" if done else f"[{STYLES[PENDING]}]{PENDING}[/]"
