"""A block on the floor pulled through a spring whose far end moves at a constant speed: the
stick–slip limit cycle of dry friction with a static coefficient above the kinetic one.

The driven spring–block model (Popov, Contact Mechanics and Friction, 2010, ch. 12; Leine, van
Campen, de Kraker and van den Steen, Nonlinear Dynamics 16, 1998, whose belt-driven oscillator is
the same system seen from the belt). With the spring's stretch s = v_b t - x, stiffness k and
ω = sqrt(k/m):

- stick: x stays while k s grows to mu_s m g, at s_1 = mu_s m g / k (first at t_1 = s_1 / v_b);
- slip: m s'' = -k s + mu_k m g, an oscillation about s_k = mu_k m g / k that starts at s_1 with
  s' = v_b; it ends when x' = v_b - s' is zero again, after ω t_slip = 2 π - 2 atan(ω Δ / v_b)
  with Δ = s_1 - s_k, at s = s_k - Δ; the peak speed is v_b + sqrt((ω Δ)² + v_b²);
- stick again until s = s_1: t_stick = 2 Δ / v_b. The period is t_slip + t_stick, and over a
  period the block advances v_b times it.

With mu_s = mu_k the slip is one whole oscillation (period 2 π / ω, peak speed 2 v_b) whose
speed only touches zero. The kinetic coefficient is reached here through a friction law of the
sliding speed, mu_k + (mu_s - mu_k) exp(-vRel / V_DECAY), with V_DECAY well below the speeds of
the slip.
"""

import numpy as np
import pytest

from tests.physics.models import BodyOnFloor, rectangle, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
MASS, STIFFNESS, DRIVE = 1.0, 100.0, 0.1  # kg, N/m, m/s
MU_S, MU_K = 0.4, 0.3
V_DECAY = 1e-4  # m/s
WIDTH, HEIGHT = 0.1, 0.02  # m: flat enough never to tip
OMEGA = np.sqrt(STIFFNESS / MASS)
S_1, S_K = MU_S * MASS * G / STIFFNESS, MU_K * MASS * G / STIFFNESS
DELTA = S_1 - S_K
T_1 = S_1 / DRIVE
T_SLIP = (2.0 * np.pi - 2.0 * np.arctan(OMEGA * DELTA / DRIVE)) / OMEGA
T_STICK = 2.0 * DELTA / DRIVE
V_PEAK = DRIVE + np.hypot(OMEGA * DELTA, DRIVE)
MOVING = 1e-4  # m/s: the block slips while faster


def pulled_block(folder, law: str, dt_max: float, max_penetration: float):
    block = BodyOnFloor(rectangle(WIDTH, HEIGHT), MASS, MASS * (WIDTH**2 + HEIGHT**2) / 12.0,
                        position=(0.0, 0.5 * HEIGHT, 0.0), dt_max=dt_max, max_penetration=max_penetration,
                        break_time=3.0, force_x=f"{STIFFNESS!r}*({DRIVE!r}*t-b'body'x[t])")
    folder = block.write(folder)
    cop = folder / "model.cop"
    cop.write_text(cop.read_text().replace("friction = c'mu", f"friction = {law}"))
    return run_folder(folder)


def phases(result):
    """Times (s) at which slips start and end."""
    t, moving = result.time, result.u[:, 0] > MOVING
    return t[1:][moving[1:] & ~moving[:-1]], t[1:][~moving[1:] & moving[:-1]]


STRIBECK = f"{MU_K!r}+{MU_S - MU_K!r}*Exp[-vRel/{V_DECAY!r}]"


@pytest.fixture(scope="module")
def cycle(tmp_path_factory):
    return pulled_block(tmp_path_factory.mktemp("cycle"), STRIBECK, 1e-4, 1e-7)


def test_the_limit_cycle_has_the_analytic_phases(cycle):
    starts, ends = phases(cycle)
    assert len(starts) == 4 and len(ends) == 4
    assert starts[0] == pytest.approx(T_1, rel=5e-3)
    np.testing.assert_allclose(np.diff(starts), T_SLIP + T_STICK, rtol=5e-3)
    np.testing.assert_allclose(ends - starts, T_SLIP, rtol=5e-3)
    np.testing.assert_allclose(starts[1:] - ends[:-1], T_STICK, rtol=2e-2)
    assert cycle.u[:, 0].max() == pytest.approx(V_PEAK, rel=1e-2)


def test_the_block_rests_while_the_spring_loads_and_follows_the_drive_on_average(cycle):
    t, x, v = cycle.time, cycle.q[:, 0], cycle.u[:, 0]
    starts, ends = phases(cycle)
    for end, start in zip(ends, starts[1:]):
        stuck = (t > end + 0.03) & (t < start - 2e-3)  # after the speed left at the slip's end has decayed
        assert stuck.sum() > 1000
        assert np.ptp(x[stuck]) < 1e-12 and np.abs(v[stuck]).max() < 1e-12
    first, last = np.searchsorted(t, [starts[0], starts[-1]])
    assert (x[last] - x[first]) / (t[last] - t[first]) == pytest.approx(DRIVE, rel=1e-4)
    assert v.min() > -1e-9  # never backwards


def test_the_lost_work_is_the_friction_work_of_the_law(cycle):
    """Lost work (J) against ∫ mu(|v|) m g |v| dt by the trapezoidal rule over the samples."""
    t, v = cycle.time, np.abs(cycle.u[:, 0])
    power = (MU_K + (MU_S - MU_K) * np.exp(-v / V_DECAY)) * MASS * G * v
    friction_work = np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t))
    assert cycle.lost[-1] == pytest.approx(friction_work, rel=1e-3)


def test_coarse_steps_and_the_default_skin_keep_the_cycle(tmp_path):
    result = pulled_block(tmp_path / "coarse", STRIBECK, 1e-3, 1e-5)
    starts, ends = phases(result)
    assert len(starts) == 4
    np.testing.assert_allclose(np.diff(starts), T_SLIP + T_STICK, rtol=1e-2)
    np.testing.assert_allclose(ends - starts, T_SLIP, rtol=1e-2)
    assert result.u[:, 0].max() == pytest.approx(V_PEAK, rel=1.5e-2)


def test_equal_coefficients_give_one_harmonic_oscillation_per_cycle(tmp_path):
    result = pulled_block(tmp_path / "equal", repr(MU_K), 1e-4, 1e-7)
    starts, _ = phases(result)
    t, v = result.time, result.u[:, 0]
    assert len(starts) >= 3
    np.testing.assert_allclose(np.diff(starts), 2.0 * np.pi / OMEGA, rtol=5e-3)
    assert v.max() == pytest.approx(2.0 * DRIVE, rel=1e-3)
    assert v[t > starts[0]].min() > -1e-9
