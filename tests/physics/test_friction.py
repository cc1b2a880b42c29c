"""Coulomb friction between impacts: a block on an incline, a block sliding to rest, and a load
dragged along by a cart.

The incline is the horizontal floor with gravity turned by the slope angle alpha:
(c'gx, c'gy) = g (sin alpha, -cos alpha), so "down the slope" is +x.

The cart (mass M) slides on a frictionless floor at v0 under a load (mass m) at rest, with
friction mu between them: the load accelerates at mu g and the cart slows at mu g m / M until
both move at the common speed M v0 / (M + m), at t* = M v0 / ((M + m) mu g); the load slips back
by M v0² / (2 mu g (M + m)) and friction dissipates M m v0² / (2 (M + m)). (Momentum
conservation and Coulomb's law; the textbook two-block problem, e.g. D. Morin, "Introduction to
Classical Mechanics", Cambridge 2008, ch. 3.)"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, FreeBody, energy_residual, rectangle, run_folder, write_free_bodies

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
MU = 0.5
WIDTH, HEIGHT, MASS = 0.1, 0.02, 1.0  # m, m, kg: flat enough never to tip
MAX_PEN = 1e-7  # m


def block(gravity, velocity=(0.0, 0.0, 0.0), break_time=0.5) -> BodyOnFloor:
    """The block resting on the floor (both bottom corners at gap 0), sampled every 1e-4 s."""
    inertia = MASS * (WIDTH**2 + HEIGHT**2) / 12.0
    return BodyOnFloor(rectangle(WIDTH, HEIGHT), MASS, inertia, position=(0.0, 0.5 * HEIGHT, 0.0), velocity=velocity,
                       gravity=gravity, friction=MU, break_time=break_time, dt_max=1e-4, max_penetration=MAX_PEN)


def incline(alpha: float) -> tuple[float, float]:
    return G * np.sin(alpha), -G * np.cos(alpha)


@pytest.mark.parametrize("slope", [0.3, 0.49])
def test_block_sticks_when_the_slope_is_within_the_friction_cone(tmp_path, slope):
    """The block may settle into the floor by up to maximumPenetration, nothing more."""
    result = run_folder(block(incline(np.arctan(slope))).write(tmp_path))
    assert np.abs(result.q[:, 0]).max() < MAX_PEN  # m
    assert np.abs(result.q[:, 1] - 0.5 * HEIGHT).max() < MAX_PEN
    assert np.abs(result.u[-1]).max() < 1e-9


@pytest.mark.parametrize("slope", [0.51, 0.7, 1.5])
def test_block_slides_down_at_g_sin_minus_mu_cos(tmp_path, slope):
    alpha = np.arctan(slope)
    result = run_folder(block(incline(alpha)).write(tmp_path))
    expected = G * (np.sin(alpha) - MU * np.cos(alpha))
    curve = np.polyfit(result.time, result.q[:, 0], 2)  # x = a t² / 2 from rest
    assert 2.0 * curve[0] == pytest.approx(expected, rel=0.005)
    assert result.u[-1, 0] == pytest.approx(expected * result.time[-1], rel=0.005)
    assert np.abs(result.q[:, 2]).max() < 2.0 * MAX_PEN / WIDTH  # no rocking beyond the penetration allowed
    # the lost work is the friction work mu N x
    assert result.lost[-1] == pytest.approx(MU * MASS * G * np.cos(alpha) * result.q[-1, 0], rel=1e-6)
    assert np.abs(energy_residual(result)).max() < 1e-9


def test_sliding_block_stops_after_v0_squared_over_2_mu_g(tmp_path):
    v0 = 1.2  # m/s
    result = run_folder(block((0.0, -G), velocity=(v0, 0.0, 0.0), break_time=0.4).write(tmp_path))
    distance = v0 * v0 / (2.0 * MU * G)
    assert result.q[:, 0].max() == pytest.approx(distance, rel=0.005)
    assert result.q[-1, 0] == pytest.approx(distance, rel=0.005)
    assert result.lost[-1] == pytest.approx(0.5 * MASS * v0 * v0, rel=1e-5)  # the kinetic energy
    assert np.abs(energy_residual(result)).max() < 1e-12


def test_sliding_block_comes_to_rest(tmp_path):
    v0 = 1.2  # m/s
    result = run_folder(block((0.0, -G), velocity=(v0, 0.0, 0.0), break_time=0.3).write(tmp_path))
    stopped = result.time > v0 / (MU * G) * 1.01
    assert np.abs(result.u[stopped, 0]).max() < 1e-6  # m/s; it chatters at about mu g dt_max / 2
    assert np.ptp(result.q[stopped, 0]) < MAX_PEN  # m; the chatter makes it creep back


def test_block_resting_on_two_corners_stays_level(tmp_path):
    result = run_folder(block(incline(np.arctan(0.3)), break_time=0.1).write(tmp_path))
    assert np.abs(result.q[:, 2]).max() < 1e-12  # rad


@pytest.mark.parametrize("dt_max, max_penetration", [(1e-4, 1e-7), (1e-3, 1e-5)])
def test_a_load_on_a_sliding_cart_reaches_the_common_speed(tmp_path, dt_max, max_penetration):
    """Fine steps, and coarse ones with the default skin: the closed form to 10⁻⁶ and better."""
    cart_mass, load_mass, v0 = 2.0, 1.0, 1.0  # kg, kg, m/s
    cart = FreeBody("box0", rectangle(0.4, 0.1), cart_mass, cart_mass * (0.4**2 + 0.1**2) / 12.0,
                    position=(0.0, 0.05, 0.0), velocity=(v0, 0.0, 0.0))
    load = FreeBody("box1", rectangle(0.1, 0.05), load_mass, load_mass * (0.1**2 + 0.05**2) / 12.0,
                    position=(0.0, 0.125, 0.0))
    folder = write_free_bodies(tmp_path / "cart", [cart, load], [("box0", "floor"), ("box1", "box0")], floor=True,
                               gravity=G, friction=MU, restitution=0.0, dt_max=dt_max,
                               max_penetration=max_penetration, break_time=0.4)
    cop = folder / "model.cop"
    cop.write_text(cop.read_text().replace("[box0-floor]\nfriction = c'mu", "[box0-floor]\nfriction = 0"))
    result = run_folder(folder)
    t, cart_speed, load_speed = result.time, result.u[:, 0], result.u[:, 3]
    common = cart_mass * v0 / (cart_mass + load_mass)
    together = common / (MU * G)
    slipping = (t > 0.01) & (t < together - 0.01)
    np.testing.assert_allclose(np.gradient(load_speed, t)[slipping], MU * G, rtol=1e-6)
    np.testing.assert_allclose(np.gradient(cart_speed, t)[slipping], -MU * G * load_mass / cart_mass, rtol=1e-6)
    after = t > together + 2.0 * dt_max
    np.testing.assert_allclose(result.u[after][:, [0, 3]], common, rtol=1e-9)
    slip = cart_mass * v0**2 / (2.0 * MU * G * (cart_mass + load_mass))
    assert result.q[-1, 3] - result.q[-1, 0] == pytest.approx(-slip, rel=1e-6)
    assert result.lost[-1] == pytest.approx(cart_mass * load_mass * v0**2 / (2.0 * (cart_mass + load_mass)), rel=1e-9)
    assert np.abs(energy_residual(result)).max() < 1e-12
    assert np.abs(result.q[:, [2, 5]]).max() < 1e-12  # rad: both stay level
    assert result.state.clock[K.IMPACTS] == 0
