"""mbds: planar rigid multibody dynamics with unilateral contacts and run-in wear."""

from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("mbds")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+source"

__all__ = ["__version__", "open_campaign"]


def __getattr__(name: str):
    """``mbds.open_campaign`` (:func:`mbds.campaign.collect.open_campaign`), imported on first use."""
    if name == "open_campaign":
        from mbds.campaign.collect import open_campaign

        return open_campaign
    raise AttributeError(f"module 'mbds' has no attribute {name!r}")
