"""Campaign job files on a copy of campaigns/2mass (quick to read, runs in a fraction of a second
once compiled)."""

from pathlib import Path

from typer.testing import CliRunner

from mbds.cli.campaign import app
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]


def two_mass(tmp_path: Path, campaign: str | None, jobs: str = "000-002", create: int = 1) -> Path:
    """A copy of campaigns/2mass with a job file of ``jobs`` and ``campaign`` as its
    ``[campaign]`` section (None: no section); the job file's path."""
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    text = f"[main]\njobs = {jobs}\ncreateNextVersionAtEnd = {create}\n"
    if campaign is not None:
        text += "[campaign]\n" + campaign
    job = folder / "2mass.job"
    job.write_text(text)
    return job


def campaign(*args):
    """Exit code, output and error output of ``mbds-campaign``."""
    result = CliRunner().invoke(app, list(map(str, args)))
    return result.exit_code, result.stdout, result.stderr
