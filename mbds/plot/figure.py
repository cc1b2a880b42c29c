"""New figures and axes, and saving figures and animations atomically."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

from matplotlib.animation import Animation, FFMpegWriter, PillowWriter
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from mbds.errors import ModelError

FIGURE_FORMATS = ("png", "svg", "pdf")
VIDEO_FORMATS = ("mp4", "gif")


def new_axes(size: tuple[float, float] = (6.4, 4.8)) -> Axes:
    """Axes on a new figure (not registered with pyplot, so nothing stays open)."""
    return Figure(figsize=size, layout="constrained").add_subplot()


def video_suffix() -> str:
    """mp4 when ffmpeg is installed, gif otherwise."""
    return "mp4" if FFMpegWriter.isAvailable() else "gif"


def save(what: Figure | Axes | Animation, path: str | Path, fps: float = 30, dpi: int = 100) -> Path:
    """Write a figure (png, svg, pdf) or an animation (mp4 through ffmpeg, gif through Pillow)
    to ``path`` through a temporary file and a rename; the path."""
    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    with _beside(path) as tmp:
        if isinstance(what, Animation):
            if suffix not in VIDEO_FORMATS:
                raise ModelError(f"an animation is saved as {' or '.join(VIDEO_FORMATS)}", path)
            if suffix == "mp4" and not shutil.which("ffmpeg"):
                raise ModelError("mp4 needs ffmpeg, which is not installed; write a .gif", path)
            writer = FFMpegWriter(fps=fps) if suffix == "mp4" else PillowWriter(fps=fps)
            what.save(str(tmp), writer=writer, dpi=dpi)
        else:
            if suffix not in FIGURE_FORMATS:
                raise ModelError(f"a figure is saved as {', '.join(FIGURE_FORMATS)}", path)
            figure = what.figure if isinstance(what, Axes) else what
            figure.savefig(tmp, format=suffix, dpi=dpi)
    return path


@contextlib.contextmanager
def _beside(path: Path):
    """A temporary file beside ``path`` with its extension (the writers read the format from
    it), renamed to ``path`` when the block ends normally and removed otherwise."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
