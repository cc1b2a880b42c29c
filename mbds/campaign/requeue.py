"""Slurm requeue: a campaign that its time limit stopped puts its own job back in the queue.

The batch script (``mbds/campaign/slurm.sbatch``, ``submit --requeue``) exports
``MBDS_MAX_REQUEUES``. When Slurm's ``USR1`` stops the campaign before its time limit, the
ledger is saved; then, while tasks remain and the job has been requeued fewer times than that
limit (Slurm counts them in ``SLURM_RESTART_COUNT``), rank 0 records the requeue in the ledger
and runs ``scontrol requeue <job id>``. Slurm then ends this run of the job and starts it again
when resources allow; the new run resumes from the ledger.
"""

from __future__ import annotations

import os
import shutil
import subprocess

from mbds.campaign.ledger import Ledger

MAX_REQUEUES = "MBDS_MAX_REQUEUES"
"""The environment variable through which the batch script gives the limit."""


def requeue(ledger: Ledger, environ=os.environ) -> str | None:
    """Requeue the Slurm job this campaign runs in, if its script asked for requeues and the
    limit is not reached; what was done, as a sentence (None outside such a job)."""
    limit, job_id = environ.get(MAX_REQUEUES, ""), environ.get("SLURM_JOB_ID", "")
    if not limit.isdigit() or not job_id.isdigit():
        return None
    count = int(environ.get("SLURM_RESTART_COUNT", "0") or 0)
    if count >= int(limit):
        return f"not requeued: Slurm job {job_id} was requeued {count} times, the limit (--max-requeues)"
    scontrol = shutil.which("scontrol")
    if scontrol is None:
        return "not requeued: scontrol not found on PATH"
    ledger.record_submission(job_id, "scontrol requeue", requeue=count + 1)
    done = subprocess.run([scontrol, "requeue", job_id], capture_output=True, text=True)
    if done.returncode != 0:
        said = (done.stderr or done.stdout).strip() or f"exit code {done.returncode}"
        return f"scontrol did not requeue Slurm job {job_id}: {said}"
    return f"requeued Slurm job {job_id} ({count + 1} of at most {limit} requeues)"
