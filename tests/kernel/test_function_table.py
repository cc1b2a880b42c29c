"""Functions called through a table of addresses (mbds.kernel.function_table): the kernel calls
each row's own function, and a table is refused for a function compiled for another signature."""

from types import SimpleNamespace

import numba
import numpy as np
import pytest
from mbds.kernel.function_table import address_table, function_at

SIGNATURE = "float64(float64[::1], float64)"
TWO_ROWS = {"first": SIGNATURE, "second": SIGNATURE}
_SCALED_SUM = function_at(SIGNATURE)


@numba.njit(SIGNATURE)
def _sum_times(x, c):
    return c * x.sum()


@numba.njit(SIGNATURE)
def _max_plus(x, c):
    return x.max() + c


@numba.njit
def _call_rows(table, x):
    return _SCALED_SUM(table, 0)(x, 2.0), _SCALED_SUM(table, 1)(x, 2.0)


def test_each_row_calls_its_function():
    x = np.array([1.0, 4.0, 2.0])
    table = address_table(SimpleNamespace(first=_sum_times, second=_max_plus), TWO_ROWS)
    assert _call_rows(table, x) == (14.0, 6.0)
    assert _call_rows(table[::-1].copy(), x) == (6.0, 14.0)


def test_a_function_of_another_signature_is_refused():
    other = numba.njit("float64(float64[::1], int64)")(lambda x, c: x.sum())
    with pytest.raises(TypeError, match="not compiled for"):
        address_table(SimpleNamespace(first=_sum_times, second=other), TWO_ROWS)
