"""A ladder sliding down a frictionless wall on a frictionless floor leaves the wall at two
thirds of its initial height.

The classic sliding-ladder problem of rigid-body mechanics texts, solved here in closed form
from the energy and the two constraints. A uniform rod of length L and centroidal inertia
m L²/12 leans at θ0 against the wall. While both ends touch, its centre moves on a circle of
radius L/2 about the corner, and energy gives θ'² = (3 g / L)(sin θ0 - sin θ). The wall pushes
while the centre's horizontal acceleration is positive, which ends at sin θ = (2/3) sin θ0; from
then on the horizontal speed of the centre is constant, (1/3) sqrt(g L) sin^(3/2) θ0.

The rod is a thin hexagon whose two ends are single vertices on its axis, so the contacts are
the ends of the ideal ladder.
"""

import numpy as np
import pytest

from tests.physics.models import FreeBody, add_fixed_body, run_folder, write_free_bodies

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
LENGTH, MASS = 1.0, 1.0  # m, kg
TAPER, HALF_THICKNESS = 0.02, 0.005  # m


def ladder(folder, tilt: float, dt_max: float, max_penetration: float):
    """The ladder released from rest at ``tilt`` (rad) from the floor, its top end on the wall
    x = 0 and its bottom end on the floor y = 0; run for 0.8 s."""
    half = 0.5 * LENGTH
    shape = np.array([[-half, 0.0], [-half + TAPER, -HALF_THICKNESS], [half - TAPER, -HALF_THICKNESS], [half, 0.0],
                      [half - TAPER, HALF_THICKNESS], [-half + TAPER, HALF_THICKNESS]])
    rod = FreeBody("rod", shape, MASS, MASS * LENGTH**2 / 12.0,
                   position=(half * np.cos(tilt), half * np.sin(tilt), -tilt))
    folder = write_free_bodies(folder, [rod], [("rod", "floor"), ("rod", "wall")], floor=True, gravity=G,
                               friction=0.0, restitution=0.0, dt_max=dt_max, max_penetration=max_penetration,
                               break_time=0.8)
    add_fixed_body(folder, "wall", np.array([[0.0, 0.0], [0.0, 2.0], [-0.1, 2.0], [-0.1, 0.0]]))
    return run_folder(folder)


def leaving_speed(tilt: float) -> float:
    """The centre's horizontal speed (m/s) once the ladder has left the wall."""
    return np.sqrt(G * LENGTH) * np.sin(tilt) ** 1.5 / 3.0


@pytest.mark.parametrize("degrees", [60.0, 80.0])
def test_the_ladder_leaves_the_wall_at_two_thirds_of_its_height(tmp_path, degrees):
    tilt = np.radians(degrees)
    result = ladder(tmp_path / "ladder", tilt, 1e-4, 1e-7)
    t, x, vx, theta, spin = result.time, result.q[:, 0], result.u[:, 0], -result.q[:, 2], -result.u[:, 2]
    top = x - 0.5 * LENGTH * np.cos(theta)  # the top end's distance from the wall (m)
    both = top < 1e-9
    assert both[0] and not both[-1]
    np.testing.assert_allclose(spin[both] ** 2, 3.0 * G / LENGTH * (np.sin(tilt) - np.sin(theta[both])),
                               rtol=1e-5, atol=1e-6)
    before_landing = t < t[~both][0] + 0.05
    speed = vx[before_landing].max()
    assert speed == pytest.approx(leaving_speed(tilt), rel=1e-5)
    plateau = np.argmax(vx >= speed * (1.0 - 1e-7))  # the wall's push ends here
    assert np.sin(theta[plateau]) == pytest.approx(2.0 / 3.0 * np.sin(tilt), rel=5e-3)


def test_coarse_steps_and_the_default_skin_keep_the_leaving_speed(tmp_path):
    tilt = np.radians(60.0)
    result = ladder(tmp_path / "coarse", tilt, 1e-3, 1e-5)
    t, vx = result.time, result.u[:, 0]
    flight = (t > 0.4) & (t < 0.5)  # off the wall, not yet lying on the floor
    np.testing.assert_allclose(vx[flight], leaving_speed(tilt), rtol=1e-4)
