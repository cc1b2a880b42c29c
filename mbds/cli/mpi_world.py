"""Where ``mbds-campaign run`` stands under an MPI launcher (mpiexec, mpirun, srun): how many ranks
the launcher started, this process's rank, MPI's world, and a worker rank's whole life.

Nothing here imports typer or rich: a worker rank started as ``mbds-campaign run JOB`` goes from
the console script straight to :func:`serve_worker` (see :mod:`mbds.cli.campaign_entry`), so
that many ranks starting at once import only what running tasks needs.
"""

from __future__ import annotations

import os
import sys
import time

LAUNCHER_SIZES = ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "MV2_COMM_WORLD_SIZE", "PMIX_SIZE")
"""Environment variables in which MPI launchers (MPICH's Hydra, Intel MPI, Open MPI, MVAPICH,
PMIx) tell each process how many ranks they started; Slurm's srun: ``SLURM_STEP_NUM_TASKS``."""

LAUNCHER_RANKS = ("PMI_RANK", "OMPI_COMM_WORLD_RANK", "MV2_COMM_WORLD_RANK", "PMIX_RANK")
"""The same launchers' variables holding this process's rank; Slurm's srun: ``SLURM_PROCID``."""

EXIT_ALONE = 2
"""Exit code of a rank that its launcher started as one of several but that MPI shows a world of 1."""

ABORT_GRACE = 0.5
"""Seconds a rank with an uncaught exception waits, after printing its traceback, before it aborts
every rank: the launcher reads a rank's output through a pipe and lost the end of the traceback
when the abort came first (about one launch in twelve)."""


def _first_number(names, environ) -> int | None:
    for name in names:
        value = environ.get(name, "")
        if value.isdigit():
            return int(value)
    return None


def _in_srun_step(environ) -> bool:
    """Whether this process was started by ``srun`` (a job step), not merely inside an allocation."""
    return "SLURM_STEP_ID" in environ


def launcher_ranks(environ=os.environ) -> int:
    """How many ranks the launcher (mpiexec, mpirun, srun) started, from its environment; 1 when
    the process was not started by one."""
    slurm = ["SLURM_STEP_NUM_TASKS"] if _in_srun_step(environ) else []
    return _first_number([*LAUNCHER_SIZES, *slurm], environ) or 1


def launcher_rank(environ=os.environ) -> int:
    """This process's rank as the launcher's environment says (0 when not started by one)."""
    slurm = ["SLURM_PROCID"] if _in_srun_step(environ) else []
    return _first_number([*LAUNCHER_RANKS, *slurm], environ) or 0


def mpi_world():
    """MPI's world communicator when launched on more than one rank (``mbds-campaign run`` or
    ``python -m mpi4py -m mbds.cli.campaign run`` under mpiexec or srun), else None.

    A process that its launcher started as one of several ranks but that finds a world of one
    (mpi4py built against another MPI library than the launcher's) stops with exit 2 instead of
    running the whole campaign alone beside its copies."""
    asked = launcher_ranks()
    if asked == 1 and "mpi4py.run" not in sys.modules:
        return None
    from mpi4py import MPI

    size = MPI.COMM_WORLD.Get_size()
    if size == 1 and asked > 1:
        print(f"error: the launcher started {asked} ranks, but MPI sees a world of 1 in this process: "
              "mpi4py was built against another MPI library than the launcher's (use the mpiexec "
              "of the MPI that mpi4py uses, e.g. the one beside this Python)", file=sys.stderr)
        raise SystemExit(EXIT_ALONE)
    return MPI.COMM_WORLD if size > 1 else None


def abort_on_uncaught(comm) -> None:
    """Make an uncaught exception in this rank abort all ranks (what ``python -m mpi4py`` does),
    so that a failing rank never leaves the others waiting."""
    if comm is None or "mpi4py.run" in sys.modules or getattr(sys.excepthook, "aborts_mpi", False):
        return  # a second call (the entry, then the run command) keeps the first hook
    previous = sys.excepthook

    def abort(kind, value, trace):
        previous(kind, value, trace)
        sys.stderr.flush()
        time.sleep(ABORT_GRACE)  # the launcher passes the traceback on before the abort kills its reader
        comm.Abort(1)

    abort.aborts_mpi = True
    sys.excepthook = abort


def serve_worker(comm) -> None:
    """A worker rank (rank > 0 of ``comm``): run the tasks rank 0 sends until it says to quit."""
    from mbds.campaign import executors
    from mbds.campaign.run import stop_signals

    with stop_signals() as stopping:
        executors.serve(comm, stopping)


def leave_process(status: int) -> None:
    """End this process with ``status`` through C's ``exit`` (POSIX), skipping the interpreter's
    teardown but not the C exit handlers.

    MPICH (4.1 and later) tells its process manager that a rank is done from such a handler, not
    from ``MPI_Finalize``. A rank that left with ``os._exit`` would close its link to the manager
    unannounced; Hydra's proxy then kills every rank still running with SIGKILL, and mpiexec
    reports 9, or 0 whatever the ranks' exit codes (tests/mpi/test_rank_exit.py)."""
    import ctypes

    sys.stdout.flush()
    sys.stderr.flush()
    ctypes.CDLL(None).exit(status)
