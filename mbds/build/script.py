"""Running a build script from the command line: the model's folder on success, a located
``file:line: message`` and exit code 2 for a declaration error (no traceback)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

from mbds.errors import ModelError


def run_build(build: Callable[..., Path], *args) -> None:
    """Call ``build(*args)`` and print the world file it wrote; on a :class:`ModelError` print
    it to stderr and exit with code 2."""
    try:
        world = build(*args)
    except ModelError as error:
        print(f"error: {error}", file=sys.stderr)
        raise SystemExit(2) from None
    print(world)
