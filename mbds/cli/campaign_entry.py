"""The ``mbds-campaign`` console script.

Under an MPI launcher, every rank of ``mbds-campaign run JOB`` starts MPI first. A worker rank
(rank > 0) then serves tasks at once, without importing the command-line parser (typer, rich):
its arguments are rank 0's to read. Rank 0, like every other use, goes to
:data:`mbds.cli.campaign.app`; whenever it ends, even before it could schedule (a wrong option,
say), it releases the workers, so that none waits for it forever.

When the command is over, every process, MPI rank or not, leaves without the interpreter's
teardown (0.8-1.1 s once numba, sympy and xarray are loaded, measured): it flushes its streams,
ends MPI where it began, and exits with the command's code through C's ``exit``
(:func:`_leave`, :func:`mbds.cli.mpi_world.leave_process`).
"""

from __future__ import annotations

import logging
import sys

HELP = ("--help", "-h")


def _launched_run(argv: list[str]) -> bool:
    """Whether this process is one of several ranks that a launcher started for ``run`` (a help
    request is answered by every rank)."""
    from mbds.cli.mpi_world import launcher_ranks

    return argv[:1] == ["run"] and not any(arg in HELP for arg in argv) and launcher_ranks() > 1


def main() -> None:
    comm = None
    if _launched_run(sys.argv[1:]):
        from mbds.cli.mpi_world import abort_on_uncaught, mpi_world, serve_worker

        comm = mpi_world()
        abort_on_uncaught(comm)
        if comm is not None and comm.Get_rank() > 0:
            serve_worker(comm)
            _leave(0)
    from mbds.cli.campaign import app

    try:
        app()
    except SystemExit as done:
        _leave(done.code, comm)
    _leave(0, comm)


def _leave(code, comm=None) -> None:
    """Exit with ``code`` (as SystemExit reads it) once the streams are flushed, the workers of
    ``comm`` (rank 0's world) released and MPI, if this process began it, ended; skip the
    interpreter's teardown."""
    from mbds.cli.mpi_world import leave_process

    status = code if isinstance(code, int) else (0 if code is None else 1)
    if code is not None and not isinstance(code, int):
        print(code, file=sys.stderr)
    logging.shutdown()
    if comm is not None:
        from mbds.campaign.executors import release

        release(comm)
    mpi = sys.modules.get("mpi4py.MPI")
    if mpi is not None and mpi.Is_initialized() and not mpi.Is_finalized():
        mpi.Finalize()
    leave_process(status)
