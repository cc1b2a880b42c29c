"""Limit cycles that impacts sustain: the rimless wheel and the block on a vibrating table.

- A regular N-gon rolling down a slope gamma without slipping or bouncing is McGeer's rimless
  wheel (T. McGeer, "Passive dynamic walking", Int. J. Robotics Research 9(2), 62-82, 1990).
  Between vertex impacts it swings about its pivot vertex; at each impact the angular velocity
  drops by r = (I + m R² cos 2a) / (I + m R²), 2a = 2 pi / N, and a step down the slope gains
  m g R (cos(a - gamma) - cos(a + gamma)) = 2 m g R sin a sin gamma. The steady roll, reached
  from any start that keeps rolling, has the speed before each impact
  omega*² = 4 m g R sin a sin gamma / ((I + m R²) (1 - r²)).
- A body bouncing on a table that moves as s(t) = A sin(w t) (P. J. Holmes, "The dynamics of
  repeated impacts with a sinusoidally vibrating table", J. Sound Vib. 84(2), 173-189, 1982):
  it flies freely between impacts, and at an impact its speed relative to the table is
  reversed and scaled by e. The reference is the exact impact map (the impact times as roots of
  the flight against s(t), not Holmes' high-bounce approximation), as in J. M. Luck and
  A. Mehta, Phys. Rev. E 48, 3988 (1993). At A = 4 mm, 10 Hz and e = 0.5 the period-1 orbit
  (an impact every period) is unstable: a block dropped from rest oscillates away from it into a
  stable period-2 orbit. A flat block dropped level lands on both bottom corners at once and
  stays level, so it follows the point-mass map.

A flight is compared through what stays constant along it, whatever samples show it: the time
of its apex, t + v / g, and the height of its apex, y + v² / (2 g).
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, regular_polygon, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²


@pytest.mark.parametrize("omega0", [4.0, 15.0])
def test_rimless_wheel_settles_on_mcgeers_steady_roll(tmp_path, omega0):
    """A 12-gon on a 0.1 rad slope with coarse steps and the default skin, started slower and
    faster than the steady roll: after 3 s the speed before each impact is within 0.1 % of omega*."""
    sides, radius, mass, slope = 12, 0.05, 1.0, 0.1  # -, m, kg, rad
    inertia = mass * radius**2 * (1.0 + 2.0 * np.cos(np.pi / sides) ** 2) / 6.0
    pivot = inertia + mass * radius**2
    ratio = (inertia + mass * radius**2 * np.cos(2.0 * np.pi / sides)) / pivot
    half = np.pi / sides
    steady = np.sqrt(4.0 * mass * G * radius * np.sin(half) * np.sin(slope) / (pivot * (1.0 - ratio**2)))
    folder = BodyOnFloor(regular_polygon(sides, radius), mass, inertia, position=(0.0, radius, 0.0),
                         velocity=(-omega0 * radius, 0.0, omega0), gravity=(-G * np.sin(slope), -G * np.cos(slope)),
                         friction=1.5, restitution=0.0, dt_max=1e-4, max_penetration=1e-6,
                         break_time=3.0).write(tmp_path / "wheel")
    result = run_folder(folder)
    omega = result.u[:, 2]
    jumps = np.flatnonzero(np.abs(np.diff(omega)) > 0.5 * (1.0 - ratio) * np.abs(omega[1:])) + 1
    assert len(jumps) > 30
    assert np.median(omega[jumps] / omega[jumps - 1]) == pytest.approx(ratio, rel=1e-3)
    np.testing.assert_allclose(omega[jumps[-5:] - 1], steady, rtol=1e-3)
    assert result.state.clock[K.OVER_PENETRATIONS] == 0


TABLE_AMPLITUDE, TABLE_OMEGA = 0.004, 20.0 * np.pi  # m, rad/s (10 Hz)
BLOCK_WIDTH, BLOCK_HALF_HEIGHT, DROP = 0.04, 0.01, 0.005  # m
RESTITUTION = 0.5


def exact_flights(end: float) -> np.ndarray:
    """(apex time s, apex height m of the block's centre) of every flight of the exact impact map
    that starts and ends before ``end``, after the drop from rest DROP above the table at t = 0."""
    a, w, e = TABLE_AMPLITUDE, TABLE_OMEGA, RESTITUTION
    start, height, speed = 0.0, DROP, 0.0  # the flight's start, the bottom's height there, its speed
    flights, flight = [], None  # flight: the current one's apex, kept once it ends before ``end``
    while True:
        times = start + np.arange(1, 40001) * 1e-5  # the next impact comes within 0.4 s here

        def gap(t):
            return height + speed * (t - start) - 0.5 * G * (t - start) ** 2 - a * np.sin(w * t)

        below = np.flatnonzero(gap(times) <= 0.0)[0]
        hit = brentq(gap, times[below] - 1e-5, times[below], xtol=1e-14)
        if hit >= end:
            return np.array(flights)
        if flight is not None:
            flights.append(flight)
        table = a * w * np.cos(w * hit)
        speed = (1.0 + e) * table - e * (speed - G * (hit - start))
        start, height = hit, a * np.sin(w * hit)
        flight = (start + speed / G, height + BLOCK_HALF_HEIGHT + speed**2 / (2.0 * G))


def on_the_table(tmp_path, dt_max: float, max_penetration: float, end: float, restitution: float = RESTITUTION,
                 size=(BLOCK_WIDTH, 2.0 * BLOCK_HALF_HEIGHT), drop=DROP, table=(TABLE_AMPLITUDE, TABLE_OMEGA),
                 tilt=0.0):
    """The run of a flat block (width, height m) dropped from ``drop`` (m, its lowest corner
    above the table) onto the table moving as a sin(w t) (``table``: a m, w rad/s), tilted by
    ``tilt`` (rad)."""
    width, height = size
    block = BodyOnFloor(rectangle(width, height), 1.0, (width**2 + height**2) / 12.0,
                        position=(0.0, 0.5 * height + drop + 0.5 * width * abs(tilt), tilt), restitution=restitution,
                        dt_max=dt_max, max_penetration=max_penetration, break_time=end)
    folder = block.write(tmp_path / "table")
    with open(folder / "model.cns", "a") as constants:
        constants.write(f"c'a = {table[0]!r}\nc'w = {table[1]!r}\n")
    (folder / "model.dc").write_text(
        "%%%new%%%\nb'floor'y[t]\n%%definition\nc'a*Sin[c'w*t]\nc'a*c'w*Cos[c'w*t]\n-(c'a*c'w^2*Sin[c'w*t])\n"
        "%%J\n0\n0\n0\n%%j\n-(c'a*c'w^2*Sin[c'w*t])\n")
    return run_folder(folder)


def table_flights(tmp_path, dt_max: float, max_penetration: float, end: float) -> np.ndarray:
    """(apex time s, apex height m) of each flight of the block over the vibrating table in
    mbds, from the samples inside it; the block must stay level."""
    result = on_the_table(tmp_path, dt_max, max_penetration, end)
    t, y, v = result.time, result.q[:, 1], result.u[:, 1]
    impacts = np.flatnonzero(np.diff(v) > 0.05) + 1  # the speed jumps up at an impact
    flights = []
    for first, stop in zip(impacts, list(impacts[1:]) + [len(t)]):
        inside = slice(first + 1, stop - 1)  # (samples of the flight only)
        flights.append((np.median(t[inside] + v[inside] / G), np.median(y[inside] + v[inside] ** 2 / (2.0 * G))))
    assert np.abs(result.q[:, 2]).max() < 1e-9  # level throughout
    return np.array(flights[:-1])


def test_a_block_on_a_vibrating_table_follows_the_exact_impact_map(tmp_path):
    """Fine steps: every flight of 3 s (29 impacts), through the transient from the unstable
    period-1 orbit into the period-2 orbit, matches the exact map: apex times within 0.2 ms,
    apex heights within 0.5 %; on the period-2 orbit within 10⁻⁴."""
    exact = exact_flights(3.0)
    flights = table_flights(tmp_path, 1e-4, 1e-7, 3.0)
    assert len(flights) == len(exact) > 25
    np.testing.assert_allclose(flights[:, 0], exact[:, 0], atol=2e-4)
    np.testing.assert_allclose(flights[:, 1], exact[:, 1], rtol=5e-3)
    np.testing.assert_allclose(flights[-4:], exact[-4:], rtol=1e-4)
    assert max(exact[-2:, 1]) / min(exact[-2:, 1]) > 1.25  # two different flights alternate: period 2


def test_coarse_steps_reach_the_same_period_2_orbit(tmp_path):
    """maximumTimestep 1 ms and the default skin (1 mm): the transient's flights may come in
    another order, but after 3 s the block flies the exact map's period-2 orbit, its two apex
    heights alternating within 10⁻³ and apexes two table periods apart."""
    exact = exact_flights(3.0)
    orbit = sorted(exact[-2:, 1])
    flights = table_flights(tmp_path, 1e-3, 1e-5, 3.0)
    last = flights[-4:]
    lows, highs = (last[0::2], last[1::2]) if last[0, 1] < last[1, 1] else (last[1::2], last[0::2])
    np.testing.assert_allclose(lows[:, 1], orbit[0], rtol=1e-3)
    np.testing.assert_allclose(highs[:, 1], orbit[1], rtol=1e-3)
    np.testing.assert_allclose(last[2:, 0] - last[:2, 0], 2.0 * 2.0 * np.pi / TABLE_OMEGA, atol=2e-4)


def test_a_block_resting_between_flights_stays_level(tmp_path):
    """At e = 0.45 each flight ends in a chatter of shrinking bounces and a rest on both corners
    until the table lifts the block off again (373 impacts in 3 s, each rebound e times the
    landing before it). A block resting level
    leaves level: the settling of its two contacts (docs/theory.md §3) must not turn it. It
    stayed level to 10⁻¹⁵ rad with 10⁻⁵ s and 10⁻⁹ m, but with 10⁻⁴ s its tilt grew 5-fold
    every table period from round-off, until a corner struck first at 2 s."""
    result = on_the_table(tmp_path, 1e-4, 1e-7, 3.0, restitution=0.45)
    assert result.state.clock[K.IMPACTS] > 250
    assert np.abs(result.q[:, 2]).max() < 1e-12


def test_a_tilt_dies_out_on_a_table_that_throws_a_plastic_block(tmp_path):
    """e = 0: the block (10 x 5 cm) lands plastically and rests on both corners until the table
    (2.4 g at 15.6 Hz) throws it up again. Started 10⁻¹⁰ rad off level, the landings and rests
    take the tilt out (with 10⁻⁵ s and 10⁻⁸ m it is at round-off, 10⁻¹⁷ rad, after 0.2 s). While
    the settling of the two corners' gaps moved the velocities, each lift-off carried it into the
    flight as a spin, and with 10⁻⁴ s and 10⁻⁶ m the tilt grew to 10⁻⁵ rad."""
    omega = 2.0 * np.pi * 15.6  # rad/s
    result = on_the_table(tmp_path, 1e-4, 1e-6, 2.0, restitution=0.0, size=(0.1, 0.05), drop=0.009,
                          table=(2.4 * G / omega**2, omega), tilt=1e-10)
    assert np.abs(result.q[result.time > 1.0, 2]).max() < 1e-9
