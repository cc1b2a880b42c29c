"""Watch post-processing: each [common] option of the .wtc file changes the series as documented."""

import numpy as np
import pytest

from mbds.data.watches import (
    distinct_points,
    smooth_points,
    watch_series,
)
from mbds.kernel.layout import ANGLE, IMP_N, IMP_T, IMP_X, IMP_Y, POINT_COLUMNS, WORK
from mbds.model.geometry import smooth_closed
from mbds.model.system import WatchOptions

INTERVALS = np.array([0.0, 0.5, 0.5, 1.0])


@pytest.fixture
def sums():
    """4 samples, 2 watches (the second an x-y watch)."""
    s = np.zeros((4, 2, POINT_COLUMNS))
    s[:, :, IMP_N] = [[0, 1], [2, 0], [0, 0], [4, 2]]
    s[:, :, IMP_T] = [[0, 0], [1, 0], [0, 0], [-1, 1]]
    s[:, :, IMP_X] = [[0, 3], [0, 0], [0, 0], [0, 1]]
    s[:, :, IMP_Y] = [[0, 6], [0, 0], [0, 0], [0, 4]]
    s[:, :, WORK] = [[0, 1], [3, 0], [0, 0], [1, 2]]
    s[:, :, ANGLE] = [[0, 0.5], [1.5, 0.5], [1.5, 0.5], [2.0, -1.0]]
    return s


def test_defaults_pass_the_interval_sums_through(sums):
    out = watch_series(sums, INTERVALS, WatchOptions())
    for name, column in (("normal", IMP_N), ("tangential", IMP_T), ("x", IMP_X), ("y", IMP_Y)):
        np.testing.assert_array_equal(out.impulse[name], sums[:, :, column])
    np.testing.assert_array_equal(out.work, sums[:, :, WORK])
    assert out.angle is None and out.t_div_n is None and not out.force


def test_convert_impulse_to_force_divides_by_the_interval(sums):
    out = watch_series(sums, INTERVALS, WatchOptions(convert_impulse_to_force=True))
    assert out.force
    np.testing.assert_array_equal(out.impulse["normal"][:, 0], [0, 4, 0, 4])  # empty first interval -> 0
    np.testing.assert_array_equal(out.impulse["y"][:, 1], [0, 0, 0, 4])


def test_time_constant_decays_between_samples(sums):
    tau = 0.25
    out = watch_series(sums, INTERVALS, WatchOptions(time_constant=tau))
    y = out.impulse["normal"][:, 0]
    assert y[1] == 2
    assert y[2] == pytest.approx(2 * np.exp(-0.5 / tau))
    assert y[3] == pytest.approx(y[2] * np.exp(-1.0 / tau) + 4)


def test_force_then_decay(sums):
    out = watch_series(sums, INTERVALS, WatchOptions(time_constant=1.0, convert_impulse_to_force=True))
    y = out.impulse["normal"][:, 0]
    assert y[3] == pytest.approx(4 * np.exp(-0.5) * np.exp(-1.0) + 4)


def test_cumulative_work(sums):
    out = watch_series(sums, INTERVALS, WatchOptions(cumulative_work=True))
    np.testing.assert_array_equal(out.work[:, 0], [0, 3, 3, 4])
    np.testing.assert_array_equal(out.work[:, 1], [1, 1, 1, 3])


def test_angle_instead_of_work(sums):
    out = watch_series(sums, INTERVALS, WatchOptions(absolute_angle_instead_of_work=True))
    assert out.work is None
    np.testing.assert_array_equal(out.angle, sums[:, :, ANGLE])


def test_averaged_t_div_n_is_the_running_ratio_of_tangential_to_normal_impulse(sums):
    out = watch_series(sums, INTERVALS, WatchOptions(write_averaged_t_div_n=True))
    nt = out.t_div_n[:, 0]
    assert nt[0] == 0.0  # no normal impulse yet: 0, not 0/0
    np.testing.assert_allclose(nt[1:], [0.5, 0.5, 0.0])  # (1 + 0 - 1) / (2 + 0 + 4)
    # an x-y watch gives the same ratio of its normal and tangential sums: the frame the watch
    # writes its impulses in does not change the friction ratio
    np.testing.assert_allclose(out.t_div_n[:, 1], [0.0, 0.0, 0.0, 1 / 3])


def test_distinct_points_drop_the_closing_points():
    values = np.array([1.0, 2.0, 3.0, 0.0, 5.0, 6.0, 7.0, 8.0, 0.0])  # bodies of 3 and 4 distinct points
    distinct = distinct_points(values, np.array([0, 4, 9]))
    np.testing.assert_array_equal(distinct, [1.0, 2.0, 3.0, 5.0, 6.0, 7.0, 8.0])


def test_smoothing_is_a_wrapping_centred_moving_average():
    values = np.array([6.0, 0, 0, 0, 0, 3.0])
    np.testing.assert_allclose(smooth_closed(values, 1), [3, 2, 0, 0, 1, 3])
    assert smooth_closed(values, 1).sum() == pytest.approx(values.sum())  # nothing is lost
    np.testing.assert_array_equal(smooth_closed(values, 0), values)
    np.testing.assert_allclose(smooth_closed(values, 3), np.full(6, 1.5))  # window covers the shape


def test_smoothing_stays_within_each_body():
    values = np.array([3.0, 0, 0, 9.0, 0, 0, 0])
    out = smooth_points(values, np.array([0, 3, 7]), 1)
    np.testing.assert_allclose(out[:3], [1, 1, 1])
    np.testing.assert_allclose(out[3:], [3, 3, 0, 3])
