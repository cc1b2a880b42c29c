"""Slurm requeue: the batch script asks for it (or not), and a campaign stopped by SIGUSR1 (Slurm's
warning before the time limit) requeues its job through the `scontrol` found on PATH (a fake
here), records it in the ledger, and stops requeueing at the limit."""

import os
import signal
import subprocess
import sys

from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import expand
from tests.campaign.models import campaign, two_mass
from tests.campaign.test_run import SLOW, wait_for_done_runs


def test_the_script_requeues_unless_told_not_to(tmp_path):
    job = two_mass(tmp_path, None)
    code, out, err = campaign("submit", job, "--dry-run", "--max-requeues", "2")
    assert code == 0, err
    assert "#SBATCH --requeue\n" in out and "export MBDS_MAX_REQUEUES=2\n" in out
    code, out, err = campaign("submit", job, "--dry-run", "--no-requeue")
    assert code == 0, err
    assert "#SBATCH --no-requeue\n" in out and "MBDS_MAX_REQUEUES=" not in out


def fake_scontrol(folder):
    """An scontrol that records its arguments in ``args.txt``."""
    folder.mkdir()
    script = folder / "scontrol"
    script.write_text(f'#!/bin/sh\necho "$@" >> "{folder}/args.txt"\n')
    script.chmod(0o755)
    return folder


def stopped_by_usr1(tmp_path, restarts: int):
    """Run a campaign as Slurm job 99 (requeued ``restarts`` times, at most 2), stop it with
    SIGUSR1 after its first run; the exit code, its error output, the fake scontrol's folder
    and the plan."""
    job = two_mass(tmp_path, SLOW, jobs="000-001")
    plan = expand(job)
    bin_folder = fake_scontrol(tmp_path / "bin")
    env = {**os.environ, "PATH": f"{bin_folder}{os.pathsep}{os.environ['PATH']}", "SLURM_JOB_ID": "99",
           "MBDS_MAX_REQUEUES": "2", "SLURM_RESTART_COUNT": str(restarts)}
    process = subprocess.Popen([sys.executable, "-m", "mbds.cli.campaign", "run", str(job)], env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for_done_runs(plan, process, 1)
    process.send_signal(signal.SIGUSR1)
    _, err = process.communicate(timeout=120)
    return process.returncode, err, bin_folder, plan


def test_a_campaign_stopped_by_usr1_requeues_its_job_and_records_it(tmp_path):
    code, err, bin_folder, plan = stopped_by_usr1(tmp_path, restarts=0)
    assert code == 3 and "requeued Slurm job 99 (1 of at most 2 requeues)" in err
    assert (bin_folder / "args.txt").read_text().split() == ["requeue", "99"]
    (record,) = Ledger.read(plan.folder).submissions
    assert record["job_id"] == "99" and record["requeue"] == 1
    code, out, err = campaign("status", plan.job.path)
    assert code == 0 and "Slurm job 99 requeued (requeue 1)" in out


def test_no_requeue_beyond_the_limit(tmp_path):
    code, err, bin_folder, plan = stopped_by_usr1(tmp_path, restarts=2)
    assert code == 3 and "not requeued: Slurm job 99 was requeued 2 times" in err
    assert not (bin_folder / "args.txt").exists()
    assert Ledger.read(plan.folder).submissions == []
