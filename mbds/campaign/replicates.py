"""Replicates whose results came out bit-identical.

Replicates of a version differ only in the seed of the lexicographic tolerance draws, which
matter only where the tolerance decides a pivot of the LCP solver. Where it never does, the
replicates' runs are bit-identical and the ensemble says nothing about the model's sensitivity:
the campaign reports such versions (``mbds-campaign status`` and the collected provenance). Run
tasks record a digest of their end state in the ledger (``digest``,
:func:`mbds.campaign.tasks.result_digest`).
"""

from __future__ import annotations

from collections import defaultdict

from mbds.campaign.ledger import DONE, Ledger
from mbds.campaign.plan import RUN, Plan
from mbds.io.folder import version_name


def identical_replicates(plan: Plan, ledger: Ledger) -> tuple[list[str], int]:
    """The versions (``v00/003``) whose replicate runs are all done with one digest, and how many
    versions have all their replicate runs done (none when the campaign has no replicates)."""
    if not plan.campaign or plan.campaign.replicates < 2:
        return [], 0
    groups: dict[str, list] = defaultdict(list)
    for task in plan.tasks:
        if task.kind == RUN:
            variant = task.variant.id if task.variant else plan.job.path.stem
            groups[f"{variant}/{version_name(task.version)}"].append(ledger.entry(task.id))
    complete = {k: runs for k, runs in groups.items() if all(e.get("state") == DONE and "digest" in e for e in runs)}
    same = sorted(k for k, runs in complete.items() if len({e["digest"] for e in runs}) == 1)
    return same, len(complete)
