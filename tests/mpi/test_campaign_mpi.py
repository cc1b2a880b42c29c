"""A campaign of 4 chains run on MPI ranks (mpiexec -n 2 and -n 3), in a process pool and in one
process gives bit-identical collected data."""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mbds
from mbds.campaign.collect import collect
from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import expand
from tests.campaign.models import two_mass

MPIEXEC = Path(sys.executable).parent / "mpiexec"
FOUR = "c'gravity = 9.81, 5\ncontact.mass1-mass2.friction = 0.1, 0.3\nworld.breakTime = 0.05\n"
LAUNCHES = {
    "one process": [],
    "pool": ["--workers", "2"],
    "2 ranks": ["-n", "2"],
    "3 ranks": ["-n", "3"],
}


def launch(job, how):
    """Run the campaign of ``job`` as ``how`` says; the collected tree."""
    args = LAUNCHES[how]
    command = [sys.executable, "-m", "mbds.cli.campaign", "run", str(job)]
    if args[:1] == ["-n"]:
        command = [str(MPIEXEC), *args, sys.executable, "-m", "mpi4py", "-m", "mbds.cli.campaign", "run", str(job)]
    else:
        command += args
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return mbds.open_campaign(collect(expand(job)))


@pytest.mark.mpi
def test_collected_data_do_not_depend_on_how_the_campaign_ran(tmp_path):
    trees = {}
    for how in LAUNCHES:
        job = two_mass(tmp_path / how.replace(" ", "_"), FOUR, jobs="000-002")
        trees[how] = launch(job, how)
        ledger = Ledger.read(expand(job).folder)
        ranks = {e.get("rank") for e in ledger.tasks.values()}
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
