"""How fast ``mbds-campaign status`` answers on a large plan: a copy of campaigns/2mass with 100
values of c'gravity and 143 replicates (14,300 chains of 7 tasks: 100,100 tasks). Expanding the
plan, reading the ledger and printing the status table are timed in this process, CPU time, best
of 3. Run from the repository root: ``.venv/bin/python benchmarks/status.py``.
"""

from __future__ import annotations

import io
import shutil
import tempfile
import time
from pathlib import Path

from rich.console import Console

from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import expand
from mbds.cli.campaign_status import print_status

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "2mass"
        shutil.copytree(ROOT / "campaigns" / "2mass", folder)
        gravity = ", ".join(f"{9 + k / 100:.2f}" for k in range(100))
        job = folder / "2mass.job"
        job.write_text(f"[main]\njobs = 000-002\ncreateNextVersionAtEnd = 1\n"
                       f"[campaign]\nc'gravity = {gravity}\nreplicates = 143\n")
        best = float("inf")
        for _ in range(3):
            start = time.process_time()
            plan = expand(job)
            print_status(plan, Ledger.read(plan.folder), Console(file=io.StringIO(), width=160))
            best = min(best, time.process_time() - start)
        print(f"status of a {len(plan.tasks):,}-task plan: {best:.2f} s of CPU (goal: under 2 s)")


if __name__ == "__main__":
    main()
