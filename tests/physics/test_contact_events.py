"""Impacts that must happen, and round-off that must not count as one.

- A block dropped flat strikes with both bottom corners at once: the simultaneous impact of
  Poisson's law (Pfeiffer and Glocker, "Multibody Dynamics with Unilateral Contacts", Wiley
  1996, ch. 7) keeps it level, and each bounce reaches e² of the previous height (the normal
  velocity is reversed and scaled by e).
- A block sliding on the floor without friction, and a block landing with e = 0, have at most
  the one impact of the landing; resting and sliding contacts log none.
- A regular polygon rolling down a slope without slipping or bouncing pivots from vertex to
  vertex; at each vertex impact the angular momentum about the new vertex is conserved, so
  omega+/omega- = (I + m R² cos 2a) / (I + m R²), 2a = 2 pi / N (the rimless wheel of
  T. McGeer, "Passive dynamic walking", Int. J. Robotics Research 9(2), 62-82, 1990), with
  I = m R² (1 + 2 cos²(pi/N)) / 6 for a uniform regular N-gon of circumradius R.
"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, regular_polygon, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
WIDTH, HEIGHT, MASS = 0.2, 0.1, 1.0  # m, m, kg
INERTIA = MASS * (WIDTH**2 + HEIGHT**2) / 12.0  # kg m²


def flat_block(**kwargs) -> BodyOnFloor:
    return BodyOnFloor(rectangle(WIDTH, HEIGHT), MASS, INERTIA, **kwargs)


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_flat_drop_stays_level_and_bounces_by_e_squared(tmp_path, e):
    drop = 0.05
    folder = flat_block(position=(0.0, 0.5 * HEIGHT + drop, 0.0), restitution=e, friction=0.5,
                        break_time=0.5).write(tmp_path / "flat")
    result = run_folder(folder)
    assert np.abs(result.q[:, 2]).max() < 1e-9
    assert np.abs(result.u[:, 2]).max() < 1e-9
    bottom = result.q[:, 1] - 0.5 * HEIGHT
    apex = bottom + 0.5 * result.u[:, 1] ** 2 / G  # constant in free flight
    flights = np.split(np.arange(len(apex)), np.flatnonzero(np.diff(result.u[:, 1]) > 0.0) + 1)
    heights = [np.median(apex[k][bottom[k] > 1e-5]) for k in flights if (bottom[k] > 1e-5).sum() > 3]
    heights = [height for height in heights if height > 1e-4]  # 1000 maxPen: the impact depth is negligible
    assert len(heights) >= 4
    assert heights[0] == pytest.approx(drop, rel=1e-6)
    for before, after in zip(heights[:-1], heights[1:]):
        assert after / before == pytest.approx(e * e, rel=1e-3)


def test_a_frictionless_sliding_block_logs_no_impact(tmp_path):
    folder = flat_block(position=(0.0, 0.5 * HEIGHT, 0.0), velocity=(1.0, 0.0, 0.0), history_each_step=True,
                        dt_max=1e-4, max_penetration=1e-8, break_time=0.05).write(tmp_path / "slide")
    result = run_folder(folder)
    assert result.state.clock[K.STEPS] >= 500
    assert result.state.clock[K.IMPACTS] == 0
    assert result.energy[-1] == pytest.approx(result.energy[0], rel=1e-12)
    assert result.u[-1, 0] == pytest.approx(1.0, rel=1e-12)


def test_a_block_landing_with_e_0_logs_one_impact_and_samples_it_once(tmp_path):
    folder = flat_block(position=(0.0, 0.5 * HEIGHT + 0.01, 0.0), velocity=(0.3, 0.0, 0.0), friction=0.3,
                        dt_max=1e-4, max_penetration=1e-8, history_every=100, break_time=0.3,
                        extra={"writeToHistoryAtCollision": "1"}).write(tmp_path / "land")
    result = run_folder(folder)
    assert result.state.clock[K.IMPACTS] == 1
    regular = np.isclose(result.time / 1e-2, np.round(result.time / 1e-2), rtol=0.0, atol=1e-6)
    assert (~regular).sum() == 1  # the one sample at the collision
    assert abs(result.u[-1, 1]) < 1e-9 and abs(result.u[-1, 0]) < 1e-9  # came to rest by friction


def test_polygon_rolling_down_a_slope_loses_the_rimless_wheel_ratio(tmp_path):
    """A 12-gon on a 0.1 rad slope: steep enough for a steady roll, the energy a step down the
    slope gains brings the wheel back over the next vertex (a hexagon there stops)."""
    sides, radius, mass, slope = 12, 0.05, 1.0, 0.1  # -, m, kg, rad
    inertia = mass * radius**2 * (1.0 + 2.0 * np.cos(np.pi / sides) ** 2) / 6.0
    ratio = (inertia + mass * radius**2 * np.cos(2.0 * np.pi / sides)) / (inertia + mass * radius**2)
    shape = regular_polygon(sides, radius)  # a vertex straight down
    apothem = radius * np.cos(np.pi / sides)
    folder = BodyOnFloor(shape, mass, inertia, position=(0.0, radius, 0.0), velocity=(6.0 * radius, 0.0, -6.0),
                         gravity=(G * np.sin(slope), -G * np.cos(slope)), friction=1.5, restitution=0.0,
                         dt_max=1e-5, max_penetration=1e-9, break_time=0.4).write(tmp_path / "wheel")
    result = run_folder(folder)
    omega = result.u[:, 2]
    jumps = np.flatnonzero(np.abs(np.diff(omega)) > 0.05 * np.abs(omega[1:])) + 1
    assert len(jumps) >= 4
    for k in jumps:
        assert omega[k] / omega[k - 1] == pytest.approx(ratio, rel=5e-3)
    assert result.q[:, 1].min() > apothem - 1e-6  # never below the flat-side height
    # every vertex impact is counted; the pivot's drift adds counted approaches too (30 for 5
    # vertices), so the count is a lower bound here
    assert result.state.clock[K.IMPACTS] >= len(jumps)
