"""The version of mbds (the installed distribution's; ``0.0.0+source`` in a source tree that is
not installed). Modules ask :func:`version` when they write it, never at import: reading the
installed distribution's metadata takes 40-60 ms (measured), which every process of a campaign
would pay at start. ``mbds.__version__`` and this module's ``__version__`` ask it too."""

from __future__ import annotations

import functools


@functools.cache
def version() -> str:
    """The installed distribution's version, ``0.0.0+source`` when mbds is not installed."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("mbds")
    except PackageNotFoundError:  # running from a source tree that is not installed
        return "0.0.0+source"


def __getattr__(name: str) -> str:
    if name == "__version__":
        return version()
    raise AttributeError(f"module 'mbds._version' has no attribute {name!r}")
