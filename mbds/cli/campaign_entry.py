"""The ``mbds-campaign`` console script.

A worker rank of ``mbds-campaign run JOB`` under an MPI launcher (rank > 0 in the launcher's
environment) serves tasks at once, without importing the command-line parser (typer, rich):
its arguments are rank 0's to read. Every other use goes to :data:`mbds.cli.campaign.app`.

When the command is over, every process, MPI rank or not, leaves without the interpreter's
teardown (0.8-1.1 s once numba, sympy and xarray are loaded, measured): it flushes its streams,
ends MPI where it began, and exits with the command's code through C's ``exit``
(:func:`_leave`, :func:`mbds.cli.mpi_world.leave_process`).
"""

from __future__ import annotations

import logging
import sys

HELP = ("--help", "-h")


def _worker_rank(argv: list[str]) -> bool:
    """Whether this process is a worker rank of ``run`` (a help request is answered by every rank)."""
    from mbds.cli.mpi_world import launcher_rank

    return argv[:1] == ["run"] and not any(arg in HELP for arg in argv) and launcher_rank() > 0


def main() -> None:
    if _worker_rank(sys.argv[1:]):
        from mbds.cli.mpi_world import abort_on_uncaught, mpi_world, serve_worker

        comm = mpi_world()
        if comm is not None:
            abort_on_uncaught(comm)
            serve_worker(comm)
            _leave(0)
    from mbds.cli.campaign import app

    try:
        app()
    except SystemExit as done:
        _leave(done.code)
    _leave(0)


def _leave(code) -> None:
    """Exit with ``code`` (as SystemExit reads it) once the streams are flushed and MPI, if this
    process began it, is ended; skip the interpreter's teardown."""
    from mbds.cli.mpi_world import leave_process

    status = code if isinstance(code, int) else (0 if code is None else 1)
    if code is not None and not isinstance(code, int):
        print(code, file=sys.stderr)
    logging.shutdown()
    mpi = sys.modules.get("mpi4py.MPI")
    if mpi is not None and mpi.Is_initialized() and not mpi.Is_finalized():
        mpi.Finalize()
    leave_process(status)
