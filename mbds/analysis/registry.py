"""The registry of analyses: name -> function(system, settings, progress) -> result."""

from __future__ import annotations

from collections.abc import Callable

from mbds.errors import ModelError

ANALYSES: dict[str, Callable] = {}


def register_analysis(name: str):
    """Function decorator: register the analysis ``name``."""
    def add(function):
        ANALYSES[name] = function
        return function
    return add


def analysis(name: str) -> Callable:
    """The analysis registered as ``name``; ModelError naming the known ones otherwise."""
    import mbds.analysis.dapbc  # noqa: F401  (registers the body-coordinate analyses)

    if name not in ANALYSES:
        raise ModelError(f"unknown analysis '{name}' (known: {', '.join(sorted(ANALYSES))})")
    return ANALYSES[name]
