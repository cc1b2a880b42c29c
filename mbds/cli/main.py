"""The ``mbds`` command."""

from __future__ import annotations

import sys
from pathlib import Path

import typer
from rich.console import Console

from mbds._version import version as mbds_version
from mbds.cli.errors import reported_errors

app = typer.Typer(
    help="Planar rigid multibody dynamics with unilateral contacts, impacts, friction and run-in wear.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _version(value: bool) -> None:
    if value:
        print(f"mbds {mbds_version()}")
        raise typer.Exit()


@app.callback()
def main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version."),
) -> None:
    """mbds: simulate MBDS models and run wear campaigns."""


@app.command()
def check(
    paths: list[Path] = typer.Argument(..., help="Model folders (MBDS or DAP_BC), .wld world files or .job job files."),
    compile: bool = typer.Option(True, "--compile/--no-compile", help="Also compile the model's functions."),
    version: int = typer.Option(0, "--model-version", help="Version whose [body:k] watch sections apply."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """Validate models and print a summary of each; a model folder's job files (and their
    [campaign] sections) are checked too; exit code 2 on bad input."""
    from mbds.campaign.plan import expand
    from mbds.cli.dapbc_check import check_dapbc
    from mbds.cli.summary import print_summary
    from mbds.io.dapbc import is_dapbc_folder
    from mbds.io.dapbc_job import is_dapbc_job
    from mbds.model.load import load_model

    console = _console()
    with reported_errors(debug):
        for path in paths:
            if is_dapbc_folder(path) or (path.suffix.lower() == ".job" and is_dapbc_job(path)):
                check_dapbc(path, compile, console)
                continue
            is_job = path.suffix.lower() == ".job"
            model = load_model(expand(path).job.world_path() if is_job else path, version=version, compile=compile)
            print_summary(model, console)
            console.print(f"[green]ok[/green] {model.world_path}")
            for job in [path] if is_job else sorted(path.glob("*.job")) if path.is_dir() else []:
                plan = expand(job)
                console.print(f"[green]ok[/green] {job}: {len(plan.tasks)} tasks in {len(plan.chains)} chain(s)",
                              highlight=False)


@app.command()
def run(
    path: Path = typer.Argument(..., help="A version folder (campaigns/2mass/000), a model folder, or a DAP_BC model folder (with inBodies.m)."),
    break_time: float = typer.Option(None, "--break-time", help="Length of the run (s); default: breakTime."),
    start_from: int = typer.Option(None, "--from", help="Start where this version's run ended (e.g. 000)."),
    seed: int = typer.Option(0, "--seed", help="Seed of the randomized lexicographic tolerances."),
    force: bool = typer.Option(False, "--force", help="Replace a complete run, or version 000's copies of model files that changed."),
    final_time: float = typer.Option(None, "--final-time", help="DAP_BC: final time T (s); asked for on a terminal."),
    report_step: float = typer.Option(None, "--report-step", help="DAP_BC: reporting time step DT (s); asked for on a terminal."),
    correct_ic: bool = typer.Option(None, "--correct-ic/--no-correct-ic", help="DAP_BC: correct the initial conditions; asked for on a terminal."),
    analysis: str = typer.Option(None, "--analysis", help="DAP_BC: forward (default), kinematic, inverse or static."),
    method: str = typer.Option("dopri5", "--method", help="DAP_BC forward dynamics: dopri5 (as ode45) or stiff."),
    rtol: float = typer.Option(1e-6, "--rtol", help="DAP_BC forward dynamics: relative tolerance (ode45's RelTol)."),
    atol: float = typer.Option(1e-9, "--atol", help="DAP_BC forward dynamics: absolute tolerance (ode45's AbsTol)."),
    projection: bool = typer.Option(True, "--projection/--no-projection", help="DAP_BC forward dynamics: project each step onto the constraints (off: DAP_BC's algorithm exactly)."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """Run one version of a model and write its outputs into the version folder; or run a
    DAP_BC model folder and write FOLDER/000/history.nc (docs/dapbc.md).

    Exit codes: 0 break time reached, 1 stopped early (maxLinesInLog, state not finite),
    2 bad input, 130 interrupted by Ctrl-C (outputs written, marked incomplete).
    """
    from mbds.io.dapbc import is_dapbc_folder

    console = _console()
    if is_dapbc_folder(path):
        from mbds.cli.dapbc_run import dapbc_run_command

        with reported_errors(debug):
            code = dapbc_run_command(path, analysis, final_time, report_step, correct_ic, method, rtol, atol,
                                     projection, console)
        raise typer.Exit(code)
    from mbds.cli.run import run_command
    from mbds.simulation.version_run import RunOptions

    if break_time is not None and not break_time > 0:
        raise typer.BadParameter("must be a positive time (s)", param_hint="--break-time")
    with reported_errors(debug):
        code = run_command(path, RunOptions(break_time, seed, start_from), console, force)
    raise typer.Exit(code)


@app.command("next")
def next_(
    version: Path = typer.Argument(..., help="A version folder with a complete run (campaigns/wearballs/000)."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """Create the next version of a model: the shapes worn by the losses of VERSION's run."""
    from mbds.cli.job import next_command

    with reported_errors(debug):
        next_command(version, _console())


@app.command()
def job(
    path: Path = typer.Argument(..., help="A job file (campaigns/wearballs/wearballs.job)."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """Run the versions a job file lists, one after the other; run again to resume.

    Exit codes: 0 every listed version complete, 1 stopped early (maxMinutesForJob(s),
    maxLinesInLog, state not finite), 2 bad input, 130 interrupted by Ctrl-C.
    """
    from mbds.cli.job import job_command

    with reported_errors(debug):
        code = job_command(path, _console())
    raise typer.Exit(code)


@app.command()
def plot(
    kind: str = typer.Argument(..., help="shapes, watches, wear, energy, multipliers, coordinates or outline."),
    path: Path = typer.Argument(..., help="A version folder, a model folder (its versions) or a history.nc."),
    output: Path = typer.Option(None, "-o", "--output", help="File to write (.png, .svg, .pdf); default <kind>.png beside the run."),
    time: float = typer.Option(None, "--time", help="shapes: the time to draw (s); default the run's end."),
    body: str = typer.Option(None, "--body", help="wear, outline: the body; default the one that lost most work."),
    versions: str = typer.Option(None, "--versions", help="wear: the versions to overlay, e.g. 000-005,008."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """Draw a figure of a run (or of a model's versions, for wear) into a file."""
    from mbds.cli.plot import plot_command

    with reported_errors(debug):
        print(f"wrote {plot_command(kind, path, output, time, body, versions)}")


@app.command()
def animate(
    path: Path = typer.Argument(..., help="A version folder, a model folder (its last run) or a history.nc."),
    output: Path = typer.Option(None, "-o", "--output", help="run.mp4 (needs ffmpeg) or run.gif; default animation.mp4 or .gif beside the run."),
    fps: float = typer.Option(30, "--fps", help="Frames per second of video."),
    speed: float = typer.Option(1.0, "--speed", help="Seconds of the run per second of video."),
    contacts: bool = typer.Option(True, "--contacts/--no-contacts", help="Mark watched points and their impulses."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """Animate a run: its bodies at FPS frames per second of video, with a time label."""
    from mbds.cli.plot import animate_command

    if not fps > 0 or not speed > 0:
        raise typer.BadParameter("--fps and --speed must be positive")
    with reported_errors(debug):
        print(f"wrote {animate_command(path, output, fps, speed, contacts)}")


@app.command()
def versions(
    model: Path = typer.Argument(..., help="A model folder (campaigns/wearballs)."),
    delete: str = typer.Option(None, "--delete", help="Delete these versions, e.g. 003-005."),
    yes: bool = typer.Option(False, "--yes", help="Delete without asking."),
    resample: str = typer.Option(None, "--resample", help="Resample the history of these versions, e.g. 002."),
    interval: float = typer.Option(None, "--interval", help="--resample: the new sample interval (s)."),
    debug: bool = typer.Option(False, "--debug", help="Show a traceback on errors."),
) -> None:
    """List a model's versions with their status, break time, lost work and wall time; delete
    versions, or resample a history to a coarser interval."""
    from mbds.cli.versions import versions_command

    with reported_errors(debug):
        versions_command(model, delete, yes, resample, interval, _console())


def _console() -> Console:
    """A console for the terminal, or a wide one for a file or pipe."""
    return Console() if sys.stdout.isatty() else Console(width=140)
