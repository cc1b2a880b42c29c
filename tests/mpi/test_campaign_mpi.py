"""A campaign of 4 chains run on MPI ranks (mpiexec -n 2 and -n 3), in a process pool and in one
process gives bit-identical collected data, and no task compiles (the warm-up did); SIGTERM to
mpiexec stops all ranks cleanly and the campaign resumes."""

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import mbds
from mbds.campaign.collect import collect
from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import RUN, expand
from mbds.data.history import read_attributes
from tests.campaign.models import two_mass
from tests.examples import copy_example

MPIEXEC = Path(sys.executable).parent / "mpiexec"
CONSOLE = Path(sys.executable).parent / "mbds-campaign"
FOUR = "c'gravity = 9.81, 5\ncontact.mass1-mass2.friction = 0.1, 0.3\nworld.breakTime = 0.05\n"
LAUNCHES = {
    "one process": [],
    "pool": ["--workers", "2"],
    "2 ranks": ["-n", "2"],
    "3 ranks": ["-n", "3"],  # launched as `mpiexec -n 3 mbds-campaign run`, the console script
}


def launch(job, how):
    """Run the campaign of ``job`` as ``how`` says; the collected tree."""
    args = LAUNCHES[how]
    command = [sys.executable, "-m", "mbds.cli.campaign", "run", str(job)]
    if how == "3 ranks":
        command = [str(MPIEXEC), *args, str(CONSOLE), "run", str(job)]
    elif args[:1] == ["-n"]:
        command = [str(MPIEXEC), *args, sys.executable, "-m", "mpi4py", "-m", "mbds.cli.campaign", "run", str(job)]
    else:
        command += args
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr  # mpiexec reports a killed rank on stdout
    return mbds.open_campaign(collect(expand(job)))


@pytest.mark.mpi
def test_collected_data_do_not_depend_on_how_the_campaign_ran(tmp_path):
    trees = {}
    for how in LAUNCHES:
        job = two_mass(tmp_path / how.replace(" ", "_"), FOUR, jobs="000-002")
        trees[how] = launch(job, how)
        ledger = Ledger.read(expand(job).folder)
        ranks = {e.get("rank") for e in ledger.tasks.values()}
        assert {e["compiled"] for e in ledger.tasks.values()} == {0}  # the warm-up compiled all
        if how == "3 ranks":
            assert ranks == {1, 2}  # rank 0 only schedules
        elif how == "2 ranks":
            assert ranks == {1}
        shutil.rmtree(job.parent / "campaign" / ".cache", ignore_errors=True)
    reference = trees.pop("one process")
    assert len(reference.ds["variant"]) == 4
    for how, tree in trees.items():
        for node in reference.subtree:
            other = tree[node.path]
            for name, variable in node.ds.data_vars.items():
                if name == "wall":
                    continue
                assert np.array_equal(variable.values, other.ds[name].values), (how, node.path, name)
        assert tree.ds.attrs["workers"] == {"pool": 2, "2 ranks": 1, "3 ranks": 2}[how]


@pytest.mark.mpi
def test_a_rank_alone_in_its_world_refuses_to_run(tmp_path):
    """A launcher that started 2 ranks (PMI_SIZE = 2) while MPI shows this process a world of
    one (mismatched MPI libraries) must not run the campaign alone: exit 2, nothing run."""
    job = two_mass(tmp_path / "alone", FOUR, jobs="000")
    env = {**os.environ, "PMI_SIZE": "2"}
    done = subprocess.run([str(CONSOLE), "run", str(job)], capture_output=True, text=True, timeout=120, env=env)
    assert done.returncode == 2, done.stderr
    assert "launcher started 2 ranks, but MPI sees a world of 1" in done.stderr
    assert not (job.parent / "campaign" / "ledger.json").exists()


@pytest.mark.mpi
def test_the_module_form_reaches_the_console_script_before_the_parser(tmp_path):
    """``python -m mpi4py -m mbds.cli.campaign run`` starts a rank as ``mbds-campaign run`` does:
    the module hands over to the console script's entry before it imports typer, so a worker
    rank of either form starts without the command-line parser (here the rank refuses a world
    of one before any role is given; ``-X importtime`` lists what it imported)."""
    job = two_mass(tmp_path / "module", FOUR, jobs="000")
    env = {**os.environ, "PMI_SIZE": "2", "PMI_RANK": "1"}
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "mbds.cli.campaign", "run", str(job)],
                          capture_output=True, text=True, timeout=120, env=env)
    assert done.returncode == 2, done.stderr
    imported = {line.rsplit("|", 1)[-1].strip() for line in done.stderr.splitlines() if line.startswith("import time:")}
    assert {"mpi4py.MPI", "mbds.cli.campaign_entry"} <= imported
    assert not {"typer", "rich.console"} & imported


def test_launcher_ranks_from_environment():
    from mbds.cli.mpi_world import launcher_rank, launcher_ranks

    assert launcher_ranks({}) == 1
    assert launcher_ranks({"PMI_SIZE": "4"}) == 4
    assert launcher_ranks({"OMPI_COMM_WORLD_SIZE": "16"}) == 16
    assert launcher_ranks({"SLURM_STEP_NUM_TASKS": "8"}) == 1  # an allocation, not an srun step
    assert launcher_ranks({"SLURM_STEP_NUM_TASKS": "8", "SLURM_STEP_ID": "0"}) == 8
    assert launcher_rank({}) == 0
    assert launcher_rank({"PMI_RANK": "3"}) == 3
    assert launcher_rank({"OMPI_COMM_WORLD_RANK": "0"}) == 0
    assert launcher_rank({"SLURM_PROCID": "2"}) == 0  # a batch script, not an srun step
    assert launcher_rank({"SLURM_PROCID": "2", "SLURM_STEP_ID": "0"}) == 2


WOODPECKER = """[main]
worldFile = woodpecker.wld
jobs = 000
createNextVersionAtEnd = 0
[campaign]
replicates = 2
world.breakTime = 2
"""


@pytest.mark.mpi
def test_sigterm_to_mpiexec_stops_every_rank_cleanly_and_the_campaign_resumes(tmp_path):
    job = copy_example("woodpecker", tmp_path / "woodpecker") / "replicates.job"
    job.write_text(WOODPECKER)
    plan = expand(job)
    process = subprocess.Popen([str(MPIEXEC), "-n", "3", sys.executable, "-m", "mpi4py", "-m", "mbds.cli.campaign",
                                "run", str(job)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    runs = {t.id for t in plan.tasks if t.kind == RUN}
    while len(runs & {k for k, e in Ledger.read(plan.folder).tasks.items() if e["state"] == "running"}) < 2:
        assert process.poll() is None, process.communicate()
        time.sleep(0.05)
    time.sleep(0.8)  # both workers are simulating 2 s of woodpecker (about 2 s of wall time)
    process.send_signal(signal.SIGTERM)  # mpiexec passes it on to every rank
    _, err = process.communicate(timeout=120)
    assert process.returncode == 3 and "resume" in err and "Abort" not in err, err
    ledger = Ledger.read(plan.folder)
    assert {ledger.state(t.id) for t in plan.tasks} == {"done", "pending"}
    stopped = [t for t in plan.tasks if "run again on resume" in ledger.entry(t.id).get("note", "")]
    assert len(stopped) == 2 and all(read_attributes(t.folder / "history.nc")["complete"] == 0 for t in stopped)
    launch(job, "3 ranks")
    ledger = Ledger.read(plan.folder)
    assert all(ledger.state(t.id) == "done" for t in plan.tasks)
    assert all(read_attributes(t.folder / "history.nc")["complete"] == 1 for t in stopped)
