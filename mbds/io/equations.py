"""Files of the equations of motion: mass matrix (``.mmx``), h-vector (``.hv``) and mechanical
energy (``.me``); their entries are expressions, kept as text with their lines."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.ini import Located
from mbds.io.text import significant_lines

_BINARY = "+-*/^"


@dataclass
class ExpressionsFile:
    """One expression per line: the h-vector (n entries) or the mechanical energy (1 entry)."""

    expressions: list[Located] = field(default_factory=list)
    path: Path | None = field(default=None, compare=False)


def parse_expressions(text: str, path: str | Path | None = None, count: int | None = None) -> ExpressionsFile:
    """Expressions, one a line; with ``count``, exactly that many are required."""
    expressions = [Located(line.text, line.number) for line in significant_lines(text, path)]
    if count is not None and len(expressions) != count:
        last = expressions[-1].line if expressions else 1
        raise ModelError(f"expected {count} expressions (one a line), found {len(expressions)}", path, last)
    return ExpressionsFile(expressions, Path(path) if path else None)


def parse_energy(text: str, path: str | Path | None = None) -> ExpressionsFile:
    """The mechanical energy: the expression on the first line (later lines are ignored)."""
    lines = significant_lines(text, path)
    return ExpressionsFile([Located(lines[0].text, lines[0].number)] if lines else [], Path(path) if path else None)


def format_expressions(f: ExpressionsFile) -> str:
    return "".join(f"{e.text}\n" for e in f.expressions)


@dataclass
class MatrixFile:
    """The mass matrix: n rows of n expressions."""

    rows: list[list[Located]] = field(default_factory=list)
    path: Path | None = field(default=None, compare=False)


def split_row(text: str) -> list[str]:
    """Entries of a matrix row: TAB-separated, or else separated by spaces between operands.

    Without TABs, a space separates two entries unless it is inside brackets or next to a binary
    operator; a row written with implicit multiplication by space therefore needs TABs.
    """
    if "\t" in text:
        return [part.strip() for part in text.split("\t") if part.strip()]
    chunks: list[str] = []
    depth = 0
    current = ""
    for token in text.split():
        joins = bool(chunks or current) and (
            depth > 0 or current[-1:] in _BINARY + "([,;" or token[0] in "+*/^)]"
        )
        if current and not joins:
            chunks.append(current)
            current = token
        else:
            current = f"{current} {token}" if current else token
        depth += sum(token.count(c) for c in "([") - sum(token.count(c) for c in ")]")
    if current:
        chunks.append(current)
    return chunks


def parse_matrix(text: str, path: str | Path | None = None, size: int | None = None) -> MatrixFile:
    """The n x n mass matrix: n lines of n entries, or n*n lines of one entry each."""
    lines = significant_lines(text, path)
    n = size if size is not None else len(lines)
    if size is not None and len(lines) == n * n and n > 1:
        rows = [[Located(line.text, line.number) for line in lines[i * n : (i + 1) * n]] for i in range(n)]
        return MatrixFile(rows, Path(path) if path else None)
    if len(lines) != n:
        last = lines[-1].number if lines else 1
        raise ModelError(f"the mass matrix needs {n} rows (one a line), found {len(lines)}", path, last)
    rows = []
    for line in lines:
        entries = split_row(line.text)
        if len(entries) != n:
            raise ModelError(
                f"row has {len(entries)} entries, expected {n} (separate entries with TABs)", path, line.number
            )
        rows.append([Located(e, line.number) for e in entries])
    return MatrixFile(rows, Path(path) if path else None)


def format_matrix(m: MatrixFile) -> str:
    return "".join("\t".join(e.text for e in row) + "\n" for row in m.rows)
