"""Lines, comments and numbers of MBDS text files.

Every MBDS file is line-oriented text. ``%`` starts a comment that runs to the end of the line,
except in the block directives that begin with ``%%`` (``%%data``, ``%%%new%%%``, ...).
Numbers follow the model's ``decimalSeparator`` (``.`` or ``,``) and may use Mathematica's
exponent form ``1.5*^-7``.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from mbds.errors import ModelError

QUOTES = "`'\u2018\u2019"
"""Characters accepted as context quotes (backquote, apostrophe and their typographic forms)."""


@dataclass(frozen=True)
class Line:
    """One significant line of a file: its 1-based number and its text without comment."""

    number: int
    text: str


def read_text(path: str | Path) -> str:
    """The text of a file, or a :class:`ModelError` naming it when it cannot be read."""
    try:
        raw = Path(path).read_bytes()
    except FileNotFoundError:
        raise ModelError("file not found", path) from None
    except IsADirectoryError:
        raise ModelError("is a directory, expected a file", path) from None
    except OSError as exc:
        raise ModelError(f"cannot read file: {exc.strerror}", path) from None
    if raw.startswith(b"\xef\xbb\xbf"):
        raw = raw[3:]
    if b"\x00" in raw:
        line = raw.count(b"\n", 0, raw.index(b"\x00")) + 1
        raise ModelError("binary data (NUL character) in a text file", path, line)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("latin-1")


def strip_comment(text: str) -> str:
    """``text`` without its ``%`` comment; lines starting with ``%%`` are directives and kept."""
    stripped = text.strip()
    if stripped.startswith("%%"):
        directive, _, rest = stripped.partition(" ")
        return f"{directive} {strip_comment(rest)}".strip()
    cut = text.find("%")
    return (text if cut < 0 else text[:cut]).strip()


def significant_lines(text: str, file: str | Path | None = None) -> list[Line]:
    """The non-empty lines of ``text`` (of ``file``, for errors) after comments are removed,
    with their numbers."""
    lines = []
    for number, raw in enumerate(text.splitlines(), start=1):
        if "\x00" in raw:
            raise ModelError("binary data (NUL character) in a text file", file, number)
        content = strip_comment(raw)
        if content:
            lines.append(Line(number, content))
    return lines


def is_directive(line: Line, name: str) -> bool:
    """Whether ``line`` is the block directive ``name`` (``%%data``, ``%%J``, ...)."""
    return line.text.split()[0] == name if line.text else False


_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+|\*\^[+-]?\d+)?")


def parse_number(text: str, file: str | Path | None, line: int | None, separator: str = ".") -> float:
    """A real number, with ``separator`` as decimal mark and optional ``*^`` exponent."""
    token = text.strip()
    if separator == ",":
        if "." in token:
            raise ModelError(f"'{token}' uses '.' but decimalSeparator is ','", file, line)
        token = token.replace(",", ".")
    if not _NUMBER.fullmatch(token):
        raise ModelError(f"'{text.strip()}' is not a number", file, line)
    value = float(token.replace("*^", "e"))
    if not math.isfinite(value):
        raise ModelError(f"'{text.strip()}' is not a finite number", file, line)
    return value


def parse_flag(text: str, file: str | Path | None, line: int | None) -> bool:
    """A boolean written as ``1``/``0`` (also ``true``/``false``, ``T``/``F``)."""
    token = text.strip().lower()
    if token in ("1", "true", "t", "yes"):
        return True
    if token in ("0", "false", "f", "no", ""):
        return False
    raise ModelError(f"'{text.strip()}' is not a flag (use 1 for true, 0 for false)", file, line)


def parse_integer(text: str, file: str | Path | None, line: int | None) -> int:
    """A whole number (``MaxInt`` is the largest 32-bit integer, as in the original program)."""
    token = text.strip()
    if token.lower() == "maxint":
        return MAXINT
    if not re.fullmatch(r"[+-]?\d+", token):
        raise ModelError(f"'{token}' is not a whole number", file, line)
    return int(token)


MAXINT = 2**31 - 1


def format_number(value: float, separator: str = ".") -> str:
    """The shortest text that reads back as exactly ``value``."""
    text = repr(float(value))
    if text.endswith(".0") and "e" not in text:
        text = text[:-2]
    return text.replace(".", ",") if separator == "," else text


def write_atomic(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename (never half-written)."""
    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8", newline="\n") as handle:
        handle.write(text)


@contextlib.contextmanager
def atomic_path(path: str | Path):
    """A temporary path beside ``path`` to write to; renamed to ``path`` when the block ends
    normally, removed otherwise, so that ``path`` is either the old file or the whole new one."""
    path = Path(path)
    if path.is_dir():
        raise ModelError("is a folder where mbds writes a file: move it away", path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    except OSError as exc:
        raise ModelError(f"cannot write here: {exc.strerror or exc}", path) from None
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~process_umask())  # mkstemp makes it private; give it the usual permissions
        os.replace(tmp, path)
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        raise ModelError(f"cannot write the file: {exc.strerror or exc}", path) from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def process_umask() -> int:
    """The process's umask (read by setting it and setting it back)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
