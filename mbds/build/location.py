"""Where a declaration was made: the file and line of the user's script that called the builder."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import NamedTuple

_PACKAGE = str(Path(__file__).resolve().parent)


class Location(NamedTuple):
    """A script file and 1-based line; unpacks as the ``file, line`` of :class:`ModelError`."""

    file: str | None
    line: int | None


def declared_here() -> Location:
    """The first caller outside :mod:`mbds.build`: the declaration in the user's script."""
    frame = sys._getframe(1)
    while frame is not None and str(Path(frame.f_code.co_filename).resolve().parent) == _PACKAGE:
        frame = frame.f_back
    if frame is None:
        return Location(None, None)
    return Location(frame.f_code.co_filename, frame.f_lineno)
