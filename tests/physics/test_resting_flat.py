"""A polygon that comes to rest on one of its faces, or slides on it, keeps its steps near
maximumTimestep and stays on the floor.

The three cases were found by a random sweep of the ranges of test_tunnelling.py, run 1.5 s
after landing. In each, the two corners of the face touching the floor give the contact LCP two
tangential rows that coincide to round-off: the same normal, the same lever arm. Lemke's method
then ended, at every step, on a point that failed its solution check. The contact forces or the
impact were dropped, the body fell into the floor, the step was rejected, and the step shrank to
1e-9 s or to minimumTimestep: a million steps for a millisecond. The stick rows of such an LCP
are now solved once more with a small compliance (mbds.kernel.contact_problem.STICK_COMPLIANCE,
docs/theory.md §3).

Expected, by Newton's first law: a body lying on the floor, pressed by its weight and without
drive, stays there, and any remaining sliding is slowed by friction. So the run ends at its break
time; the steps stay within twice the count at maximumTimestep; and the body ends on the floor,
no deeper than maximumPenetration. Once it lies still (the last 0.4 s), as for the resting stack
of test_stack.py: no impact, no drift above 1e-9 m, no energy gained, every step at
maximumTimestep. Before the normal speed left at rest decayed (docs/theory.md §3), each case
floated up at just below the rest velocity until its contacts opened, fell back and chattered:
the decagon logged 15,340 impacts and the pentagon gained 1.5e-5 J.
"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import RunStopped, initial_state, simulate
from tests.physics.models import BodyOnFloor, energy_residual, rectangle, regular_polygon
from tests.physics.test_tunnelling import DT_MIN, G, lowest_vertex, polygon_mass

pytestmark = pytest.mark.physics

AFTER_LANDING = 1.5  # s simulated after the fall
SETTLED = 1.1  # s after the fall: every case lies still on its face by then
CASES = {
    "pentagon at rest": (regular_polygon(5, 0.06232890284381793), dict(
        tilt=0.29185842372142434, drop=0.0008981017826278082, spin=-4.140498659758281,
        dt_max=0.00028459252439774475, max_penetration=9.391085705121301e-08, friction=0.8529199944545277,
        restitution=0.17376904281719227)),
    "rectangle on its short side": (rectangle(0.1413652659160716, 0.25131928432027795), dict(
        tilt=2.083985407725232, drop=0.04045999531215312, spin=8.308118859215742, dt_max=7.871363526046869e-05,
        max_penetration=2.9480795415376585e-09, friction=0.9024915139224073, restitution=0.6962959362456952)),
    "decagon sliding": (regular_polygon(10, 0.14856060901903956), dict(
        tilt=0.41762323995461553, drop=0.030114598940722805, spin=-3.8847113797292536,
        dt_max=5.2230594135164854e-05, max_penetration=4.218292678284549e-09, friction=0.008333672311835794,
        restitution=0.6829171353262002)),
}


@pytest.mark.parametrize("name", CASES)
def test_a_polygon_on_its_face_keeps_its_step_and_stays_at_rest(tmp_path, name):
    shape, p = CASES[name]
    mass, inertia, shape = polygon_mass(shape)
    lowest = (np.sin(p["tilt"]) * shape[:, 0] + np.cos(p["tilt"]) * shape[:, 1]).min()
    landing = np.sqrt(2.0 * p["drop"] / G)
    break_time = landing + AFTER_LANDING
    folder = BodyOnFloor(
        shape, mass, inertia, position=(0.0, p["drop"] - lowest, p["tilt"]), velocity=(0.0, 0.0, p["spin"]),
        friction=p["friction"], restitution=p["restitution"], dt_min=DT_MIN, dt_max=p["dt_max"],
        max_penetration=p["max_penetration"], break_time=break_time,
    ).write(tmp_path / "model")
    budget = 2.0 * break_time / p["dt_max"]
    model = load_model(folder)
    state = initial_state(model, 0)

    def give_up(t):  # a collapsed step would take hours: stop the run past the budget
        if state.clock[K.STEPS] > budget:
            raise RunStopped("the step collapsed")

    settled = simulate(model, RunSettings(break_time=landing + SETTLED), state, progress=give_up)
    assert not settled.stopped
    impacts, steps = state.clock[K.IMPACTS], state.clock[K.STEPS]
    result = simulate(model, RunSettings(break_time=break_time), state, progress=give_up)
    assert not result.stopped
    assert result.state.clock[K.STEPS] <= budget
    assert -lowest_vertex(shape, result.q[-1:])[0] <= p["max_penetration"]
    # at rest: no impact, no drift, no energy gained, steps at maximumTimestep
    rest = AFTER_LANDING - SETTLED
    assert state.clock[K.IMPACTS] == impacts
    assert np.abs(result.q - result.q[0]).max() <= 1e-9
    scale = mass * G * np.ptp(shape, axis=0).max()  # J
    residual = energy_residual(result)  # (the lost work counts from the start of the run)
    assert (residual - residual[0]).min() >= -1e-12 * scale
    assert state.clock[K.STEPS] - steps <= 1.01 * rest / p["dt_max"] + 1
