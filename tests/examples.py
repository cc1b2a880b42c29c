"""Copies of the example models for tests: the model and job files only, never the version or
campaign folders that running an example leaves in it (README's first command does)."""

import re
import shutil
from pathlib import Path

CAMPAIGNS = Path(__file__).resolve().parents[1] / "campaigns"


def _runs(folder, names):
    return [n for n in names if n == "campaign" or re.fullmatch(r"\d{3}", n) or n.startswith(".")]


def copy_example(name: str, folder: Path) -> Path:
    """Copy the example model ``name`` (a folder of campaigns/) into ``folder``; return it."""
    shutil.copytree(CAMPAIGNS / name, folder, ignore=_runs)
    return folder
