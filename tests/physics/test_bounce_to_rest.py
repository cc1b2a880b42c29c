"""A block bouncing on the floor comes to rest at the accumulation point of its bounces, and a
body lying in the floor (or just above it) settles to zero gap without overshoot and without
taking up a speed.

Sources:
- Newton's impact law for a rigid body dropped flat onto a rigid floor (the bouncing ball: Leine
  and van de Wouw, "Stability and Convergence of Mechanical Systems with Unilateral
  Constraints", Springer 2008, ch. 7; Acary and Brogliato, "Numerical Methods for Nonsmooth
  Dynamical Systems", Springer 2008, §1.2). Dropped with impact speed v0, the block rebounds with
  e^k v0 after its k-th impact; the flights shrink geometrically and end at the accumulation time
  t_inf = (v0 + 2 e v0 / (1 - e)) / g, after infinitely many impacts. The block then rests.
- Cline and Pai, "Post-stabilization for rigid body simulation with contact and constraints",
  Proc. IEEE ICRA 2003, 3744-3751: a constraint violation is removed by a shift of the positions
  alone, dq = M^-1 J^T (J M^-1 J^T)^-1 (-dg), which changes no velocity.

A time-stepping run cannot follow the flights once they are shorter than a step. mbds ends the
sequence where a rebound would be slower than the rest velocity v_rest = 0.01 maximumPenetration
/ maximumTimestep (the impact is then plastic), or where the flight would stay within the band
in which a contact at rest stays held (a rise of v^2 / 2g up to 0.25 maximumPenetration,
docs/theory.md §3 and §4). So it counts the impacts that come before the first rebound slower
than v_end = max(v_rest, sqrt(2 g 0.25 maximumPenetration)): 1 + floor(ln(v_end / v0) / ln e) of
them. Before, the block chattered on at the scale of one step's fall for good: 15,682 counted
impacts in the 0.5 s after t_inf with a maximum step of 1e-5 s (e = 0.5).

A contact at rest relaxes its normal speed to zero with the time constant tau = 10 maximum
steps, and each step shifts the positions so that its gap moves by dt v_s, v_s = -g / (4 tau)
within half the rest velocity (mbds.kernel.settling): the gap decays as g0 (1 - dt / (4 tau))^k
after k steps, g0 exp(-t / (4 tau)) to within 0.5 % of g0 here.
"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from mbds.kernel.contact_problem import HELD_FRACTION, REST_FRACTION, REST_RELAXATION
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import initial_state, simulate
from tests.physics.models import BodyOnFloor, energy_residual, rectangle
from tests.physics.test_tunnelling import G, polygon_mass

DROP, DT_MAX, MAX_PEN = 0.05, 1e-5, 1e-7  # m, s, m

pytestmark = pytest.mark.physics


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_a_bouncing_block_comes_to_rest_at_the_accumulation_point(tmp_path, e):
    mass, inertia, shape = polygon_mass(rectangle(0.1, 0.1))
    v0 = np.sqrt(2.0 * G * DROP)
    t_inf = (v0 + 2.0 * e * v0 / (1.0 - e)) / G
    folder = BodyOnFloor(shape, mass, inertia, position=(0.0, DROP - shape[:, 1].min(), 0.0), friction=0.5,
                         restitution=e, dt_max=DT_MAX, max_penetration=MAX_PEN, break_time=t_inf + 0.25,
                         ).write(tmp_path / "model")
    model = load_model(folder)
    state = initial_state(model, 0)
    simulate(model, RunSettings(break_time=t_inf + 0.05), state)  # the last held rise settles
    bounces = state.clock[K.IMPACTS]
    v_end = max(REST_FRACTION * MAX_PEN / DT_MAX, np.sqrt(2.0 * G * HELD_FRACTION * MAX_PEN))
    expected = 1 + np.floor(np.log(v_end / v0) / np.log(e))
    assert expected - 1 <= bounces <= expected
    rest = simulate(model, RunSettings(break_time=t_inf + 0.25), state)
    assert state.clock[K.IMPACTS] == bounces  # none after the accumulation point (0.2 s)
    assert np.abs(rest.u).max() <= 1e-12
    assert np.abs(rest.q - rest.q[0]).max() <= 1e-9
    residual = energy_residual(rest)
    assert (residual - residual[0]).min() >= -1e-12 * mass * G * DROP  # no energy gained
    assert state.clock[K.STEPS] <= 1.01 * (t_inf + 0.25) / DT_MAX  # steps at maximumTimestep


# depth, of maximumPenetration: in the floor, settling out slower than v_rest / 2, or just above it
# (within the closed band of 0.01 maximumPenetration), settling down without an impact
@pytest.mark.parametrize("depth", [0.05, 0.15, -0.005])
def test_a_body_in_the_floor_settles_out_without_taking_up_a_speed(tmp_path, depth):
    dt_max = 1e-4
    tau = REST_RELAXATION * dt_max
    mass, inertia, shape = polygon_mass(rectangle(0.2, 0.1))
    g0 = -depth * MAX_PEN
    folder = BodyOnFloor(shape, mass, inertia, position=(0.0, g0 - shape[:, 1].min(), 0.0), friction=0.5,
                         dt_max=dt_max, max_penetration=MAX_PEN, history_each_step=True, break_time=40.0 * tau,
                         ).write(tmp_path / "model")
    model = load_model(folder)
    result = simulate(model, RunSettings(break_time=40.0 * tau))
    assert result.state.clock[K.IMPACTS] == 0
    gap = result.q[:, 1] + shape[:, 1].min()
    expected = g0 * np.exp(-result.time / (4.0 * tau))
    assert np.abs(gap - expected).max() <= 0.01 * abs(g0)
    assert (np.sign(g0) * gap).min() >= -1e-3 * abs(g0)  # no overshoot
    assert np.abs(result.u[:, 1]).max() <= 1e-3 * REST_FRACTION * MAX_PEN / dt_max  # no speed taken up
    assert np.abs(result.q[:, 2]).max() <= 1e-12  # level
    # the contact's work on the way out is in the lost work: the energy balance holds
    residual = energy_residual(result)
    assert np.abs(residual).max() <= 1e-3 * mass * G * abs(g0)


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_a_lift_off_shorter_than_a_step_lands_as_fast_as_it_left(tmp_path, e):
    """A block lying on the floor leaves it at v0 = 5 v_rest (Newton's law as above): its flight,
    2 v0 / g, is a tenth of a maximum step. The step ends where the flight does, so the block
    lands at v0 and rebounds at e v0, e^2 v0, ..., until a rebound is slower than v_rest. A step
    of maximumTimestep would land it about 20 times faster than it left, with the energy of the
    penetration it reached, and the bounces would grow."""
    dt_max, max_pen = 1e-3, 1e-5
    v_rest = REST_FRACTION * max_pen / dt_max
    v0 = 5.0 * v_rest
    mass, inertia, shape = polygon_mass(rectangle(0.1, 0.1))
    folder = BodyOnFloor(shape, mass, inertia, position=(0.0, -shape[:, 1].min(), 0.0), velocity=(0.0, v0, 0.0),
                         friction=0.5, restitution=e, dt_max=dt_max, max_penetration=max_pen, history_each_step=True,
                         break_time=0.05).write(tmp_path / "model")
    result = simulate(load_model(folder), RunSettings(break_time=0.05))
    expected = 1 + int(np.floor(np.log(v_rest / v0) / np.log(e)))
    assert result.state.clock[K.IMPACTS] == expected
    # each flight is one step, and a sample at a step's start comes before its impact: the samples
    # moving down are the landings
    vy = result.u[:, 1]
    landings = -vy[vy < -1e-3 * v_rest]
    assert landings == pytest.approx(v0 * e ** np.arange(expected), rel=1e-9)
    assert np.abs(result.q[:, 2]).max() <= 1e-12  # level
