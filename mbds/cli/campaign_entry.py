"""The ``mbds-campaign`` console script.

A worker rank of ``mbds-campaign run JOB`` under an MPI launcher (rank > 0 in the launcher's
environment) serves tasks at once, without importing the command-line parser (typer, rich):
its arguments are rank 0's to read. Every other use goes to :data:`mbds.cli.campaign.app`.
"""

from __future__ import annotations

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
            return
    from mbds.cli.campaign import app

    app()
