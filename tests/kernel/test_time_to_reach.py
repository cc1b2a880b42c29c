"""The time at which an open contact reaches its target depth (the step limit of step 6)."""

import numpy as np
import pytest

from mbds.kernel.stepper import _time_to_reach


@pytest.mark.parametrize("distance, rate, accel", [
    (1e-3, -0.5, 0.0), (1e-3, -0.5, -3.0), (1e-3, 0.5, -3.0), (1e-3, -0.5, 3.0), (1e-3, 0.5, -1e-20),
    (1e-3, -1e-12, -9.81),
])
def test_the_time_solves_the_quadratic(distance, rate, accel):
    """distance + rate t + accel t² / 2 = 0 at the first t > 0 (a separating contact whose
    deceleration is round-off small reaches it only after a very long time, never by a division
    by zero)."""
    t = _time_to_reach(distance, rate, accel)
    assert 0.0 < t < np.inf
    assert distance + rate * t + 0.5 * accel * t * t == pytest.approx(0.0, abs=1e-12 * max(1.0, abs(rate * t)))


def test_a_receding_gap_is_never_reached():
    assert _time_to_reach(1e-3, 0.5, 3.0) == np.inf
    assert _time_to_reach(1e-3, 0.5, 0.0) == np.inf
