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
    """Wear campaigns across MPI ranks: run, status, collect, submit (Slurm)."""


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


EXIT_FAILED, EXIT_STOPPED = 1, 3


@app.command()
def collect(path: Path = JOB, debug: bool = DEBUG) -> None:
    """Merge the campaign's runs into one file, campaign.nc in the campaign folder (read it with
    mbds.open_campaign)."""
    from mbds.campaign.collect import collect as collect_runs
    from mbds.campaign.plan import expand

    with reported_errors(debug):
        print(f"wrote {collect_runs(expand(path))}")


@app.command()
def plot(
    path: Path = JOB,
    output: Path = typer.Option(None, "-o", "--output", help="Folder for the figures; default <campaign folder>/figures."),
    debug: bool = DEBUG,
) -> None:
    """Draw a collected campaign's figures: its summary and the worn shapes of every body."""
    from mbds.cli.plot import campaign_plot_command

    with reported_errors(debug):
        for written in campaign_plot_command(path, output):
            print(f"wrote {written}")


@app.command()
def run(
    path: Path = JOB,
    workers: int = typer.Option(1, "--workers", min=1, help="Processes running tasks at once without MPI."),
    debug: bool = DEBUG,
) -> None:
    """Run the campaign's tasks: on MPI ranks under mpiexec or srun (rank 0 schedules), else in
    --workers processes. Running it again resumes the campaign."""
    from mbds.campaign import executors

    comm = _mpi_world()
    if comm is not None and comm.Get_rank() > 0:
        from mbds.campaign.run import stop_signals

        with stop_signals() as stopping:
            executors.serve(comm, stopping)
        return
    ranks = executors.Ranks(comm) if comm is not None else None
    try:
        with reported_errors(debug):
            code = _schedule(path, workers, ranks)
    except typer.Exit as exc:
        code = exc.exit_code
    finally:
        if ranks is not None:
            ranks.close()
    if code and comm is not None:
        # The workers have quit. Finalizing here ends MPI cleanly: a non-zero exit would make
        # `python -m mpi4py` call MPI_Abort, which reports an abort for a mere stop or failure.
        from mpi4py import MPI

        MPI.Finalize()
    if code:
        raise typer.Exit(code)


def _schedule(path: Path, workers: int, ranks) -> int:
    """Rank 0 or the only process: check, warm up, run the loop; the exit code."""
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
    )

    from mbds.campaign import executors
    from mbds.campaign.ledger import Ledger
    from mbds.campaign.plan import done_count, expand
    from mbds.campaign.run import campaign_cache, run_campaign, stop_signals, warm_up

    plan = expand(path)
    Ledger.read(plan.folder).check(plan)
    campaign_cache(plan)
    console = Console(stderr=True)
    with stop_signals() as stopping:
        warm_up(plan)
        if ranks is not None:
            executor, workers = ranks, ranks.free()
        elif workers > 1:
            executor = executors.Pool(workers)
        else:
            executor = executors.Sequential(stopping)
        bar = Progress(TextColumn("tasks"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                       console=console, disable=not console.is_terminal)
        with bar:
            shown = bar.add_task("tasks", total=len(plan.tasks), completed=done_count(plan, Ledger.read(plan.folder)))
            try:
                outcome = run_campaign(plan, executor, stopping,
                                       lambda done, total: bar.update(shown, completed=done), workers)
            finally:
                if ranks is None:
                    executor.close()
    print(f"{len(outcome.done)} tasks done, {len(outcome.failed)} failed"
          + (f", {len(outcome.stopped)} stopped" if outcome.stopped else ""), file=sys.stderr)
    if outcome.interrupted:
        print(f"stopped; run it again to resume: mbds-campaign run {path}", file=sys.stderr)
        return EXIT_STOPPED
    return EXIT_FAILED if outcome.failed or done_count(plan, Ledger.read(plan.folder)) < len(plan.tasks) else 0


def _mpi_world():
    """MPI's world communicator when launched on more than one rank (``python -m mpi4py`` under
    mpiexec or srun), else None."""
    if "mpi4py.run" not in sys.modules:  # not launched with python -m mpi4py
        return None
    from mpi4py import MPI

    return MPI.COMM_WORLD if MPI.COMM_WORLD.Get_size() > 1 else None


if __name__ == "__main__":
    app()
