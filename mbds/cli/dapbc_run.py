"""``mbds run FOLDER`` for a DAP_BC model folder: asks what ``dap`` asks when a flag is missing
(on a terminal), prints the corrected initial conditions as DAP_BC does, shows the progress of
a forward run, and writes FOLDER/000/history.nc."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

from mbds.analysis.dapbc import Correction, DapbcSettings
from mbds.errors import ModelError


def ask(console: Console, value, question: str, convert, flag: str):
    """``value`` when given; else the answer to ``question`` on a terminal; else ModelError."""
    if value is not None:
        return value
    if not console.is_terminal:
        raise ModelError(f"{flag} is missing (it is asked for only on a terminal)")
    while True:
        answer = console.input(f"{question}\t").strip()
        try:
            return convert(answer)
        except ValueError:
            console.print(f"not understood: {escape(answer)!r}", highlight=False)


def _yes_no(answer: str) -> bool:
    if answer.lower() in ("y", "yes"):
        return True
    if answer.lower() in ("n", "no"):
        return False
    raise ValueError(answer)


def print_correction(correction: Correction, console: Console) -> None:
    """The corrected coordinates and velocities, one body a line, as DAP_BC prints them (five
    significant digits; round-off below 1e-12 shown as 0), and how much they changed."""
    def table(values: np.ndarray) -> list[str]:
        rows = np.where(np.abs(values) < 1e-12, 0.0, values).reshape(-1, 3)
        return [" ".join(f"{v:.5g}" for v in row) for row in rows]
    console.print("Corrected coordinates\nx y phi", highlight=False)
    console.print("\n".join(table(correction.q_after)), highlight=False)
    console.print("Corrected velocities\nx-dot y-dot phi-dot", highlight=False)
    console.print("\n".join(table(correction.qd_after)), highlight=False)
    dq = np.abs(correction.q_after - correction.q_before).max(initial=0.0)
    dqd = np.abs(correction.qd_after - correction.qd_before).max(initial=0.0)
    console.print(f"(largest change: coordinates {dq:.3g}, velocities {dqd:.3g}; "
                  f"{correction.iterations} Newton iterations)", highlight=False)


def dapbc_run_command(folder: Path, analysis: str | None, final_time: float | None, report_step: float | None,
                      correct_ic: bool | None, method: str, rtol: float, atol: float, projection: bool,
                      console: Console) -> int:
    """Run a DAP_BC folder; returns the exit code (0)."""
    from mbds.dapbc import run_folder

    analysis = analysis or "forward"
    if analysis in ("forward", "static"):
        correct_ic = ask(console, correct_ic, "Do you want to correct the initial conditions? [(y)es/(n)o]",
                         _yes_no, "--correct-ic or --no-correct-ic")
    final_time = ask(console, final_time, "Final time = ?", float, "--final-time")
    report_step = ask(console, report_step, "Reporting time-step = ?", float, "--report-step")
    settings = DapbcSettings(final_time, report_step, bool(correct_ic), method, rtol, atol, projection)
    console.print(f"{analysis} analysis of {escape(str(folder))}", highlight=False)
    wall = time.perf_counter()
    with Progress(TextColumn("t = {task.fields[now]:.6g} / {task.fields[end]:.6g} s"), BarColumn(),
                  TextColumn("{task.fields[nfev]:,} evaluations"), TimeElapsedColumn(),
                  console=console, disable=not console.is_terminal, transient=True) as bar:
        task = bar.add_task("", total=final_time, now=0.0, end=final_time, nfev=0)

        def progress(now, end, nfev):
            bar.update(task, completed=now, now=now, nfev=nfev)

        result, path = run_folder(folder, analysis, settings, progress)
    if result.correction is not None:
        print_correction(result.correction, console)
    if analysis == "forward":
        console.print(f"Number of function evaluations = {result.nfev}", highlight=False)
    console.print(f"wall time {time.perf_counter() - wall:.3g} s; wrote {escape(str(path))}", highlight=False)
    return 0
