"""data.txt and watches.txt tables: what numpy.savetxt writes with the same format, zeros,
signed zeros and non-finite values included."""

import io

import numpy as np

from mbds.data.legacy import NUMBER, _table


def test_tables_are_what_savetxt_writes():
    rng = np.random.default_rng(7)
    values = rng.normal(size=(50, 9)) * 10.0 ** rng.integers(-12, 12, size=(50, 9))
    values[rng.random((50, 9)) < 0.8] = 0.0
    values[0, :4] = [-0.0, np.nan, np.inf, -np.inf]
    expected = io.StringIO()
    np.savetxt(expected, values, fmt=NUMBER, delimiter=" ")
    assert _table(values) == expected.getvalue()
    assert _table(values).splitlines()[0].split()[:4] == ["-0", "nan", "inf", "-inf"]
