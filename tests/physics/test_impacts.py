"""Impacts against closed-form results: bounce heights, energy, the loss of one impact and an
oblique impact with friction. Gravity is (c'gx, c'gy); see :mod:`tests.physics.models`."""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import (
    BodyOnFloor,
    energy_residual,
    rectangle,
    regular_polygon,
    run_folder,
)

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
RADIUS = 0.05  # m, circumradius of the polygon ball
BALL_MASS = 1.0  # kg
DROP = 0.2  # m, height of the lowest vertex at the start


def ball(e: float, break_time: float, **world) -> BodyOnFloor:
    """A 64-sided polygon ball, vertex down and without spin, dropped from DROP onto the floor."""
    shape = regular_polygon(64, RADIUS)
    return BodyOnFloor(shape, BALL_MASS, 0.5 * BALL_MASS * RADIUS**2, position=(0.0, RADIUS + DROP, 0.0),
                       restitution=e, break_time=break_time, **world)


def apex_heights(result) -> np.ndarray:
    """Height (m) of the lowest vertex at the top of each flight: y + v²/(2g) - R is constant in
    free flight, so every sample of a flight gives it; flights are split at upward jumps of v."""
    y, v = result.q[:, 1], result.u[:, 1]
    impacts = np.flatnonzero(np.diff(v) > 0.0) + 1
    heights = []
    for start, stop in zip(np.r_[0, impacts], np.r_[impacts, len(v)]):
        flying = y[start:stop] - RADIUS > 1e-5
        if flying.any():
            heights.append(np.median((y + 0.5 * v * v / G - RADIUS)[start:stop][flying]))
    return np.array(heights)


@pytest.mark.parametrize("e", [0.8, 0.5])
def test_bounce_heights_shrink_by_restitution_squared(tmp_path, e):
    result = run_folder(ball(e, 1.5).write(tmp_path))
    heights = apex_heights(result)
    assert heights[0] == pytest.approx(DROP, rel=1e-9)
    ratios = heights[1:] / heights[:-1]
    relevant = ratios[heights[1:] > 1e-3]  # bounces well above the allowed penetration
    assert len(relevant) >= 3
    np.testing.assert_allclose(relevant, e * e, rtol=0.01)
    assert np.abs(result.q[:, 2]).max() < 1e-6  # a vertex under the centre: no spin
    assert np.abs(energy_residual(result)).max() < 1e-9 * result.energy[0]


def test_elastic_bounces_keep_the_mechanical_energy(tmp_path):
    result = run_folder(ball(1.0, 4.2).write(tmp_path))
    assert len(apex_heights(result)) >= 11  # ten impacts
    drift = np.abs(result.energy / result.energy[0] - 1.0)
    assert drift.max() < 1e-3
    assert result.lost[-1] == pytest.approx(0.0, abs=1e-6 * result.energy[0])


def test_fast_ball_does_not_pass_the_skin_with_the_default_factor(tmp_path):
    result = run_folder(ball(0.8, 1.2, displacement_factor=0.5).write(tmp_path))
    lowest = result.q[:, 1] - RADIUS
    assert lowest.min() > -2e-7  # twice maximumPenetration


def corner_drop(e: float, tilt: float, speed: float, gap: float = 1e-3, after: float = 2e-3) -> tuple[BodyOnFloor, float]:
    """A 0.1 m x 0.04 m block, 2 kg, turned by ``tilt`` (rad), moving straight down at ``speed``
    (m/s) without gravity, its lowest corner ``gap`` (m) above the floor, run ``after`` (s)
    past the impact. Returns the model and the horizontal lever arm (m) of that corner."""
    shape = rectangle(0.1, 0.04)
    c, s = np.cos(tilt), np.sin(tilt)
    world = shape @ np.array([[c, s], [-s, c]])
    lowest = world[np.argmin(world[:, 1])]
    mass, inertia = 2.0, 2.0 * (0.1**2 + 0.04**2) / 12.0
    model = BodyOnFloor(shape, mass, inertia, position=(0.0, gap - lowest[1], tilt), velocity=(0.0, -speed, 0.0),
                        gravity=(0.0, 0.0), restitution=e, break_time=gap / speed + after, max_penetration=1e-8,
                        dt_max=1e-5, history_each_step=True)
    return model, lowest[0]


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_one_frictionless_impact_loses_half_meff_gamma_squared(tmp_path, e):
    speed, tilt = 1.5, 0.3
    model, arm = corner_drop(e, tilt, speed)
    result = run_folder(model.write(tmp_path))
    m_eff = 1.0 / (1.0 / model.mass + arm**2 / model.inertia)
    expected = 0.5 * m_eff * speed**2 * (1.0 - e * e)
    assert result.lost[-1] == pytest.approx(expected, rel=1e-9, abs=1e-12)
    # after the impact the corner separates at e times the approach speed
    vy, omega = result.u[-1, 1], result.u[-1, 2]
    assert vy + omega * arm == pytest.approx(e * speed, rel=1e-9, abs=1e-9)
    assert np.abs(energy_residual(result)).max() < 1e-12


@pytest.mark.parametrize("tangential", [2.0, 0.2])
def test_oblique_impact_of_a_flat_block_with_friction(tmp_path, tangential):
    """A block (half-width a, half-height b) lands flat on both bottom corners at (v_t, -v_n).
    Compression ends with both corners at rest normally, so the normal impulses balance the
    friction impulse's moment: N2 - N1 = -b T / a. If v_t > mu (1 + e) v_n the corners slide
    through the impact: T = -mu N in both phases, the moments cancel, the block leaves without
    spin and v_t drops by mu (1 + e) v_n. Otherwise compression ends in stick (T = -m v_t); the
    expansion impulses e N1, e N2 then turn the block, and keeping the corners' tangential
    velocity v_x + omega b at zero gives omega = e b m v_t / (J + m b²) and v_x = -b omega."""
    mu, e, normal, mass, a, b = 0.3, 0.5, 1.0, 1.0, 0.05, 0.01
    inertia = mass * ((2 * a) ** 2 + (2 * b) ** 2) / 12.0
    model = BodyOnFloor(rectangle(2 * a, 2 * b), mass, inertia, position=(0.0, b + 1e-3, 0.0),
                        velocity=(tangential, -normal, 0.0), gravity=(0.0, 0.0), friction=mu, restitution=e,
                        break_time=2e-3, max_penetration=1e-8, dt_max=1e-5)
    result = run_folder(model.write(tmp_path))
    if tangential > mu * (1.0 + e) * normal:
        expected = (tangential - mu * (1.0 + e) * normal, e * normal, 0.0)
    else:
        omega = e * b * mass * tangential / (inertia + mass * b * b)
        expected = (-b * omega, e * normal, omega)
    np.testing.assert_allclose(result.u[-1], expected, rtol=1e-9, atol=1e-12)
    vx, vy, omega = expected
    lost = 0.5 * mass * (tangential**2 + normal**2 - vx**2 - vy**2) - 0.5 * inertia * omega**2
    assert result.lost[-1] == pytest.approx(lost, rel=1e-9)


def test_going_back_after_lcp_failures(tmp_path):
    """With a pivot limit too small for the contact LCPs, every contact step fails; with
    TryToSolveByGoingBack the stepper returns two steps, halves the step and tries again (down to
    the minimum step, then goes on without contact forces). The run still ends at its break time
    with increasing sample times, and takes a different path than without going back."""
    def run(going_back):
        model = ball(0.5, 0.3)
        model.extra = {"TryToSolveByGoingBack": "1" if going_back else "0"}
        model.dt_min = 1e-6
        return run_folder(model.write(tmp_path / f"back{going_back}"), 0.4, max_pivots=1)

    plain, back = run(False), run(True)
    for result in (plain, back):
        assert result.complete and result.time[-1] == pytest.approx(0.4)
        assert np.all(np.diff(result.time) > 0)
        assert result.state.clock[K.LCP_FAILURES] > 0
    assert back.state.clock[K.STEPS] > plain.state.clock[K.STEPS]  # the steps gone back are taken again


@pytest.mark.parametrize("max_penetration", [1e-3, 2e-3])
def test_a_floor_thinner_than_the_default_skin_bounces_the_ball(tmp_path, max_penetration):
    """The default skin (100 maximumPenetration: 0.1 and 0.2 m) is as thick as the floor block
    (0.1 m) or thicker, so a vertex on the floor's top face also lies within the skin of its
    bottom face, seen from inside. Only the nearest face is in contact: the bounces shrink by e²
    as on a thick floor (the first impact used to be plastic here: the ball stopped dead)."""
    result = run_folder(ball(0.8, 1.5, max_penetration=max_penetration).write(tmp_path))
    heights = apex_heights(result)
    relevant = (heights[1:] / heights[:-1])[heights[1:] > 20 * max_penetration]
    assert len(relevant) >= 3
    np.testing.assert_allclose(relevant, 0.64, rtol=0.02)
    assert result.q[:, 1].min() > RADIUS - 2 * max_penetration  # never sinks into the floor
