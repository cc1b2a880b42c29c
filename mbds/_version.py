"""The version of mbds (the installed distribution's; ``0.0.0+source`` in a source tree that is
not installed). Modules import it from here, never from the root package."""

from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("mbds")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+source"
