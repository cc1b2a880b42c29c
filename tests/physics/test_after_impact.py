"""The step after an impact starts from the post-impact velocities.

A spinning square strikes the floor with one corner (restitution 0, friction high enough to
stick): Newton's law with e = 0 and a sticking contact makes the corner's velocity zero, so the
post-impact velocities follow from the impulse balance alone,
u+ = u- - M^-1 W^T (W M^-1 W^T)^-1 W u- (W the corner's normal and tangential rows; Pfeiffer &
Glocker, Multibody Dynamics with Unilateral Contacts, 1996, ch. 7), computed here with numpy.
After the impact the square pivots on the corner with the new angular velocity, so the contact
force it needs (its centripetal part is m omega+^2 r) depends on the post-impact state. One
step through the impact must therefore equal the same step started from (q, u+): velocity
terms, contact rows and h computed from the pre-impact velocities would differ from it by
dt/2 times the error of the start accelerations.
"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, run_folder

pytestmark = pytest.mark.physics

SIDE, MASS = 0.1, 1.0  # m, kg
INERTIA = MASS * SIDE**2 / 6.0  # kg m², centroidal
TILT = 0.3  # rad
MU = 1.0
STEP = 1e-5  # s, the one step compared (below every step limit of these states)


def lowest_corner() -> np.ndarray:
    """The lowest corner of the tilted square relative to its centre (m)."""
    c, s = np.cos(TILT), np.sin(TILT)
    world = rectangle(SIDE, SIDE) @ np.array([[c, s], [-s, c]])
    return world[np.argmin(world[:, 1])]


def plastic_sticking_impact(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Post-impact velocities (x', y', Rz') and the impulses (normal, tangential) (N s) that bring
    the corner to rest."""
    d = lowest_corner()
    W = np.array([[0.0, 1.0, d[0]], [1.0, 0.0, -d[1]]])  # normal (y), tangential (x) rows
    minv = np.diag([1.0 / MASS, 1.0 / MASS, 1.0 / INERTIA])
    impulse = np.linalg.solve(W @ minv @ W.T, -W @ u)
    return u + minv @ W.T @ impulse, impulse


def square(velocity) -> BodyOnFloor:
    d = lowest_corner()
    return BodyOnFloor(rectangle(SIDE, SIDE), MASS, INERTIA, position=(0.0, -d[1], TILT), velocity=tuple(velocity),
                       friction=MU, restitution=0.0, max_penetration=1e-7, dt_max=1e-4)


@pytest.mark.parametrize("spin", [10.0, -5.0])
def test_step_through_an_impact_equals_the_step_from_the_post_impact_state(tmp_path, spin):
    before = np.array([0.0, -0.5, spin])  # m/s, m/s, rad/s
    after, impulse = plastic_sticking_impact(before)
    assert impulse[0] > 0.0 and abs(impulse[1]) < MU * impulse[0]  # an impact that sticks
    through = run_folder(square(before).write(tmp_path / "through"), break_time=STEP)
    fresh = run_folder(square(after).write(tmp_path / "fresh"), break_time=STEP)
    assert through.state.clock[K.T] == fresh.state.clock[K.T] == STEP  # one step each, of the same size
    np.testing.assert_allclose(through.state.u, fresh.state.u, rtol=0, atol=1e-12)
    np.testing.assert_allclose(through.state.q, fresh.state.q, rtol=0, atol=1e-15)
