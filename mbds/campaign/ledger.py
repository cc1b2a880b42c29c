"""The ledger: the state of a campaign's tasks, kept in ``ledger.json`` in the campaign folder.

Each task is ``pending`` (the default of a task not in the file), ``running``, ``done`` or
``failed``; ``blocked`` is not stored but derived from the plan (a task after a failed one,
:func:`mbds.campaign.plan.task_states`). An entry also holds what the executor reports:
``reason`` (failed), ``rank``, ``wall`` (s), ``output`` (path), ``compiled`` (functions numba
compiled during the task), ``start`` and ``end`` (UTC, ISO 8601, to the millisecond). Every change
is saved at once through a temporary file and a rename, so a hard kill leaves the previous or the
new ledger, never half of one.

API for executors (one process, the scheduling one, writes the ledger)::

    ledger = Ledger.load(plan.folder)      # resume: ``running`` entries of a dead run -> pending
    ledger.bind(plan)                      # the folder is this job's, with these variants
    ledger.mark(task.id, RUNNING, rank=3)
    ledger.mark(task.id, **run_task(task)) # done or failed, with its info

``Ledger.read`` reads it as it is (``running`` kept), for ``status`` while a campaign runs.
``ledger.record_submission(job_id, script)`` keeps the Slurm jobs of the campaign.
"""

from __future__ import annotations

import json
from datetime import datetime, timezone
from pathlib import Path
from typing import TYPE_CHECKING

from mbds.errors import ModelError
from mbds.io.text import write_atomic

if TYPE_CHECKING:
    from mbds.campaign.plan import Plan

PENDING, RUNNING, DONE, FAILED, BLOCKED = "pending", "running", "done", "failed", "blocked"
STORED_STATES = (PENDING, RUNNING, DONE, FAILED)
LEDGER_FILE = "ledger.json"
FORMAT = 1


class Ledger:
    """The tasks' entries (id -> dict), what the campaign was made from (``campaign``: job
    file and variant table) and the Slurm ``submissions``, saved in ``folder/ledger.json``."""

    def __init__(self, folder: str | Path, tasks: dict | None = None, campaign: dict | None = None,
                 submissions: list | None = None):
        self.folder = Path(folder)
        self.tasks: dict[str, dict] = tasks or {}
        self.campaign: dict = campaign or {}
        self.submissions: list[dict] = submissions or []

    @property
    def path(self) -> Path:
        return self.folder / LEDGER_FILE

    @classmethod
    def read(cls, folder: str | Path) -> Ledger:
        """The ledger as saved (an empty one when there is none yet)."""
        path = Path(folder) / LEDGER_FILE
        if not path.is_file():
            return cls(folder)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            if data.get("format") != FORMAT:
                raise ValueError(f"format {data.get('format')!r}, expected {FORMAT}")
            ledger = cls(folder, data["tasks"], data["campaign"], data["submissions"])
        except (ValueError, KeyError, TypeError, AttributeError) as exc:
            raise ModelError(f"not a readable campaign ledger ({exc})", path) from None
        for task_id, entry in ledger.tasks.items():
            if entry.get("state") not in STORED_STATES:
                raise ModelError(f"task {task_id} has state {entry.get('state')!r}", path)
        return ledger

    @classmethod
    def load(cls, folder: str | Path) -> Ledger:
        """The ledger, for a run that takes the campaign over: tasks left ``running`` by a run
        that ended (killed, out of time) are pending again; done and failed ones stay."""
        ledger = cls.read(folder)
        for entry in ledger.tasks.values():
            if entry["state"] == RUNNING:
                entry["state"] = PENDING
                entry["note"] = f"interrupted (started {entry.get('start', '?')})"
        return ledger

    def state(self, task_id: str) -> str:
        """The stored state of a task (``pending`` when it has no entry)."""
        return self.tasks.get(task_id, {}).get("state", PENDING)

    def entry(self, task_id: str) -> dict:
        """Everything stored about a task (empty when nothing is)."""
        return dict(self.tasks.get(task_id, {}))

    def mark(self, task_id: str, state: str, save: bool = True, **info) -> None:
        """Set the state of a task with its ``info`` (JSON values: ``reason``, ``rank``,
        ``wall`` in s, ``output``, ...) and save (unless told not to: a caller marking several
        tasks saves once after them). ``running`` stamps ``start`` and starts a new entry;
        ``done`` and ``failed`` stamp ``end``."""
        if state not in STORED_STATES:
            raise ValueError(f"unknown task state {state!r}")
        entry = {} if state in (PENDING, RUNNING) else self.tasks.get(task_id, {})
        entry.update(info, state=state)
        if state != PENDING:
            entry["start" if state == RUNNING else "end"] = utc_now()
        self.tasks[task_id] = entry
        if save:
            self.save()

    def bind(self, plan: Plan) -> None:
        """Check the ledger against the plan (:meth:`check`); a new ledger takes the plan's
        job file and variants, and is saved."""
        self.check(plan)
        if not self.campaign:
            self.campaign = _made_of(plan)
            self.save()

    def check(self, plan: Plan) -> None:
        """ModelError at the job file's line when this campaign folder was begun by another
        job file, or with other variants, replicates, mode or seed."""
        if not self.campaign:
            return
        made_of = _made_of(plan)
        if self.campaign.get("job") != made_of["job"]:
            raise ModelError(f"the campaign folder {self.folder} belongs to {self.campaign.get('job')}; give this job "
                             "its own with 'folder = ...' in [campaign]", plan.job.path, plan.line)
        changed = [key for key in made_of if self.campaign.get(key) != made_of[key]]
        if changed:
            raise ModelError(f"[campaign] differs from the campaign begun in {self.folder} ({', '.join(changed)}); "
                             "use another 'folder = ...' or remove that folder", plan.job.path, plan.line)

    def record_submission(self, job_id: str, script: str | Path, **info) -> None:
        """Keep a Slurm job submitted for this campaign (or requeued: ``requeue`` = its count),
        and save."""
        self.submissions.append({"job_id": job_id, "script": str(script), "time": utc_now(), **info})
        self.save()

    def save(self) -> None:
        """Write ``ledger.json`` atomically (temporary file and rename)."""
        self.folder.mkdir(parents=True, exist_ok=True)
        data = {"format": FORMAT, "campaign": self.campaign, "submissions": self.submissions, "tasks": self.tasks}
        write_atomic(self.path, json.dumps(data, indent=1, sort_keys=True) + "\n")


def _made_of(plan: Plan) -> dict:
    """What a campaign folder's tasks are made from: the job file and the variant table."""
    campaign = plan.campaign
    return {
        "job": str(plan.job.path.resolve()),
        "mode": campaign.mode if campaign else None,
        "replicates": campaign.replicates if campaign else 1,
        "seed": campaign.seed if campaign else 0,
        "variants": {v.id: v.values for v in plan.variants},
    }


def utc_now() -> str:
    """The time now, UTC, ISO 8601 to the millisecond."""
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")
