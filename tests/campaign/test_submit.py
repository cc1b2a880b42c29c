"""`mbds-campaign submit`: the batch script as text, and submission through a fake sbatch first
on PATH, whose job id lands in the ledger."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from mbds.campaign.ledger import Ledger
from mbds.campaign.slurm import SCRIPT_NAME
from tests.campaign.models import ROOT, campaign, two_mass

EXPECTED = Path(__file__).parent / "data" / "expected.sbatch"
SECTION = "c'gravity = 9.81, 5\nreplicates = 2\nmode = ensemble\n"
OPTIONS = ["--time", "02:00:00", "--account", "proj42", "--partition", "compute", "--signal-seconds", "600"]


def normalised(script: str, root: Path) -> str:
    return script.replace(sys.executable, "<PYTHON>").replace(str(root), "<ROOT>")


def test_dry_run_prints_the_expected_script_and_writes_nothing(tmp_path):
    job = two_mass(tmp_path, SECTION)
    code, out, err = campaign("submit", job, "--dry-run", *OPTIONS)
    assert code == 0, err
    assert normalised(out, tmp_path) == EXPECTED.read_text()
    assert not (job.parent / "campaign").exists()


def test_dry_run_leaves_out_directives_not_asked_for(tmp_path):
    job = two_mass(tmp_path, None)
    code, out, err = campaign("submit", job, "--dry-run")
    assert code == 0, err
    assert "#SBATCH --time" not in out and "#SBATCH --account" not in out and "#SBATCH --partition" not in out
    assert "#SBATCH --ntasks=2\n" in out and "#SBATCH --job-name=mbds-2mass\n" in out
    assert f"srun {sys.executable} -m mpi4py -m mbds.cli.campaign run {job}" in out


def fake_sbatch(folder: Path, answer: str, code: int = 0) -> Path:
    """An sbatch that records its arguments in ``args.txt`` and prints ``answer``."""
    folder.mkdir()
    script = folder / "sbatch"
    script.write_text(f'#!/bin/sh\necho "$@" > "{folder}/args.txt"\necho "{answer}"\nexit {code}\n')
    script.chmod(0o755)
    return folder


def test_submit_calls_sbatch_with_the_script_and_records_the_job_id(tmp_path, monkeypatch):
    job = two_mass(tmp_path, SECTION)
    bin_folder = fake_sbatch(tmp_path / "bin", "Submitted batch job 4242")
    monkeypatch.setenv("PATH", f"{bin_folder}{os.pathsep}{os.environ['PATH']}")
    code, out, err = campaign("submit", job, *OPTIONS)
    assert code == 0, err
    assert "submitted Slurm job 4242" in out
    script = job.parent / "campaign" / SCRIPT_NAME
    assert (bin_folder / "args.txt").read_text().split() == [str(script)]
    assert normalised(script.read_text(), tmp_path) == EXPECTED.read_text()
    (submission,) = Ledger.read(job.parent / "campaign").submissions
    assert submission["job_id"] == "4242" and submission["script"] == str(script)
    code, out, err = campaign("status", job)
    assert code == 0 and "Slurm job 4242 submitted" in out


def test_sbatch_refusing_the_script_is_an_error_and_records_nothing(tmp_path, monkeypatch):
    job = two_mass(tmp_path, SECTION)
    bin_folder = fake_sbatch(tmp_path / "bin", "sbatch: error: invalid account", code=1)
    monkeypatch.setenv("PATH", f"{bin_folder}{os.pathsep}{os.environ['PATH']}")
    code, out, err = campaign("submit", job)
    assert code == 2 and "sbatch did not submit the script: sbatch: error: invalid account" in " ".join(err.split())
    assert Ledger.read(job.parent / "campaign").submissions == []


def test_submit_without_sbatch_on_path_says_so(tmp_path, monkeypatch):
    job = two_mass(tmp_path, None)
    monkeypatch.setenv("PATH", str(tmp_path))
    code, out, err = campaign("submit", job)
    assert code == 2 and "sbatch not found on PATH" in err and "Traceback" not in err


def test_scripts_are_valid_shell(tmp_path):
    job = two_mass(tmp_path, SECTION)
    script = tmp_path / "campaign.sbatch"
    script.write_text(campaign("submit", job, "--dry-run")[1])
    for shell, path in (("bash", script), ("sh", ROOT / "workflows" / "local.sh")):
        checked = subprocess.run([shell, "-n", str(path)], capture_output=True, text=True)
        assert checked.returncode == 0, checked.stderr


def test_a_wheel_ships_the_template_and_submit_works_from_it(tmp_path):
    """Built and installed as a user would (not editable), `submit --dry-run` finds its template."""
    source = tmp_path / "source"  # the package's sources alone: the build leaves nothing in the repository
    shutil.copytree(ROOT / "mbds", source / "mbds", ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, source / name)
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
                            "-w", str(tmp_path / "wheel"), str(source)], capture_output=True, text=True)
    assert built.returncode == 0, built.stderr
    (wheel,) = (tmp_path / "wheel").glob("mbds-*.whl")
    site = tmp_path / "site"
    installed = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target", str(site),
                                str(wheel)], capture_output=True, text=True)
    assert installed.returncode == 0, installed.stderr
    job = two_mass(tmp_path, None)
    env = {**os.environ, "PYTHONPATH": str(site)}
    done = subprocess.run([sys.executable, "-c", "import mbds, sys; print(mbds.__file__); "
                           "from mbds.cli.campaign import app; sys.argv = ['mbds-campaign', 'submit', '--dry-run', "
                           f"{str(job)!r}]; app()"], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith(str(site)) and "#SBATCH --ntasks=2" in done.stdout


def test_nodes_memory_mpi_and_a_preamble_reach_the_script(tmp_path):
    job = two_mass(tmp_path, None)
    preamble = tmp_path / "env.sh"
    preamble.write_text("module load mpich\nsource ~/venv/bin/activate\n")
    code, out, err = campaign("submit", job, "--dry-run", "--nodes", "2", "--mem-per-cpu", "2G", "--mpi", "pmix",
                              "--preamble", preamble)
    assert code == 0, err
    assert "#SBATCH --nodes=2\n#SBATCH --mem-per-cpu=2G\n" in out
    assert "# Preamble from env.sh:\nmodule load mpich\nsource ~/venv/bin/activate\n# The ranks" in out
    assert f"srun --mpi=pmix {sys.executable} -m mpi4py" in out
    preamble.write_text("module load mpich\n#SBATCH --mem=1G\n")
    code, out, err = campaign("submit", job, "--dry-run", "--preamble", preamble)
    assert code == 2 and f"{preamble}:2: #SBATCH lines go in submit's options" in " ".join(err.split())


def test_a_complete_campaign_is_not_submitted_again_without_force(tmp_path, monkeypatch):
    job = two_mass(tmp_path, None, jobs="000", create=0)
    bin_folder = fake_sbatch(tmp_path / "bin", "Submitted batch job 7")
    monkeypatch.setenv("PATH", f"{bin_folder}{os.pathsep}{os.environ['PATH']}")
    from mbds.campaign.plan import expand

    plan = expand(job)
    ledger = Ledger.read(plan.folder)
    ledger.bind(plan)
    for task in plan.tasks:
        ledger.mark(task.id, "done")
    code, out, err = campaign("submit", job)
    assert code == 0 and "every task of the campaign is done; nothing submitted" in err
    assert not (bin_folder / "args.txt").exists()
    code, out, err = campaign("submit", job, "--force")
    assert code == 0 and "submitted Slurm job 7" in out


def test_submit_from_another_folder_gives_sbatch_the_full_path(tmp_path, monkeypatch):
    job = two_mass(tmp_path, None)
    bin_folder = fake_sbatch(tmp_path / "bin", "Submitted batch job 8")
    monkeypatch.setenv("PATH", f"{bin_folder}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.chdir(tmp_path)
    code, out, err = campaign("submit", job.relative_to(tmp_path))
    assert code == 0, err
    assert (bin_folder / "args.txt").read_text().split() == [str(job.parent / "campaign" / SCRIPT_NAME)]
