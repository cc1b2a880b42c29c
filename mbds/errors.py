"""Errors and warnings about user input, located by file and line."""

from __future__ import annotations

import warnings
from pathlib import Path


class ModelError(Exception):
    """Bad user input: a message, and where it was found (file and 1-based line, when known)."""

    def __init__(self, message: str, file: str | Path | None = None, line: int | None = None):
        super().__init__(message)
        self.message = message
        self.file = str(file) if file is not None else None
        self.line = line

    def __str__(self) -> str:
        return f"{location(self.file, self.line)}{self.message}"


class ModelWarning(UserWarning):
    """Input that is accepted but probably not what the user meant (an unknown key, say)."""


def location(file: str | Path | None, line: int | None) -> str:
    """``file:line: `` prefix (empty parts left out)."""
    if file is None:
        return ""
    return f"{file}:{line}: " if line is not None else f"{file}: "


def warn(message: str, file: str | Path | None = None, line: int | None = None) -> None:
    """Issue a :class:`ModelWarning` located at ``file:line``."""
    warnings.warn(f"{location(file, line)}{message}", ModelWarning, stacklevel=2)
