"""``mbds check`` of DAP_BC inputs: a job file naming a DAP_BC folder (its ``[campaign]``
checked as ``mbds-campaign`` checks it), or a DAP_BC model folder itself."""

from __future__ import annotations

from pathlib import Path

from rich.console import Console
from rich.markup import escape


def check_dapbc(path: Path, compile: bool, console: Console) -> None:
    """Read (and with ``compile``, compile) the DAP_BC model of ``path`` and, for a job file,
    expand its campaign; ModelError (``file:line``) on bad input."""
    from mbds.campaign.plan import expand
    from mbds.io.dapbc import read_dapbc_folder
    from mbds.model.dapbc import build_system

    plan = expand(path) if path.suffix.lower() == ".job" else None
    folder = plan.job.model_folder() if plan else path
    model = read_dapbc_folder(folder)
    if compile:
        build_system(model)
    console.print(f"[green]ok[/green] DAP_BC model {escape(str(folder))}: {model.nB} bodies, {len(model.joints)} "
                  f"joints, {len(model.forces)} forces, {len(model.functs)} functions", highlight=False)
    if plan:
        console.print(f"[green]ok[/green] {escape(str(path))}: {len(plan.tasks)} tasks in {len(plan.chains)} "
                      "chain(s)", highlight=False)
