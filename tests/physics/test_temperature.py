"""Contact temperatures (an mbds extension, docs/theory.md "Contact temperature"): the energy lost
at a contact heats its points, which relax towards initialTemperature.

Model (per shape point p of a body whose contact pair has ``heatCapacity`` C > 0 and
``coolingTime`` tau): dT_p/dt = P_p / (2 C) - (T_p - T_0) / tau, where P_p is the power lost at
the contacts booked on p (the vertex takes all of a contact's loss, the edge's two points share
it). Over the points of one body the booked powers add up to the power lost, P, so the excess
temperatures add up to the solution of the linear equation: for constant P,
sum_p (T_p - T_0) = P tau / (2 C) (1 - exp(-t / tau)); with no heating they decay as
exp(-t / tau); with tau = 0 (no cooling) they add up to the energy lost / (2 C)."""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
WIDTH, HEIGHT, MASS = 0.1, 0.02, 1.0  # m, m, kg
AMBIENT = 20.0  # °C
CAPACITY = 0.003  # J/°C


def block(folder, friction, gravity=(0.0, -G), velocity=(0.0, 0.0, 0.0), break_time=0.5, heat=None):
    """The block of tests/physics/test_friction.py, its pair with the heat keys ``heat``."""
    inertia = MASS * (WIDTH**2 + HEIGHT**2) / 12.0
    model = BodyOnFloor(rectangle(WIDTH, HEIGHT), MASS, inertia, position=(0.0, 0.5 * HEIGHT, 0.0), velocity=velocity,
                        gravity=gravity, break_time=break_time, dt_max=1e-4, max_penetration=1e-7).write(folder)
    cop = model / "model.cop"
    keys = {"initialTemperature": AMBIENT, "heatCapacity": CAPACITY, **(heat or {})}
    text = cop.read_text().replace("friction = c'mu", f"friction = {friction}")
    cop.write_text(text + "".join(f"{key} = {value!r}\n" for key, value in keys.items()))
    return model


def block_temperatures(result) -> np.ndarray:
    """(samples, 4): the temperatures of the block's four corners (one watch per point)."""
    return result.watches[:, :4, K.TEMP]


def test_constant_sliding_power_heats_to_p_tau_over_2c(tmp_path):
    """On a slope of exactly tan(alpha) = mu the block slides at constant speed, losing
    P = mu m g cos(alpha) v0; the corners' excess temperatures add up to
    P tau / (2 C) (1 - exp(-t / tau))."""
    mu, v0, tau = 0.3, 0.5, 0.2
    alpha = np.arctan(mu)
    gravity = (G * np.sin(alpha), -G * np.cos(alpha))
    result = run_folder(block(tmp_path, mu, gravity, (v0, 0.0, 0.0), 0.6, {"coolingTime": tau}))
    assert np.abs(result.u[:, 0] - v0).max() < 1e-9  # the speed stays v0
    power = mu * MASS * G * np.cos(alpha) * v0
    expected = power * tau / (2.0 * CAPACITY) * (1.0 - np.exp(-result.time / tau))
    excess = (block_temperatures(result) - AMBIENT).sum(axis=1)
    assert excess[-1] > 0.9 * power * tau / (2.0 * CAPACITY)
    np.testing.assert_allclose(excess[1:], expected[1:], rtol=2e-3)


def test_without_cooling_the_heat_is_the_energy_lost(tmp_path):
    """coolingTime 0 (no cooling): a block sliding to rest from v0 holds m v0² / 2 as heat, half
    of it in its own points: sum (T_p - T_0) = m v0² / (4 C)."""
    v0 = 1.2
    result = run_folder(block(tmp_path, 0.5, velocity=(v0, 0.0, 0.0), break_time=0.3))
    excess = (block_temperatures(result) - AMBIENT).sum(axis=1)
    assert excess[-1] == pytest.approx(0.5 * MASS * v0 * v0 / (2.0 * CAPACITY), rel=1e-5)
    assert np.all(np.diff(excess) >= -1e-12)  # it never cools
    assert result.lost[-1] == pytest.approx(0.5 * MASS * v0 * v0, rel=1e-5)


def test_a_block_at_rest_cools_exponentially(tmp_path):
    """Once the block has stopped, the corners' excess temperature decays as exp(-t / tau)."""
    v0, mu, tau = 1.2, 0.5, 0.05
    result = run_folder(block(tmp_path, mu, velocity=(v0, 0.0, 0.0), break_time=0.5, heat={"coolingTime": tau}))
    rest = result.time > v0 / (mu * G) * 1.05
    t, excess = result.time[rest], (block_temperatures(result)[rest] - AMBIENT).sum(axis=1)
    assert excess[0] > 1.0  # °C
    np.testing.assert_allclose(excess / excess[0], np.exp(-(t - t[0]) / tau), rtol=1e-6)


def test_friction_falls_as_the_block_heats(tmp_path):
    """friction = 0.3 - 0.001 * temp (initialTemperature 0): a contact's temperature is the mean
    of its corner's and of the floor's, which lies between T_corner / 2 and T_corner, so the
    deceleration a of the sliding block lies between (0.3 - 0.001 T_hotter) g and
    (0.3 - 0.0005 T_cooler) g of its two bottom corners (up to the one step by which the law's
    temperature lags), and falls from 0.3 g as the block heats."""
    v0 = 1.2
    model = block(tmp_path, "0.3-0.001*temp", velocity=(v0, 0.0, 0.0), break_time=0.6,
                  heat={"initialTemperature": 0.0})
    result = run_folder(model)
    sliding = result.u[:, 0] > 0.05
    deceleration = -result.a[sliding, 0] / G
    cooler, hotter = np.sort(block_temperatures(result)[sliding], axis=1)[:, -2:].T  # the bottom corners
    assert deceleration[1] == pytest.approx(0.3, abs=1e-3)
    assert cooler[-1] > 20.0  # °C
    assert np.all(deceleration[1:] >= 0.3 - 0.001 * hotter[1:] - 1e-4)
    assert np.all(deceleration[1:] <= 0.3 - 0.0005 * cooler[1:] + 1e-4)
    assert deceleration[-1] < 0.3 - 0.01
    # it slides farther than at a constant 0.3: v0² / (2 * 0.3 g)
    assert result.q[:, 0].max() > 1.05 * v0 * v0 / (2.0 * 0.3 * G)


def test_pairs_without_the_keys_keep_a_constant_temperature(tmp_path):
    """Leaving heatCapacity out keeps today's behaviour: no temperature is written, the law sees
    initialTemperature."""
    model = block(tmp_path, "0.3-0.001*temp", velocity=(1.2, 0.0, 0.0), break_time=0.2, heat={"heatCapacity": 0.0})
    result = run_folder(model)
    assert np.isnan(block_temperatures(result)).all()
    sliding = result.u[:, 0] > 0.05
    np.testing.assert_allclose(-result.a[sliding, 0][1:] / G, 0.3 - 0.001 * AMBIENT, rtol=1e-9)
