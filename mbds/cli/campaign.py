"""The ``mbds-campaign`` command: wear campaigns over many ranks."""

from __future__ import annotations

import typer

app = typer.Typer(
    help=(
        "Run-in wear campaigns: expand a job file into chains of versions and parameter variants, "
        "run them across MPI ranks, and collect the results into one dataset."
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


@app.callback(invoke_without_command=True)
def main(ctx: typer.Context) -> None:
    """Wear campaigns across MPI ranks (commands: none yet in this release)."""
    if ctx.invoked_subcommand is None:
        print(ctx.get_help())
