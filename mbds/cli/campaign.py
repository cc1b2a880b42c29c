"""The ``mbds-campaign`` command: wear campaigns over many ranks."""

from __future__ import annotations

import sys
from pathlib import Path

import typer
from rich.console import Console

from mbds.cli.errors import reported_errors

app = typer.Typer(
    help=(
        "Run-in wear campaigns: expand a job file into chains of versions and parameter variants, "
        "run them across MPI ranks, and collect the results into one dataset."
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

JOB = typer.Argument(..., help="A job file, with or without a [campaign] section.")
DEBUG = typer.Option(False, "--debug", help="Show a traceback on errors.")


@app.callback()
def main() -> None:
    """Wear campaigns across MPI ranks: submit (Slurm), status."""


def _check_time(value: str) -> str:
    from mbds.campaign.slurm import TIME_FORMAT

    if value and not TIME_FORMAT.fullmatch(value):
        raise typer.BadParameter("Slurm's format: minutes, HH:MM:SS or D-HH:MM:SS")
    return value


@app.command()
def submit(
    path: Path = JOB,
    ntasks: int = typer.Option(0, "--ntasks", min=0, help="MPI ranks; default: 1 scheduler + 1 per task that can run at once."),
    time: str = typer.Option("", "--time", callback=_check_time, help="Slurm time limit (HH:MM:SS); default: the partition's."),
    account: str = typer.Option("", "--account", help="Slurm account to charge."),
    partition: str = typer.Option("", "--partition", help="Slurm partition."),
    job_name: str = typer.Option("", "--job-name", help="Slurm job name; default: mbds-<job file name>."),
    signal_seconds: int = typer.Option(300, "--signal-seconds", min=1, max=65535,
                                       help="Tell the campaign to stop this many s before the time limit."),
    dry_run: bool = typer.Option(False, "--dry-run", help="Print the batch script; submit nothing."),
    debug: bool = DEBUG,
) -> None:
    """Write the campaign's Slurm batch script (workflows/slurm.sbatch) and submit it with sbatch."""
    from mbds.campaign.ledger import Ledger
    from mbds.campaign.plan import expand
    from mbds.campaign.slurm import SlurmOptions, render_script
    from mbds.campaign.slurm import submit as submit_script

    if ntasks == 1:
        raise typer.BadParameter("a campaign needs 2 ranks or more (one schedules)", param_hint="--ntasks")
    with reported_errors(debug):
        plan = expand(path)
        script = render_script(plan, SlurmOptions(ntasks, time, account, partition, job_name, signal_seconds))
        if dry_run:
            sys.stdout.write(script)
            return
        ledger = Ledger.read(plan.folder)
        ledger.bind(plan)
        job_id = submit_script(plan, script, ledger)
        print(f"submitted Slurm job {job_id}; follow it with: mbds-campaign status {path}")


@app.command()
def status(path: Path = JOB, debug: bool = DEBUG) -> None:
    """Print the state of every chain and version of the campaign, and its progress."""
    from mbds.campaign.ledger import Ledger
    from mbds.campaign.plan import expand
    from mbds.cli.campaign_status import print_status

    console = Console() if sys.stdout.isatty() else Console(width=160, no_color=True, highlight=False)
    with reported_errors(debug):
        plan = expand(path)
        ledger = Ledger.read(plan.folder)
        ledger.check(plan)
        print_status(plan, ledger, console)


if __name__ == "__main__":
    app()
