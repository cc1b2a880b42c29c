"""A block on the floor under a horizontal force that ramps up and back down, through rest,
slip, stick and slip the other way.

Coulomb's law with one coefficient mu (the block's two bottom corners share the normal load):
the block stays at rest while |F| <= mu m g and otherwise accelerates at (F - sgn(v) mu m g)/m
(any dynamics text with Coulomb friction, e.g. Pfeiffer & Glocker, Multibody Dynamics with
Unilateral Contacts, 1996, ch. 5; Popov, Contact Mechanics and Friction, 2010, ch. 10). With the
triangular force F(t) = k min(t, 2T - t):

- rest until t1 = mu m g / k;
- slip: v = k (t - t1)² / (2m) up to T; from T on the acceleration is k (t* - t) / m with
  t* = 2T - t1, so v = vmax - k (t - t*)² / (2m) with vmax = k (T - t1)² / m;
- stick at t2 = t* + sqrt(2) (T - t1), where F = k (t1 - sqrt(2) (T - t1)) is inside the cone
  (|F| <= mu m g because T - t1 <= sqrt(2) t1);
- rest until F = -mu m g at t3 = 2T + t1, then slip backwards: v = -k (t - t3)² / (2m).

The friction work is mu m g times the path length.
"""

import numpy as np
import pytest

from mbds.kernel.contact_problem import REST_FRACTION, STICK_FRACTION, REST_RELAXATION
from tests.physics.models import BodyOnFloor, rectangle, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
MU = 0.5
WIDTH, HEIGHT, MASS = 0.1, 0.02, 1.0  # m, m, kg: flat enough never to tip under the force
RATE = 20.0  # N/s, k
PEAK = 0.5  # s, T
MAX_PEN = 1e-7  # m
T1 = MU * MASS * G / RATE
T_STAR = 2.0 * PEAK - T1
T2 = T_STAR + np.sqrt(2.0) * (PEAK - T1)
T3 = 2.0 * PEAK + T1
V_MAX = RATE * (PEAK - T1) ** 2 / MASS


def expected_velocity(t: np.ndarray) -> np.ndarray:
    """The analytic velocity (m/s) of the module docstring."""
    rising = RATE * np.clip(t - T1, 0.0, PEAK - T1) ** 2 / (2.0 * MASS)
    falling = V_MAX - RATE * (t - T_STAR) ** 2 / (2.0 * MASS)
    backwards = -RATE * (t - T3) ** 2 / (2.0 * MASS)
    return np.select([t <= PEAK, t <= T2, t <= T3], [rising, falling, 0.0], backwards)


@pytest.fixture(scope="module")
def ramp(tmp_path_factory):
    block = BodyOnFloor(rectangle(WIDTH, HEIGHT), MASS, MASS * (WIDTH**2 + HEIGHT**2) / 12.0,
                        position=(0.0, 0.5 * HEIGHT, 0.0), friction=MU, max_penetration=MAX_PEN, dt_max=1e-4,
                        history_every=10, break_time=1.5, force_x=f"{RATE!r}*Min[t, {2.0 * PEAK!r} - t]")
    return run_folder(block.write(tmp_path_factory.mktemp("ramp")))


def test_the_velocity_follows_rest_slip_stick_slip(ramp):
    t, v = ramp.time, ramp.u[:, 0]
    assert T1 < PEAK < T_STAR < T2 < T3 < t[-1]
    np.testing.assert_allclose(v, expected_velocity(t), rtol=0.0, atol=1e-3 * V_MAX)
    assert v.max() == pytest.approx(V_MAX, rel=1e-3)


def test_the_block_rests_exactly_while_the_force_is_inside_the_cone(ramp):
    t, x, v = ramp.time, ramp.q[:, 0], ramp.u[:, 0]
    before = t < T1 - 1e-3
    assert np.abs(x[before]).max() < MAX_PEN and np.abs(v[before]).max() < 1e-9
    stuck = (t > T2 + 1e-3) & (t < T3 - 1e-3)
    assert stuck.sum() > 100
    # a contact sticks once its sliding speed is below the stick threshold (STICK_FRACTION x
    # REST_FRACTION x maxPen / dt_max), and the speed left then decays with the time constant
    # REST_RELAXATION x dt_max: after 20 time constants it is gone to round-off
    assert np.abs(v[stuck]).max() < STICK_FRACTION * REST_FRACTION * MAX_PEN / 1e-4
    settled = stuck & (t > T2 + 20.0 * REST_RELAXATION * 1e-4)
    assert np.abs(v[settled]).max() < 1e-6 * REST_FRACTION * MAX_PEN / 1e-4
    assert np.ptp(x[stuck]) < 1e-3 * MAX_PEN  # m: no creep while stuck
    assert v[-1] < -0.01  # slipping backwards again at the end


def test_the_lost_work_is_the_friction_work_along_the_path(ramp):
    path = np.abs(np.diff(ramp.q[:, 0])).sum()
    assert ramp.lost[-1] == pytest.approx(MU * MASS * G * path, rel=1e-4)
