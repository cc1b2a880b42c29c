"""Rest targets of dependent contact rows (mbds.kernel.redundancy): the projection is the
orthogonal one onto the range of the rows (numpy's least squares gives the same), and a group
whose rows are independent keeps its targets bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from mbds.kernel.redundancy import project_targets

TOL = 1e-10


def group(rng, n, contacts, copies, stick):
    """Rows of a group: ``contacts`` random contacts (normal and tangential rows) on n coordinates,
    then ``copies`` repeats of some of them; the first ``stick`` contacts are stick candidates.
    Returns (WN, WT, part, hrow, span, rows) with rows the R x n matrix W_R^T."""
    WN, WT = rng.standard_normal((2, contacts, n))
    pick = rng.integers(0, contacts, copies)
    WN, WT = np.vstack([WN, WN[pick]]), np.vstack([WT, WT[pick]])
    k = len(WN)
    part = rng.permutation(k)
    hrow = np.sort(rng.choice(k, min(stick, k), replace=False))
    span = np.tile(np.array([0, n]), (k, 1))
    return WN, WT, part, hrow, span, np.vstack([WN[part], WT[part[hrow]]])


def project(WN, WT, part, hrow, span, d):
    n = WN.shape[1]
    out = d.copy()
    rank = project_targets(part, len(part), len(hrow), hrow, WN, WT, span, out, TOL, np.zeros((n, n)),
                           np.zeros((2, n)), np.zeros(n, dtype=np.int64))
    return rank, out


@pytest.mark.parametrize("seed", range(12))
def test_dependent_rows_get_the_orthogonal_projection_of_their_targets(seed):
    """More rows than coordinates, or copies of contacts: the result equals W_R^T x for the
    least-squares x of W_R^T x = d, and the rank is numpy's."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 10))
    WN, WT, part, hrow, span, rows = group(rng, n, int(rng.integers(1, n)), int(rng.integers(0, 3)),
                                           int(rng.integers(0, n)))
    if np.linalg.matrix_rank(rows) == len(rows):  # make them dependent: one more contact than fits
        WN, WT, part, hrow, span, rows = group(rng, n, n, 1, n)
    d = rng.standard_normal(len(rows))
    rank, out = project(WN, WT, part, hrow, span, d)
    assert rank == np.linalg.matrix_rank(rows) < len(rows)
    x = np.linalg.lstsq(rows, d, rcond=None)[0]
    np.testing.assert_allclose(out, rows @ x, rtol=0, atol=1e-9 * np.abs(d).max())
    assert np.abs(out - d).max() > 1e-6  # the targets did not agree: something was taken off


def test_independent_rows_keep_their_targets_bit_for_bit():
    rng = np.random.default_rng(3)
    WN, WT, part, hrow, span, rows = group(rng, 8, 3, 0, 2)
    d = rng.standard_normal(len(rows))
    rank, out = project(WN, WT, part, hrow, span, d)
    assert rank == len(rows) == 5
    assert np.array_equal(out, d)


def test_targets_that_one_motion_meets_are_kept():
    """Targets d = W_R^T v (one motion v) stay as they are, to round-off, on dependent rows."""
    rng = np.random.default_rng(5)
    WN, WT, part, hrow, span, rows = group(rng, 4, 4, 1, 3)
    d = rows @ rng.standard_normal(4)
    rank, out = project(WN, WT, part, hrow, span, d)
    assert rank == 4 < len(rows)
    np.testing.assert_allclose(out, d, rtol=0, atol=1e-12 * np.abs(d).max())


def test_a_group_on_some_of_the_coordinates():
    """Rows that are zero outside columns 2 … 5 of 9 (their span): the same projection as over
    all columns."""
    rng = np.random.default_rng(11)
    WN, WT, part, hrow, span, rows = group(rng, 4, 4, 0, 2)
    pad = lambda W: np.hstack([np.zeros((len(W), 2)), W, np.zeros((len(W), 3))])  # noqa: E731
    span[:] = (2, 6)
    d = rng.standard_normal(len(rows))
    rank, out = project(pad(WN), pad(WT), part, hrow, span, d)
    assert rank == 4 < len(rows)
    np.testing.assert_allclose(out, rows @ np.linalg.lstsq(rows, d, rcond=None)[0], rtol=0, atol=1e-9)


def test_rows_without_entries_meet_only_zero_targets():
    """A group whose rows are all zero (no coordinate in their span) gets zero targets, rank 0."""
    WN, WT = np.zeros((2, 2, 3))
    span = np.zeros((2, 2), dtype=np.int64)
    rank, out = project(WN, WT, np.array([0, 1]), np.array([1]), span, np.array([1.0, -2.0, 3.0]))
    assert rank == 0
    assert np.array_equal(out, np.zeros(3))
