"""Reader of LCP test files (dense and sparse-block)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mbds.errors import ModelError
from mbds.io.lcpfile import read_lcp

DATA = Path(__file__).resolve().parents[2].parent / "shared" / "testdata" / "lcp"
needs_data = pytest.mark.skipif(not DATA.is_dir(), reason=f"peer LCP collection not found at {DATA}")

ORTIZ_BLOCK = """4
1
4 4
4
2
2
2 4
2 4
3
4
0 2 4
0 1 0 1
0
3 -1 1 2
1
0 1 -1 1
2
0 0 1 0
3
3 1 -1 2
-2 1 0 3
comment
"""


@needs_data
@pytest.mark.parametrize("name", ["lcp_ortiz", "lcp_deudeu", "lcp_trivial"])
def test_dense_and_block_files_agree(name):
    M, q = read_lcp(DATA / "siconos" / f"{name}.dat")
    Mb, qb = read_lcp(DATA / "siconos" / f"{name}_block.dat")
    np.testing.assert_array_equal(M, Mb)
    np.testing.assert_array_equal(q, qb)
    assert M.dtype == q.dtype == np.float64 and M.flags.c_contiguous


@needs_data
def test_dense_values_are_column_major_and_comment_ignored():
    M, q = read_lcp(DATA / "siconos" / "lcp_exp_murty2.dat")
    expected = np.triu(np.full((6, 6), 2.0), 1) + np.eye(6)
    np.testing.assert_array_equal(M, expected)
    np.testing.assert_array_equal(q, [-126, -124, -120, -112, -96, -64])


@needs_data
def test_every_peer_file_parses():
    for path in sorted(DATA.glob("siconos*/*.dat")):
        M, q = read_lcp(path)
        assert M.shape == (q.size, q.size) and np.isfinite(M).all()


def test_block_layout(tmp_path):
    path = tmp_path / "ortiz_block.dat"
    path.write_text(ORTIZ_BLOCK)
    M, q = read_lcp(path)
    expected = np.array([[3, 1, 0, -1], [-1, 2, 1, 1], [0, 1, 3, -1], [0, 0, 1, 2]], dtype=float)
    np.testing.assert_array_equal(M, expected)
    np.testing.assert_array_equal(q, [-2, 1, 0, 3])


def test_missing_blocks_are_zero(tmp_path):
    # 2 x 2 block-diagonal layout with only the (1, 1) block given
    path = tmp_path / "sparse.dat"
    path.write_text("2 1 2 2 1 2 2 1 2 1 2 3 1 0 0 1 1 0 5 -1 -1")
    M, q = read_lcp(path)
    np.testing.assert_array_equal(M, [[0, 0], [0, 5]])
    np.testing.assert_array_equal(q, [-1, -1])


@pytest.mark.parametrize(
    "text, line, message",
    [
        ("", None, "unexpected end of file"),
        ("2\n0\n2 2\n2 2\n1 0\n0 1\n-1\n", 7, "unexpected end of file, expected value of q"),
        ("2\n0\n2 2\n2 2\n1 x\n0 1\n-1 -1\n", 5, "expected a number, got 'x'"),
        ("2\n0\n2 2\n2 2\n1 nan\n0 1\n-1 -1\n", 5, "not finite"),
        ("two\n", 1, "expected an integer"),
        ("0\n", 1, "size n: 0 is not >= 1"),
        ("2\n3\n", 2, "storage type"),
        ("2\n0\n3 2\n", 3, "number of rows 3 differs from n = 2"),
        ("2 1 2 2 1 1 1 2 3", 1, "block column boundary: 3 is not in 1 .. 2"),
        ("2 1 2 2 1 1 1 1 2 2 1 0 1 0 0 1 0 0 1", 1, "last block row boundary is 1, not n = 2"),
        ("2 1 2 2 1 1 1 2 2 2 1 0 1 0 1 1 0 0 1 -1 -1", 1, "block number 1 found where block 0"),
        ("2 1 2 2 1 1 1 2 2 2 1 0 0 0 0 1 0 0 1 -1 -1", 1, "block row pointers"),
    ],
)
def test_malformed_input_raises_model_error(tmp_path, text, line, message):
    path = tmp_path / "bad.dat"
    path.write_text(text)
    with pytest.raises(ModelError) as info:
        read_lcp(path)
    assert info.value.file == str(path)
    assert info.value.line == line
    assert message in info.value.message


def test_unreadable_file_raises_model_error(tmp_path):
    with pytest.raises(ModelError, match="cannot read"):
        read_lcp(tmp_path / "missing.dat")
