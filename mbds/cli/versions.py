"""``mbds versions``: the versions of a model (the History window), deleting and resampling them."""

from __future__ import annotations

import shutil
from pathlib import Path

import typer
from rich.console import Console
from rich.table import Table

from mbds.data.history import FILE_NAME, read_attributes
from mbds.errors import ModelError
from mbds.io.folder import find_world, version_name
from mbds.io.job import expand_versions
from mbds.simulation.versions import existing_versions


def version_rows(model: Path) -> list[tuple[str, str, str, str, str]]:
    """Per version folder: number, status (complete, stopped: why, not run), break time (s),
    lost work (J) and wall time (s) of its run."""
    find_world(model)
    rows = []
    for number in existing_versions(model):
        history = model / version_name(number) / FILE_NAME
        if not history.is_file():
            rows.append((version_name(number), "not run", "", "", ""))
            continue
        attrs = read_attributes(history)
        status = "complete" if attrs.get("complete") else f"stopped: {attrs.get('stop_reason', '')}"
        wall = attrs.get("wall_time", float("nan"))
        rows.append((version_name(number), status, f"{attrs['break_time']:.6g}", f"{attrs['run_lost_work']:.6g}",
                     f"{wall:.3g}" if wall == wall else "-"))
    return rows


def versions_command(model: Path, delete: str | None, yes: bool, resample: str | None, interval: float | None,
                     console: Console) -> None:
    """List the versions of ``model``; delete those of ``delete`` (asking unless ``yes``) or
    resample the history of version ``resample`` to ``interval`` s."""
    if delete:
        _delete(model, expand_versions(delete), yes, console)
    elif resample:
        from mbds.data.resample import resample as resample_history

        if interval is None:
            raise ModelError("--resample needs --interval (s)")
        for number in expand_versions(resample):
            path = model / version_name(number) / FILE_NAME
            if not path.is_file():
                raise ModelError(f"no {FILE_NAME}: version {version_name(number)} has not run", path.parent)
            console.print(f"{path}: {resample_history(path, interval)} samples at {interval:g} s")
    table = Table("version", "status", "break time (s)", "lost work (J)", "wall time (s)", title=str(model))
    for row in version_rows(model):
        table.add_row(*row)
    console.print(table)


def _delete(model: Path, numbers: list[int], yes: bool, console: Console) -> None:
    """Remove the folders of version ``numbers`` (all must exist)."""
    find_world(model)
    present = set(existing_versions(model))
    missing = [version_name(n) for n in numbers if n not in present]
    if missing:
        raise ModelError(f"no version {', '.join(missing)}", model)
    names = ", ".join(version_name(n) for n in numbers)
    if not yes and not typer.confirm(f"delete version {names} of {model} with its outputs?"):
        console.print("nothing deleted")
        return
    for number in numbers:
        shutil.rmtree(model / version_name(number))
    console.print(f"deleted {names}")
