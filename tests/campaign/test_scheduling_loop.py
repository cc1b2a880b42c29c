"""The scheduling loop writes the ledger at most every SAVE_EVERY seconds (set to 1 s here) while
tasks run on other processes (issue 12): writing it takes time proportional to the plan, and a result that
comes back meanwhile waits for it. Every change reaches the file when the loop ends."""

import json
import time

from mbds.campaign import run as campaign_run
from mbds.campaign.executors import Sequential
from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import expand
from mbds.campaign.run import run_campaign, warm_up_first

SAVE_EVERY = 1.0
from tests.campaign.models import two_mass

QUICK = "c'gravity = 9.81, 9.7, 9.6, 9.5\nworld.breakTime = 0.002\n"


class Elsewhere(Sequential):
    """Performs each task at once, as :class:`Sequential` does, but as a remote executor: its
    result comes back at the loop's next look, and the loop does not write the ledger before
    handing a task out."""

    inline = False


def test_the_ledger_is_written_at_most_every_save_interval_and_complete_at_the_end(tmp_path, monkeypatch):
    plan = expand(two_mass(tmp_path, QUICK, jobs="000-001"))
    writes = []
    save = Ledger.save

    def counted(ledger):
        writes.append(time.monotonic())
        save(ledger)

    monkeypatch.setattr(Ledger, "save", counted)
    monkeypatch.setattr(campaign_run, "SAVE_EVERY", SAVE_EVERY)
    structures = warm_up_first(plan)
    begun = time.monotonic()
    outcome = run_campaign(plan, Elsewhere(lambda: False), lambda: False, structures=structures)
    elapsed = time.monotonic() - begun
    assert len(outcome.done) == len(plan.tasks) == 20 and not outcome.failed
    # each result and each hand-out is a change: 40 writes if each were written at once
    assert len(writes) <= 2 + elapsed / SAVE_EVERY + 1, (len(writes), elapsed)
    # the first write is the ledger's binding to the plan, the last the loop's end
    gaps = [b - a for a, b in zip(writes[1:-1], writes[2:-1])]
    assert all(gap >= SAVE_EVERY * 0.999 for gap in gaps), gaps
    ledger = json.loads((plan.folder / "ledger.json").read_text())
    assert {entry["state"] for entry in ledger["tasks"].values()} == {"done"}
    assert len(ledger["campaign"]["runs"]) == 1


class OnDisk(Sequential):
    """:class:`Sequential` that reads ``ledger.json`` before each task starts and keeps the
    states it finds there of the tasks whose results have come back."""

    def __init__(self, stopping, folder):
        super().__init__(stopping)
        self.ledger = folder / "ledger.json"
        self.returned: list[str] = []
        self.seen: list[str] = []

    def submit(self, task):
        tasks = json.loads(self.ledger.read_text())["tasks"]
        self.seen += [tasks[task_id]["state"] for task_id in self.returned]
        super().submit(task)

    def results(self):
        done = super().results()
        self.returned += [task_id for task_id, _ in done]
        return done


def test_an_inline_executor_writes_each_change(tmp_path, monkeypatch):
    """One task at a time in the scheduling process: ``status`` from another terminal must show
    each result as it comes: the ledger is written as each task starts (with every result before
    it), whatever the loop's interval."""
    plan = expand(two_mass(tmp_path, QUICK, jobs="000"))
    monkeypatch.setattr(campaign_run, "SAVE_EVERY", 3600.0)
    executor = OnDisk(lambda: False, plan.folder)
    outcome = run_campaign(plan, executor, lambda: False, structures=warm_up_first(plan))
    assert len(outcome.done) == len(plan.tasks) == 12
    assert len(executor.seen) >= len(plan.tasks)  # (several tasks may start between two looks)
    assert set(executor.seen) == {"done"}
