"""Painlevé's sliding rod: where Coulomb friction leaves the contact forces without a solution,
the rod's corner is stopped by an impulse (an impact without collision).

Sources: P. Painlevé, "Sur les lois du frottement de glissement", Comptes Rendus 121, 112-115
(1895); F. Génot and B. Brogliato, "New results on Painlevé paradoxes", European Journal of
Mechanics A/Solids 18(4), 653-677 (1999); D. E. Stewart, "Rigid-body dynamics with friction and
impact", SIAM Review 42(1), 3-39 (2000), section 2 (Painlevé's example and its resolution by an
impulsive force).

A rod of mass m and centroidal inertia I slides on one corner r (from the centroid) with the
corner moving in -x, so friction pushes it in +x: a normal force lambda gives the corner the
normal acceleration a + b lambda with a = -g (at rest in rotation) and
b = 1/m + r_x (r_x - mu r_y) / I. For a thin uniform rod at angle theta,
b = (1 + 3 cos² theta - 3 mu sin theta cos theta) / m, negative above the critical coefficient
mu_c(theta), at least 4/3 (at tan theta = 2). With a < 0 and b < 0 no force keeps the corner on
the floor: the rod cannot go on sliding. Stewart's velocity-level formulation stops the corner
by an impulse; where the impulse that makes it stick lies in Coulomb's cone, angular momentum
about the corner is conserved and the rod leaves the event turning about it with
omega+ = m (r_c x v_G-) / (I + m |r_c|²), r_c the vector from the corner to the centroid. The
corner then stays stuck where the floor's force that turns the rod about it lies in the cone, and
slides off from rest where it does not. Below
mu_c the same rod slides on with bounded forces and no jump in velocity.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, energy_residual, rectangle, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
LENGTH, THICKNESS, MASS = 1.0, 0.02, 1.0  # m, m, kg
INERTIA = MASS * (LENGTH**2 + THICKNESS**2) / 12.0  # kg m²


@dataclass
class Rod:
    """The rod at angle ``theta`` (rad) on its lowest corner, the corner sliding at ``speed`` (m/s,
    negative: in -x) under friction ``mu``."""

    theta: float
    mu: float
    speed: float
    dt_max: float = 1e-5
    max_penetration: float = 1e-7

    @cached_property
    def corner(self) -> np.ndarray:
        """The lowest corner relative to the centroid (m)."""
        c, s = np.cos(self.theta), np.sin(self.theta)
        corners = rectangle(LENGTH, THICKNESS) @ np.array([[c, s], [-s, c]])
        return corners[np.argmin(corners[:, 1])]

    def normal_coefficient(self) -> float:
        """b (m/s² per N): the corner's normal acceleration per unit normal force, friction
        mu lambda pushing in +x."""
        rx, ry = self.corner
        return 1.0 / MASS + rx * (rx - self.mu * ry) / INERTIA

    def impulsive_stick(self) -> tuple[np.ndarray, float, np.ndarray]:
        """(v_G+ (m/s), omega+ (rad/s), impulse (N s)) of the impulse that stops the corner:
        angular momentum about the corner conserved, the rod turning about it afterwards."""
        r = -self.corner  # corner -> centroid; r x v_G- with v_G- = (speed, 0)
        omega = -MASS * r[1] * self.speed / (INERTIA + MASS * (r @ r))
        velocity = omega * np.array([-r[1], r[0]])
        return velocity, omega, MASS * (velocity - np.array([self.speed, 0.0]))

    def sticking_force(self) -> np.ndarray:
        """The floor's force (N) on the corner just after the impulse, the rod turning about the
        stuck corner at omega+ under gravity: m a_G - m g, with a_G = alpha x r_c - omega+² r_c and
        alpha = -m g r_c,x / (I + m |r_c|²). Sticking lasts where it lies in Coulomb's cone."""
        r = -self.corner
        _, omega, _ = self.impulsive_stick()
        alpha = -MASS * G * r[0] / (INERTIA + MASS * (r @ r))
        return MASS * (alpha * np.array([-r[1], r[0]]) - omega**2 * r) + np.array([0.0, MASS * G])

    def slide_off(self, omega: float) -> float:
        """The acceleration (m/s²) along the floor of the corner at rest, the rod turning at
        ``omega`` (rad/s), where sticking needs more friction than the cone holds: that of the
        sliding mode whose normal force N keeps the corner on the floor (N > 0) and whose friction
        -mu N opposes the direction it accelerates in; NaN where no mode is consistent."""
        r = -self.corner

        def corner_acceleration(direction: float, normal: float) -> np.ndarray:
            force = np.array([-direction * self.mu * normal, normal])
            alpha = (-r[0] * force[1] + r[1] * force[0]) / INERTIA  # torque of the force at -r
            centroid = force / MASS - np.array([0.0, G])
            return centroid + alpha * np.array([r[1], -r[0]]) + omega**2 * r

        for direction in (1.0, -1.0):
            free, unit = corner_acceleration(direction, 0.0), corner_acceleration(direction, 1.0)
            normal = -free[1] / (unit[1] - free[1])
            along = corner_acceleration(direction, normal)[0]
            if normal > 0.0 and along * direction > 0.0:
                return along
        return np.nan

    def run(self, tmp_path, break_time: float):
        position = (0.0, -self.corner[1], self.theta)
        folder = BodyOnFloor(rectangle(LENGTH, THICKNESS), MASS, INERTIA, position=position,
                             velocity=(self.speed, 0.0, 0.0), friction=self.mu, restitution=0.0, dt_max=self.dt_max,
                             max_penetration=self.max_penetration, history_each_step=True,
                             break_time=break_time).write(tmp_path / "rod")
        return run_folder(folder)


def corner_velocity(result, rod: Rod, k: int) -> np.ndarray:
    """World velocity (m/s) of the rod's contact corner at sample k."""
    angle = result.q[k, 2] - rod.theta  # turned since the start
    c, s = np.cos(angle), np.sin(angle)
    rx, ry = c * rod.corner[0] - s * rod.corner[1], s * rod.corner[0] + c * rod.corner[1]
    ux, uy, omega = result.u[k]
    return np.array([ux - omega * ry, uy + omega * rx])


@settings(max_examples=12, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(theta_deg=st.floats(35.0, 80.0), mu=st.floats(1.0, 3.0), speed=st.floats(-3.0, -0.2),
       dt_max=st.sampled_from([1e-5, 1e-4]))
@example(theta_deg=45.0, mu=2.0, speed=-1.0, dt_max=1e-5)
@example(theta_deg=60.0, mu=1.5, speed=-1.0, dt_max=1e-5)
@example(theta_deg=63.43, mu=1.4, speed=-2.0, dt_max=1e-4)  # just above mu_c = 4/3
@example(theta_deg=70.0, mu=2.5, speed=-3.0, dt_max=1e-4)  # a fast slide: g dt_max is 0.03 % of the speed
@example(theta_deg=73.0, mu=2.0, speed=-3.0, dt_max=1e-5)  # sticking needs |F_x| = 2.5 F_y: it slides off
def test_inconsistent_sliding_ends_in_the_impulse_that_sticks_the_corner(tmp_path, theta_deg, mu, speed, dt_max):
    rod = Rod(np.radians(theta_deg), mu, speed, dt_max)
    assume(rod.normal_coefficient() < -0.01 / MASS)  # no contact force exists (a = -g < 0): Painlevé's case
    velocity, omega, impulse = rod.impulsive_stick()
    assume(impulse[1] > 0.0 and abs(impulse[0]) <= 0.99 * mu * impulse[1])  # sticking is inside Coulomb's cone
    force = rod.sticking_force()
    assume(force[1] > 0.0)  # (else the rod leaves the floor turning about the corner)
    result = rod.run(tmp_path, 100 * dt_max)
    jumped = np.flatnonzero(np.abs(result.u[:, 0] - speed) > 0.1 * abs(speed))
    assert len(jumped), "the rod went on sliding"
    k = jumped[0]
    assert result.time[k] <= 3 * dt_max  # at once, not after a slide into the floor
    tol = max(1e-3 * abs(speed), 3.0 * G * dt_max)  # gravity over the steps around the event
    assert np.allclose(result.u[k, :2], velocity, rtol=0.0, atol=tol)
    assert abs(result.u[k, 2] - omega) <= tol / np.linalg.norm(rod.corner)
    # the impulse stops the corner's present rates, and the contact forces then hold them below the rest velocity
    # (0.01 maximumPenetration / maximumTimestep), not at what one step of motion without them would add (about
    # g dt_max: the corner lifting off and sliding): the corner stays on the floor, and stuck where the force
    # that keeps it stuck lies in Coulomb's cone; beyond the cone it slides off from rest
    rest = 0.01 * rod.max_penetration / dt_max
    sticks = abs(force[0]) <= 0.9 * mu * force[1]
    for j in range(k, len(result.time)):
        v = corner_velocity(result, rod, j)
        assert abs(v[1]) < rest
        if sticks:
            assert abs(v[0]) < rest
    if abs(force[0]) >= 1.1 * mu * force[1] and np.isfinite(rod.slide_off(omega)):
        # it slides off at the acceleration of the consistent sliding mode, which changes fast as the rod turns
        # (6.7 % per step of 1e-4 s at 71.5 deg, mu = 1.625): over each step, the mean of the mode's accelerations
        # at the rod's sampled angles and spins
        def slide(j):
            return Rod(result.q[j, 2], mu, speed, dt_max).slide_off(result.u[j, 2])

        for j in range(k, k + 5):
            step = result.time[j + 1] - result.time[j]
            rise = corner_velocity(result, rod, j + 1)[0] - corner_velocity(result, rod, j)[0]
            assert rise == pytest.approx(0.5 * (slide(j) + slide(j + 1)) * step, rel=0.005)
    kinetic_before = 0.5 * MASS * speed**2
    kinetic_after = 0.5 * MASS * velocity @ velocity + 0.5 * INERTIA * omega**2
    assert result.lost[k] == pytest.approx(kinetic_before - kinetic_after, rel=0.0, abs=2.0 * tol * MASS * abs(speed))
    assert np.abs(energy_residual(result)).max() < 1e-9


def test_below_the_critical_coefficient_the_rod_slides_on(tmp_path):
    rod = Rod(np.radians(30.0), 1.5, -1.0)  # mu_c(30 deg) = (1 + 3 cos²) / (3 sin cos) = 2.5
    assert rod.normal_coefficient() > 0.0
    result = rod.run(tmp_path, 1e-3)
    assert result.state.clock[K.LCP_FAILURES] == 0
    # bounded forces: no sample-to-sample jump beyond what tens of g do over a step
    assert np.abs(np.diff(result.u[:, :2], axis=0)).max() < 50.0 * G * rod.dt_max
    assert all(corner_velocity(result, rod, j)[0] < -0.9 for j in range(len(result.time)))
    assert np.abs(energy_residual(result)).max() < 1e-9
