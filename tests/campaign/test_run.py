"""Running a campaign without MPI: a failing variant stops its own chain only, a hard kill or
SIGTERM loses at most the running tasks, collect and open_campaign give the documented tree."""

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import mbds
from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import RUN, expand
from mbds.errors import ModelError
from mbds.io.folder import read_model_files
from tests.campaign.models import campaign, two_mass

FAILING = "c'gravity = 9.81, 1e308\ncontact.mass1-mass2.friction = 0.1, 0.3\nworld.breakTime = 0.05\n"
SLOW = "c'gravity = 9.81, 5\ncontact.mass1-mass2.friction = 0.1, 0.3\nworld.breakTime = 0.5\n"


def run_command(job, *extra):
    """``mbds-campaign run`` in a process of its own, started."""
    return subprocess.Popen([sys.executable, "-m", "mbds.cli.campaign", "run", str(job), *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def done_outputs(plan):
    """Modification times (ns) of the history files of the runs the ledger has as done."""
    ledger = Ledger.read(plan.folder)
    return {t.id: (t.folder / "history.nc").stat().st_mtime_ns for t in plan.tasks
            if t.kind == RUN and ledger.state(t.id) == "done"}


def wait_for_done_runs(plan, process, count):
    """Wait until ``count`` runs are done (while ``process`` runs)."""
    while len(done_outputs(plan) if (plan.folder / "ledger.json").is_file() else {}) < count:
        assert process.poll() is None, process.communicate()
        time.sleep(0.05)


def test_a_failing_variant_stops_its_chain_only_and_the_campaign_collects(tmp_path):
    job = two_mass(tmp_path, FAILING, jobs="000-001")
    code, _, err = campaign("run", job)
    assert code == 1, err
    plan = expand(job)
    ledger = Ledger.read(plan.folder)
    states = {t.id: ledger.state(t.id) for t in plan.tasks}
    assert states["v02/000/run"] == "failed" and "not finite" in ledger.entry("v02/000/run")["reason"]
    assert states["v03/000/run"] == "failed"
    assert all(states[f"{v}/001/wear"] == "done" for v in ("v00", "v01"))
    code, out, _ = campaign("status", job)
    assert code == 0 and "failed v02/000/run" in out and "blocked" in out and " done " in out
    code, out, _ = campaign("collect", job)
    assert code == 0 and "campaign.nc" in out
    tree = mbds.open_campaign(plan.folder)
    summary = tree.ds
    assert dict(summary.sizes) == {"variant": 4, "version": 2, "body": 2, "point": 9}
    assert list(summary["c_gravity"].values) == [9.81, 9.81, 1e308, 1e308]
    assert summary["status"].sel(variant="v02").values.tolist() == ["failed", "pending"]
    assert np.isnan(summary["end_energy"].sel(variant="v03").values).all()
    assert (summary["steps"].sel(variant="v00").values > 0).all()
    assert json.loads(summary.attrs["variants"])["v01"]["contact.mass1-mass2.friction"] == "0.3"
    assert summary.attrs["job_text"] == job.read_text() and summary.attrs["workers"] == 1
    for variant in ("v00", "v01"):
        for version in (0, 1):
            folder = plan.folder / variant / f"{version:03d}"
            files = read_model_files(folder)
            points = np.concatenate([s.points[:-1] for s in files.shapes])  # closed: last = first
            at = summary.sel(variant=variant, version=version)
            np.testing.assert_array_equal(at["shape_x"].values, points[:, 0])
            np.testing.assert_array_equal(at["shape_y"].values, points[:, 1])
            node = tree[f"{variant}/{version:03d}"]
            np.testing.assert_array_equal(node["point_lost_work"].values, at["point_lost_work"].values)
            assert node.ds.sizes["time"] > 10
    assert "v02" not in tree.children and "v03" not in tree.children
    loaded = mbds.open_campaign(plan.folder / "campaign.nc", load=True)  # read whole, file closed
    assert loaded.identical(tree)
    tree.close()


def test_open_campaign_before_collect_says_what_to_do(tmp_path):
    job = two_mass(tmp_path, FAILING, jobs="000")
    with pytest.raises(ModelError, match="collect the campaign first"):
        mbds.open_campaign(expand(job).folder)


def test_a_hard_kill_loses_only_the_running_tasks(tmp_path):
    job = two_mass(tmp_path, SLOW, jobs="000-001")
    plan = expand(job)
    process = run_command(job)
    wait_for_done_runs(plan, process, 2)
    process.send_signal(signal.SIGKILL)
    process.wait()
    before = done_outputs(plan)
    assert 2 <= len(before) < 8
    code, _, err = campaign("run", job)
    assert code == 0, err
    ledger = Ledger.read(plan.folder)
    assert all(ledger.state(t.id) == "done" for t in plan.tasks)
    after = done_outputs(plan)
    assert len(after) == 8 and all(after[k] == v for k, v in before.items())


def test_sigterm_stops_cleanly_and_the_campaign_resumes(tmp_path):
    job = two_mass(tmp_path, SLOW, jobs="000-001")
    plan = expand(job)
    process = run_command(job, "--workers", "2")
    wait_for_done_runs(plan, process, 1)
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 3 and "resume" in err
    ledger = Ledger.read(plan.folder)
    states = [ledger.state(t.id) for t in plan.tasks]
    assert "running" not in states and "failed" not in states and "pending" in states
    before = done_outputs(plan)
    code, _, err = campaign("run", job)
    assert code == 0, err
    after = done_outputs(plan)
    assert len(after) == 8 and all(after[k] == v for k, v in before.items())
    assert os.path.isfile(plan.folder / "ledger.json")
