"""Reader of LCP test files (dense and sparse-block storage).

The file is a stream of whitespace-separated tokens: ``n``; the storage type (0 dense,
1 sparse block); the matrix; ``n`` values of q; anything after is a free comment.

- Dense: ``nrows ncols`` twice, then nrows*ncols values in column-major order.
- Sparse block: ``nrows ncols`` once; ``nbblocks nblockrows nblockcols``; the cumulative row
  boundaries of the block rows (``nblockrows`` integers) and of the block columns
  (``nblockcols``); ``filled1 filled2``; ``filled1`` CSR row pointers (block row i holds blocks
  ptr[i] .. ptr[i+1]-1) and ``filled2`` block-column indices; then each block in order: its
  number, then its values in column-major order. Missing blocks are zero.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mbds.errors import ModelError


class _Tokens:
    """Tokens of a text with their 1-based line numbers, read front to back."""

    def __init__(self, text: str, file: str):
        self.file = file
        self.items = [(tok, no) for no, line in enumerate(text.splitlines(), 1) for tok in line.split()]
        self.pos = 0
        self.line: int | None = None  # line of the last token read

    def error(self, message: str, line: int | None = None) -> ModelError:
        return ModelError(message, self.file, line)

    def next(self, what: str) -> tuple[str, int]:
        if self.pos >= len(self.items):
            last = self.items[-1][1] if self.items else None
            raise self.error(f"unexpected end of file, expected {what}", last)
        tok, self.line = self.items[self.pos]
        self.pos += 1
        return tok, self.line

    def int(self, what: str, low: int = 0, high: int | None = None) -> int:
        tok, line = self.next(what)
        try:
            value = int(tok)
        except ValueError:
            raise self.error(f"{what}: expected an integer, got {tok!r}", line) from None
        if value < low or (high is not None and value > high):
            bounds = f">= {low}" if high is None else f"in {low} .. {high}"
            raise self.error(f"{what}: {value} is not {bounds}", line)
        return value

    def float(self, what: str) -> float:
        tok, line = self.next(what)
        try:
            value = float(tok)
        except ValueError:
            raise self.error(f"{what}: expected a number, got {tok!r}", line) from None
        if not np.isfinite(value):
            raise self.error(f"{what}: {tok!r} is not finite", line)
        return value

    def floats(self, count: int, what: str) -> np.ndarray:
        return np.array([self.float(what) for _ in range(count)], dtype=np.float64)


def read_lcp(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Read an LCP file; return M (n, n) and q (n,), float64. Raises ModelError if malformed."""
    path = Path(path)
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise ModelError(f"cannot read LCP file: {exc}", path) from None
    tokens = _Tokens(text, str(path))
    n = tokens.int("size n", low=1)
    storage = tokens.int("storage type (0 dense, 1 sparse block)", low=0, high=1)
    _sizes(tokens, n)
    if storage == 0:
        _sizes(tokens, n)
        M = np.ascontiguousarray(tokens.floats(n * n, "matrix value").reshape((n, n), order="F"))
    else:
        M = _blocks(tokens, n)
    q = tokens.floats(n, "value of q")
    return M, q


def _sizes(tokens: _Tokens, n: int) -> None:
    """Read ``nrows ncols``; both must equal n."""
    for what in ("number of rows", "number of columns"):
        value = tokens.int(what)
        if value != n:
            raise tokens.error(f"{what} {value} differs from n = {n}", tokens.line)


def _boundaries(tokens: _Tokens, count: int, n: int, what: str) -> np.ndarray:
    """Cumulative boundaries 0 < b_0 < ... < b_{count-1} = n, returned with a leading 0."""
    bounds = [0]
    for _ in range(count):
        value = tokens.int(what, low=1, high=n)
        if value <= bounds[-1]:
            raise tokens.error(f"{what} {value} does not increase", tokens.line)
        bounds.append(value)
    if bounds[-1] != n:
        raise tokens.error(f"last {what} is {bounds[-1]}, not n = {n}", tokens.line)
    return np.array(bounds)


def _blocks(tokens: _Tokens, n: int) -> np.ndarray:
    """Read the sparse-block part of the matrix (after the sizes); return the dense M."""
    nblocks = tokens.int("number of blocks", low=1)
    nbrows = tokens.int("number of block rows", low=1, high=n)
    nbcols = tokens.int("number of block columns", low=1, high=n)
    rows = _boundaries(tokens, nbrows, n, "block row boundary")
    cols = _boundaries(tokens, nbcols, n, "block column boundary")
    filled1 = tokens.int("filled1", low=nbrows + 1, high=nbrows + 1)
    filled2 = tokens.int("filled2", low=nblocks, high=nblocks)
    ptr = [tokens.int("block row pointer", low=0, high=nblocks) for _ in range(filled1)]
    if ptr[0] != 0 or ptr[-1] != nblocks or any(b < a for a, b in zip(ptr, ptr[1:])):
        raise tokens.error(f"block row pointers {ptr} are not 0 .. {nblocks} nondecreasing", tokens.line)
    bcol = [tokens.int("block column index", low=0, high=nbcols - 1) for _ in range(filled2)]
    M = np.zeros((n, n))
    seen = set()
    for brow in range(nbrows):
        for block in range(ptr[brow], ptr[brow + 1]):
            number = tokens.int("block number")
            if number != block:
                message = f"block number {number} found where block {block} was expected"
                raise tokens.error(message, tokens.line)
            bc = bcol[block]
            if (brow, bc) in seen:
                raise tokens.error(f"block ({brow}, {bc}) is given twice", tokens.line)
            seen.add((brow, bc))
            r0, r1, c0, c1 = rows[brow], rows[brow + 1], cols[bc], cols[bc + 1]
            values = tokens.floats((r1 - r0) * (c1 - c0), "block value")
            M[r0:r1, c0:c1] = values.reshape((r1 - r0, c1 - c0), order="F")
    return M
