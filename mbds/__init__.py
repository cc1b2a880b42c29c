"""mbds: planar rigid multibody dynamics with unilateral contacts and run-in wear."""

__all__ = ["__version__", "open_campaign", "outline", "select", "simulate", "stack"]
_LAZY = {
    "open_campaign": "mbds.campaign.collect",
    "outline": "mbds.data.analysis",
    "select": "mbds.data.analysis",
    "stack": "mbds.data.analysis",
    "simulate": "mbds.simulation.notebook",
}


def __getattr__(name: str):
    """``__version__`` (read from the installed distribution on first use) and the notebook API,
    imported on first use: ``open_campaign``
    (:mod:`mbds.campaign.collect`), ``outline``, ``stack``, ``select`` (:mod:`mbds.data.analysis`)
    and ``simulate`` (:mod:`mbds.simulation.notebook`)."""
    if name == "__version__":
        from mbds._version import version

        return version()
    if name in _LAZY:
        from importlib import import_module

        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'mbds' has no attribute {name!r}")
