"""How the ranks of ``mbds-campaign run`` leave: a worker that has finished must not take rank 0
down with it, mpiexec must report rank 0's exit code, and a rank 0 that stops before it schedules
anything (a wrong option) must not leave the workers waiting.

MPICH's Hydra proxy kills every rank still running (SIGKILL) when one closes its link to the
process manager without announcing its end; MPICH announces it from a C exit handler. The
script below runs the workers' real path (serve until told to quit, then leave) while rank 0,
after releasing them and ending MPI, takes a while over its own shut-down."""

import subprocess
import sys
import time
from pathlib import Path

import pytest

MPIEXEC = Path(sys.executable).parent / "mpiexec"
SCRIPT = """
import sys, time
from pathlib import Path
from mpi4py import MPI
from mbds.campaign.executors import Ranks
from mbds.cli.campaign_entry import _leave
from mbds.cli.mpi_world import serve_worker

comm = MPI.COMM_WORLD
if comm.Get_rank() > 0:
    serve_worker(comm)
    _leave(0)
Ranks(comm).close()
MPI.Finalize()
time.sleep(1.0)  # rank 0's shut-down, still under way when the workers have gone
Path(sys.argv[1]).write_text("rank 0 lived to the end")
_leave(3)
"""


@pytest.mark.mpi
def test_rank_0_outlives_the_workers_and_mpiexec_reports_its_exit_code(tmp_path):
    script, mark = tmp_path / "ranks.py", tmp_path / "mark"
    script.write_text(SCRIPT)
    done = subprocess.run([str(MPIEXEC), "-n", "3", sys.executable, str(script), str(mark)],
                          capture_output=True, text=True, timeout=120)
    assert mark.exists(), done.stdout + done.stderr  # not killed in its shut-down
    assert done.returncode == 3, done.stdout + done.stderr


@pytest.mark.mpi
def test_a_wrong_option_under_mpiexec_exits_2_on_every_rank(tmp_path):
    """typer refuses the option on rank 0 before any scheduling: the workers are released and
    the launch ends with exit 2 and typer's message, instead of waiting forever."""
    console = Path(sys.executable).parent / "mbds-campaign"
    done = subprocess.run([str(MPIEXEC), "-n", "3", str(console), "run", "--no-such-option", str(tmp_path / "w.job")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "No such option: --no-such-option" in done.stderr


FAILING = """
import time
from mpi4py import MPI
from mbds.cli.mpi_world import abort_on_uncaught

comm = MPI.COMM_WORLD
abort_on_uncaught(comm)
abort_on_uncaught(comm)  # as the entry and then the run command do
if comm.Get_rank() == 1:
    raise RuntimeError("a defect met by rank 1")
time.sleep(60)  # the other ranks would wait for rank 1 far longer
"""


@pytest.mark.mpi
def test_an_uncaught_error_in_one_rank_aborts_every_rank(tmp_path):
    """What ``python -m mpi4py`` does: the failing rank's traceback, printed once, and every rank
    stopped at once with a non-zero exit instead of waiting for it."""
    script = tmp_path / "failing.py"
    script.write_text(FAILING)
    begun = time.monotonic()
    done = subprocess.run([str(MPIEXEC), "-n", "3", sys.executable, str(script)], capture_output=True, text=True,
                          timeout=120)
    assert time.monotonic() - begun < 30
    assert done.returncode != 0
    # the traceback's source line, not its last one: the launcher may drop the last bytes a rank
    # wrote when the abort kills it (one run printed "RuntimeError: " and no message)
    assert (done.stdout + done.stderr).count('raise RuntimeError("a defect met by rank 1")') == 1
