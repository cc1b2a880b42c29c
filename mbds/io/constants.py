"""Constants files (``.cns``): ``c'name = value`` lines."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.text import QUOTES, format_number, parse_number, significant_lines

_NAME = re.compile(rf"c[{QUOTES}]([A-Za-z_]\w*)")


@dataclass
class ConstantsFile:
    """Constant values by name (without the ``c'`` context), in file order."""

    values: dict[str, float] = field(default_factory=dict)
    lines: dict[str, int] = field(default_factory=dict, compare=False)
    path: Path | None = field(default=None, compare=False)


def parse_constants(text: str, path: str | Path | None = None, separator: str = ".") -> ConstantsFile:
    values: dict[str, float] = {}
    lines: dict[str, int] = {}
    for line in significant_lines(text, path):
        key, eq, value = line.text.partition("=")
        if not eq:
            raise ModelError(f"expected c'name = value, found '{line.text}'", path, line.number)
        m = _NAME.fullmatch(key.strip().rstrip(";"))
        if not m:
            raise ModelError(f"'{key.strip()}' is not a constant name like c'gravity", path, line.number)
        name = m.group(1)
        if name in values:
            warn(f"constant c'{name} given again (first on line {lines[name]}); the last one counts", path, line.number)
        values[name] = parse_number(value.strip().rstrip(";"), path, line.number, separator)
        lines[name] = line.number
    return ConstantsFile(values, lines, Path(path) if path else None)


def format_constants(cns: ConstantsFile, separator: str = ".") -> str:
    return "".join(f"c'{name} = {format_number(v, separator)}\n" for name, v in cns.values.items())
