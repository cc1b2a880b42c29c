"""The ledger: saved atomically at every change; a run killed hard leaves its running tasks
pending on reload, done ones done; one campaign folder, one job file and variant table."""

import json
import os
import subprocess
import sys

import pytest

from mbds.campaign.ledger import DONE, FAILED, LEDGER_FILE, PENDING, RUNNING, Ledger
from mbds.campaign.plan import expand
from mbds.errors import ModelError
from tests.campaign.models import ROOT, two_mass


def test_mark_saves_state_and_info_at_once(tmp_path):
    ledger = Ledger(tmp_path / "campaign")
    ledger.mark("v00/000/run", RUNNING, rank=2)
    ledger.mark("v00/000/run", DONE, wall=1.5, output="v00/000/history.nc")
    ledger.mark("v01/000/run", FAILED, reason="x.wld:3: bad")
    saved = Ledger.read(tmp_path / "campaign")
    done = saved.entry("v00/000/run")
    assert done["state"] == DONE and done["rank"] == 2 and done["wall"] == 1.5 and done["start"] <= done["end"]
    assert saved.entry("v01/000/run")["reason"] == "x.wld:3: bad"
    assert saved.state("v02/000/run") == PENDING
    with pytest.raises(ValueError, match="unknown task state"):
        ledger.mark("v00/000/run", "blocked")


def test_a_save_that_fails_leaves_the_previous_ledger_whole(tmp_path, monkeypatch):
    ledger = Ledger(tmp_path)
    ledger.mark("a", DONE)
    before = (tmp_path / LEDGER_FILE).read_text()

    def crash(*args):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", crash)
    with pytest.raises(ModelError, match="cannot write the file: disk full"):
        ledger.mark("b", DONE)
    assert (tmp_path / LEDGER_FILE).read_text() == before
    assert [p.name for p in tmp_path.iterdir()] == [LEDGER_FILE]


KILLED = """
import os, signal, sys
from mbds.campaign.ledger import Ledger
ledger = Ledger.load(sys.argv[1])
ledger.mark("a", "done")
ledger.mark("b", "failed", reason="bad input")
ledger.mark("c", "running", rank=1)
os.kill(os.getpid(), signal.SIGKILL)
"""


def test_running_tasks_of_a_killed_run_reload_as_pending_and_done_stays_done(tmp_path):
    killed = subprocess.run([sys.executable, "-c", KILLED, str(tmp_path)], cwd=ROOT, capture_output=True)
    assert killed.returncode == -9
    assert Ledger.read(tmp_path).state("c") == RUNNING  # as saved, for status
    ledger = Ledger.load(tmp_path)  # a new run takes the campaign over
    assert [ledger.state(t) for t in "abc"] == [DONE, FAILED, PENDING]
    assert ledger.entry("c")["note"].startswith("interrupted (started ")


def test_unreadable_ledger_is_reported_with_its_path(tmp_path):
    (tmp_path / LEDGER_FILE).write_text('{"format": 1, "tasks": {"a": {"state": "resting"}}, "campaign": {}, '
                                        '"submissions": []}')
    with pytest.raises(ModelError, match="task a has state 'resting'"):
        Ledger.read(tmp_path)
    (tmp_path / LEDGER_FILE).write_text("{")
    with pytest.raises(ModelError, match=f"{LEDGER_FILE}: not a readable campaign ledger"):
        Ledger.load(tmp_path)


def test_campaign_folder_belongs_to_one_job_file_and_variant_table(tmp_path):
    job = two_mass(tmp_path, "c'gravity = 9.81, 5\n")
    plan = expand(job)
    ledger = Ledger.load(plan.folder)
    ledger.bind(plan)
    saved = json.loads((plan.folder / LEDGER_FILE).read_text())["campaign"]
    assert saved["variants"] == {"v00": {"c'gravity": "9.81"}, "v01": {"c'gravity": "5"}}
    Ledger.load(plan.folder).bind(expand(job))  # the same: accepted
    job.write_text(job.read_text().replace("9.81, 5", "9.81, 3"))
    with pytest.raises(ModelError, match=r"differs from the campaign begun .* \(variants\)") as caught:
        Ledger.load(plan.folder).bind(expand(job))
    assert caught.value.file == str(job) and caught.value.line == 5
    other = job.with_name("other.job")
    other.write_text(job.read_text().replace("[main]", "[main]\nworldFile = 2mass.wld"))
    with pytest.raises(ModelError, match="belongs to .*2mass.job"):
        Ledger.load(plan.folder).check(expand(other))
