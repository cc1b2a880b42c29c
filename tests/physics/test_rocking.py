"""Housner's rocking block: a rigid rectangle rocking on a rigid floor without sliding or bouncing.

Source: G. W. Housner, "The behavior of inverted pendulum structures during earthquakes",
Bulletin of the Seismological Society of America 53(2), 403-417 (1963). For a block of
half-width b and half-height h, R = sqrt(b² + h²), alpha = atan(b / h) and p² = 3g / (4R)
(the corner's moment of inertia is 4/3 m R²):

- at each impact the angular velocity drops by omega+/omega- = 1 - 3/2 sin²(alpha) (angular
  momentum about the striking corner is conserved);
- released from rest at tilt theta0, the block first strikes after a quarter period
  t = acosh(1 / (1 - theta0/alpha)) / p (linearised for slender blocks, sin(alpha - theta) =
  alpha - theta); after an impact with omega+, it rises for atanh(omega+ / (p alpha)) / p and
  falls back as long, in the same approximation.

The quarter period is also compared with the exact (non-linear) rocking equation
theta'' = -p² sin(alpha - theta), integrated by quadrature. Settings are the manual's defaults
for the skin; restitution 0 and friction 0.8 as in Housner's no-bounce, no-slip assumptions.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
DENSITY = 1000.0  # kg/m² (per unit depth)


def housner_block(tmp_path, b: float, h: float, tilt: float, break_time: float, dt_max: float = 1e-4):
    """Run a block of half-sizes b, h (m) released from rest on one bottom corner, tilted by
    ``tilt`` (rad; positive: standing on its left corner)."""
    mass = DENSITY * 4.0 * b * h
    inertia = mass * (b * b + h * h) / 3.0
    side = np.sign(tilt)
    c, s = np.cos(tilt), np.sin(tilt)
    position = (side * (c * b) - s * h, s * side * b + c * h, tilt)
    folder = BodyOnFloor(rectangle(2 * b, 2 * h), mass, inertia, position=position, friction=0.8, restitution=0.0,
                         dt_max=dt_max, max_penetration=1e-8, break_time=break_time).write(tmp_path / "block")
    return run_folder(folder)


def impacts(result) -> list[tuple[float, float, float]]:
    """(time (s), omega before, omega after (rad/s)) at every crossing of the level pose, from
    the samples either side of it."""
    theta, omega = result.q[:, 2], result.u[:, 2]
    found = []
    for k in np.flatnonzero(np.sign(theta[1:]) != np.sign(theta[:-1])) + 1:
        # the crossing time by the speed of the last sample before it
        found.append((result.time[k - 1] - theta[k - 1] / omega[k - 1], omega[k - 1], omega[k]))
    return found


def exact_quarter_period(alpha: float, p: float, tilt: float) -> float:
    """Time (s) from rest at ``tilt`` to the level pose under theta'' = -p² sin(alpha - theta),
    with theta = tilt - s² to take out the square-root singularity at the start."""
    start = abs(tilt)

    def integrand(s):
        if s == 0.0:
            return 2.0 / np.sqrt(2.0 * p * p * np.sin(alpha - start))
        drop = np.cos(alpha - start) - np.cos(alpha - start + s * s)  # (theta'/p)² / 2
        return 2.0 * s / np.sqrt(2.0 * p * p * drop)
    return quad(integrand, 0.0, np.sqrt(start), limit=200)[0]


@pytest.mark.parametrize(
    ("b", "h", "fraction"),
    [(0.1, 0.4, 0.4), (0.1, 0.4, -0.4), (0.04, 0.4, 0.8), (0.04, 0.4, -0.8), (0.08, 0.3, 0.6)],
)
def test_rocking_block_loses_housners_ratio_at_every_impact(tmp_path, b, h, fraction):
    alpha = np.arctan(b / h)
    ratio = 1.0 - 1.5 * np.sin(alpha) ** 2
    result = housner_block(tmp_path, b, h, fraction * alpha, break_time=2.6)
    found = impacts(result)
    assert len(found) >= 3
    for _, before, after in found:
        assert before * after > 0.0  # rocks on over the other corner, no bounce back
        assert after / before == pytest.approx(ratio, rel=5e-3)
    # every corner impact is counted; the pivot's drift adds counted approaches too, so the
    # count is a lower bound here
    assert result.state.clock[K.IMPACTS] >= len(found)
    assert result.q[:, 1].min() > h - 1e-7  # the centre never sinks below the level pose


@pytest.mark.parametrize(("b", "h", "fraction"), [(0.04, 0.4, 0.5), (0.04, 0.4, -0.8), (0.1, 0.4, 0.4)])
def test_rocking_periods_follow_housners_closed_form(tmp_path, b, h, fraction):
    alpha = np.arctan(b / h)
    radius = np.hypot(b, h)
    p = np.sqrt(3.0 * G / (4.0 * radius))
    tilt = fraction * alpha
    result = housner_block(tmp_path, b, h, tilt, break_time=3.0)
    found = impacts(result)
    assert len(found) >= 3
    first = found[0][0]
    assert first == pytest.approx(exact_quarter_period(alpha, p, tilt), rel=2e-3)
    slender = alpha < 0.11  # Housner's linearisation (sin x = x) holds to ~alpha² for slender blocks
    if slender:
        assert first == pytest.approx(np.arccosh(1.0 / (1.0 - abs(fraction))) / p, rel=5e-3)
        for (start, _, after), (end, _, _) in zip(found[:-1], found[1:]):
            half = 2.0 * np.arctanh(abs(after) / (p * alpha)) / p
            assert end - start == pytest.approx(half, rel=1e-2)
