"""Extrusion shape files (``.exs``): the closed polygon of a body, in body coordinates (m)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mbds.errors import ModelError, warn
from mbds.io.text import (
    format_number,
    is_directive,
    parse_integer,
    parse_number,
    significant_lines,
)


@dataclass
class ShapeFile:
    """Polygon points as an (N, 2) array; the first and the last point are the same."""

    points: np.ndarray
    path: Path | None = field(default=None, compare=False)
    data_line: int | None = field(default=None, compare=False)

    def __eq__(self, other) -> bool:
        return isinstance(other, ShapeFile) and np.array_equal(self.points, other.points)


def parse_shape(text: str, path: str | Path | None = None, separator: str = ".") -> ShapeFile:
    """A :class:`ShapeFile` from ``points = N`` and a ``%%data`` ... ``%%enddata`` block.

    The block holds either two lines (the N x values, then the N y values: the manual's layout)
    or N lines of ``x y`` pairs.
    """
    lines = significant_lines(text, path)
    count = None
    count_line = None
    data: list = []
    start = None
    for line in lines:
        if start is None:
            if is_directive(line, "%%data"):
                start = line.number
                data = []
                continue
            key, eq, value = line.text.partition("=")
            if eq and key.strip().lower() == "points":
                count = parse_integer(value, path, line.number)
                count_line = line.number
            else:
                warn(f"unexpected line '{line.text}' outside %%data (ignored)", path, line.number)
        elif is_directive(line, "%%enddata"):
            break
        else:
            if separator == ",":
                tokens = line.text.replace(";", " ").split()
            else:
                tokens = line.text.replace(",", " ").split()
            data.append((line.number, tokens))
    else:
        if start is None:
            raise ModelError("no %%data block", path, lines[-1].number if lines else 1)
        raise ModelError("%%data block has no %%enddata", path, start)
    if count is None:
        raise ModelError("missing 'points = N' before %%data", path, start)
    if count < 4:
        raise ModelError(f"a closed polygon needs at least 4 points (3 corners and the closing point), not {count}", path, count_line)
    values = [[parse_number(t, path, n, separator) for t in tokens] for n, tokens in data]
    if len(values) == 2 and all(len(row) == count for row in values):
        points = np.array(values, dtype=float).T
    elif len(values) == count and all(len(row) == 2 for row in values):
        points = np.array(values, dtype=float)
    else:
        shapes = ", ".join(str(len(row)) for row in values)
        raise ModelError(
            f"%%data must hold 2 lines of {count} values (x then y) or {count} lines of 'x y'; "
            f"found {len(values)} lines with {shapes} values",
            path,
            start,
        )
    return ShapeFile(points, Path(path) if path else None, start)


def format_shape(shape: ShapeFile, separator: str = ".") -> str:
    """The text of a ``.exs`` file in the manual's layout (x line, y line)."""
    xs = " ".join(format_number(v, separator) for v in shape.points[:, 0])
    ys = " ".join(format_number(v, separator) for v in shape.points[:, 1])
    return f"points = {len(shape.points)}\n%%data\n{xs}\n{ys}\n%%enddata\n"
