"""The ``mbds-campaign`` command: wear campaigns over many ranks.

``python -m mbds.cli.campaign`` (or ``python -m mpi4py -m mbds.cli.campaign``) is the console
script: run as the main module, this file hands over to :mod:`mbds.cli.campaign_entry` before
it imports the command-line parser, so that a worker rank starts as light as under
``mbds-campaign`` (the entry imports this module again, by its name, where the parser is needed,
and never returns)."""

from __future__ import annotations

if __name__ == "__main__":
    from mbds.cli.campaign_entry import main as console_script

    console_script()

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
    nodes: str = typer.Option("", "--nodes", help="Slurm nodes: a count or min-max; default: Slurm's choice."),
    mem_per_cpu: str = typer.Option("", "--mem-per-cpu", help="Memory per rank, e.g. 2G; default: the partition's."),
    mpi: str = typer.Option("", "--mpi", help="srun's --mpi plugin (pmix, pmi2, ...); default: the cluster's."),
    preamble: Path = typer.Option(None, "--preamble", help="A file of shell lines run before the campaign (module load ...)."),
    requeue: bool = typer.Option(True, "--requeue/--no-requeue",
                                 help="Requeue the job when its time limit stops the campaign with tasks left."),
    max_requeues: int = typer.Option(5, "--max-requeues", min=0, help="Requeue at most this many times."),
    force: bool = typer.Option(False, "--force", help="Submit even when every task of the campaign is done."),
    dry_run: bool = typer.Option(False, "--dry-run", help="Print the batch script; submit nothing."),
    debug: bool = DEBUG,
) -> None:
    """Write the campaign's Slurm batch script (mbds/campaign/slurm.sbatch) and submit it with sbatch."""
    from mbds.campaign.ledger import Ledger
    from mbds.campaign.plan import done_count, expand
    from mbds.campaign.slurm import SlurmOptions, render_script
    from mbds.campaign.slurm import submit as submit_script

    if ntasks == 1:
        raise typer.BadParameter("a campaign needs 2 ranks or more (one schedules)", param_hint="--ntasks")
    with reported_errors(debug):
        plan = expand(path)
        options = SlurmOptions(ntasks, time, account, partition, job_name, signal_seconds, nodes, mem_per_cpu, mpi,
                               preamble, max_requeues if requeue else None)
        script = render_script(plan, options)
        if dry_run:
            sys.stdout.write(script)
            return
        ledger = Ledger.read(plan.folder)
        ledger.check(plan)
        if not force and done_count(plan, ledger) == len(plan.tasks):
            print("warning: every task of the campaign is done; nothing submitted (--force submits anyway)",
                  file=sys.stderr)
            return
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
PLAN_NOTICE = 300
"""A plan of more tasks says its size before it runs."""


@app.command()
def collect(path: Path = JOB, debug: bool = DEBUG) -> None:
    """Merge the campaign's runs into one file, campaign.nc in the campaign folder (read it with
    mbds.open_campaign)."""
    from mbds.campaign.collect import collect as collect_runs
    from mbds.campaign.plan import expand
    from mbds.io.lock import folder_lock

    with reported_errors(debug):
        plan = expand(path)
        with folder_lock(plan.folder, "mbds-campaign collect"):
            print(f"wrote {collect_runs(plan)}")


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
    campaign_cache: bool = typer.Option(False, "--campaign-cache",
                                        help="Keep compiled models in <campaign>/.cache, not the user's shared cache."),
    debug: bool = DEBUG,
) -> None:
    """Run the campaign's tasks: on MPI ranks under mpiexec or srun (rank 0 schedules), else in
    --workers processes. Running it again resumes the campaign."""
    from mbds.campaign import executors
    from mbds.cli.mpi_world import abort_on_uncaught, mpi_world, serve_worker

    comm = mpi_world()
    abort_on_uncaught(comm)
    if comm is not None and comm.Get_rank() > 0:
        serve_worker(comm)
        return
    ranks = executors.Ranks(comm) if comm is not None else None
    code = None
    try:
        with reported_errors(debug):
            code = _schedule(path, workers, ranks, campaign_cache)
    except typer.Exit as exc:
        code = exc.exit_code
    finally:
        if ranks is not None:
            ranks.close()
    if code:
        raise typer.Exit(code)


def _schedule(path: Path, workers: int, ranks, private_cache: bool) -> int:
    """Rank 0 or the only process: check, lock the campaign folder, warm up, run the loop; the
    exit code."""
    from mbds.campaign.ledger import Ledger
    from mbds.campaign.plan import done_count, expand
    from mbds.campaign.requeue import requeue
    from mbds.io.lock import folder_lock

    plan = expand(path)
    Ledger.read(plan.folder).check(plan)
    if len(plan.tasks) > PLAN_NOTICE:
        print(f"plan: {len(plan.tasks):,} tasks in {len(plan.chains):,} chains of {max(len(plan.variants), 1):,} "
              "variant(s)", file=sys.stderr)
    plan.folder.mkdir(parents=True, exist_ok=True)
    with folder_lock(plan.folder, "mbds-campaign run"):
        outcome = _run_locked(plan, workers, ranks, private_cache)
    print(f"{len(outcome.done)} tasks done, {len(outcome.failed)} failed"
          + (f", {len(outcome.stopped)} stopped" if outcome.stopped else ""), file=sys.stderr)
    if outcome.interrupted:
        print(f"stopped; run it again to resume: mbds-campaign run {path}", file=sys.stderr)
        if done_count(plan, Ledger.read(plan.folder)) < len(plan.tasks):
            said = requeue(Ledger.read(plan.folder))
            if said:
                print(said, file=sys.stderr)
        return EXIT_STOPPED
    return EXIT_FAILED if outcome.failed or done_count(plan, Ledger.read(plan.folder)) < len(plan.tasks) else 0


def _run_locked(plan, workers: int, ranks, private_cache: bool):
    """Warm up and run the scheduling loop of ``plan`` (its folder locked); the outcome."""
    from mbds.campaign import executors
    from mbds.campaign.ledger import Ledger
    from mbds.campaign.plan import done_count
    from mbds.campaign.run import campaign_cache, run_campaign, stop_signals, warm_up_first
    from mbds.cli.campaign_progress import CampaignProgress

    campaign_cache(plan, private_cache)
    report = CampaignProgress(len(plan.tasks), done_count(plan, Ledger.read(plan.folder)))
    if ranks is not None:
        ranks.prepare({task.kind for task in plan.tasks})
    with stop_signals() as stopping:
        report.phase("warm-up: compiling the model, or loading it from the cache")
        structures = warm_up_first(plan)
        if ranks is not None and structures is not None:
            ranks.load_first(plan)
        report.phase_done(f"warm-up: {structures.count if structures else 1} distinct model(s) ready"
                          + (", the other variants' checked as their chains are prepared"
                             if structures and len(plan.variants) > 1 else ""))
        if ranks is not None:
            executor, workers = ranks, ranks.free()
        elif workers > 1:
            executor = executors.Pool(workers)
        else:
            executor = executors.Sequential(stopping)
        report.phase(f"running {report.total - report.done} of {report.total} tasks on {workers} worker(s)")

        def progress(task_id, result, done, running):
            if task_id is None:
                report.started(running)
            else:
                report.finished(task_id, result, done, running)

        with report:
            try:
                outcome = run_campaign(plan, executor, stopping, progress, workers, structures)
            finally:
                if ranks is None:
                    executor.close()
    return outcome

