"""Piles of polygons whose contacts make the contact LCPs degenerate (docs/theory.md §3).

- Corners resting on corners (seed 125 of the pile in tests/physics/test_concave_corners.py:
  friction 0.9, maximumTimestep 1e-4 s, maximumPenetration 1e-6 m). Two polygons come to rest at
  t = 0.356 s with the corner of each on both edges at the corner of the other: two stick
  candidates 1e-8 m apart whose normals are 45 degrees apart. Their friction cones overlap, so
  the contact-force LCP has solutions with any internal force between the two contacts. At the
  end point of a Heun step the solution check accepted 7e10 and 9.6e10 N (25 and 28 N at the
  step's start). Over the lever of 1e-8 m this spun the polygons to 100-200 rad/s within one
  step, and the energy grew from 14.4 J by 138 J with no LCP failure counted.
- A corner wedged in the seam where a wall stands on the floor (seed 351: friction 0.43,
  maximumTimestep 1e-3 s, maximumPenetration 1e-7 m). At t = 0.2207 s the wall's bottom corner
  lay on both edges at the polygon's corner, and that corner on the wall's face. Solved again with
  the stick compliance, the contact-force LCP still had normal forces of 1e9 N that cancelled to
  the accelerations (not trusted); one Heun step with them spun the polygon from 11.5 to 38 rad/s
  and made 35 mJ. In seed 460 (maximumTimestep 1e-4 s, maximumPenetration 1e-6 m) such forces
  made 2 % of the run's largest energy.
- A spike sliding in a narrow slot of a neighbour (seed 704: friction 0.69, maximumTimestep
  1e-3 s, maximumPenetration 1e-5 m). At t = 0.74 s the contact-force LCP of the slot's two
  faces, the spike's neighbour and the floor has no solution (friction turns the spike into both
  faces, as in Painlevé's case; its 4 x 4 LCP has none among its 16 complementary sets). Left
  without forces, its contacts, already 0.3-0.7 maxPen deep, were caught by the penetration
  check before they approached fast enough for an impact: the run took 9.9 million steps (1.7
  million over-penetrations) to reach 1.5 s.
- A vertex in the seam where a wall stands on the floor (seed 107: maximumTimestep 3e-4 s,
  maximumPenetration 1e-8 m) touches the floor's top face and the wall's bottom face with
  opposite normals (tests/kernel/test_normal_compliance.py). There the impact's LCP ended on a
  ray at every step size, and the vertex went 0.47 mm (47,000 maximumPenetration) into the floor.
- A polygon standing on a vertex beside one that slides over it at 0.9 m/s (seed 304:
  maximumTimestep 3e-4 s, maximumPenetration 1e-8 m, minimumTimestep 1e-10 s). The impact's LCP,
  whose check is relative to its largest data (the sliding speeds), left the vertex approaching
  at 3e-8 m/s after every compression; it crept beyond maximumPenetration, and from t = 0.3097 s
  the step stayed near minimumTimestep (30 s of wall time for 0.15 ms).

Sources: the work-energy balance (the piles have no drive; their contacts, restitution below 1
and Coulomb friction, only take energy, so the mechanical energy plus the work lost at the
contacts stays at the initial energy), and the step control's bound (docs/theory.md §6: no
vertex deeper than maximumPenetration unless an over-penetration is counted).
"""

import warnings

import numpy as np
import pytest

from mbds.kernel import layout as K
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import RunStopped, initial_state, simulate
from tests.physics import test_concave_corners
from tests.physics.models import energy_residual
from tests.physics.test_concave_corners import FLOOR, WALLS, depth_inside, pile, world


@pytest.mark.parametrize("seed", [125, 351, 460])  # corners on corners; forces the stick compliance leaves untrusted
def test_contact_forces_that_cancel_make_no_energy(tmp_path, seed):
    result, _ = pile(tmp_path / "pile", seed)
    assert result.state.clock[K.T] >= 1.5 - 1e-9
    gain = -energy_residual(result)
    assert gain.max() <= 1e-6 * result.energy[0], f"energy gained: {gain.max():.3g} J of {result.energy[0]:.3g} J"
    assert np.abs(result.energy).max() <= result.energy[0] * (1.0 + 1e-6)
    assert result.state.clock[K.OVER_PENETRATIONS] == 0


def test_a_vertex_in_the_seam_of_wall_and_floor_stays_out_of_both(tmp_path):
    result, shapes = pile(tmp_path / "pile", 107)
    max_penetration = 1e-8
    assert result.state.clock[K.T] >= 1.5 - 1e-9
    assert result.state.clock[K.LCP_FAILURES] == 0
    assert result.state.clock[K.OVER_PENETRATIONS] == 0
    assert_out_of_the_box(result, shapes, max_penetration)
    assert (-energy_residual(result)).max() <= 1e-6 * result.energy[0]


def assert_out_of_the_box(result, shapes, max_penetration):
    """No vertex of a pile's polygons is sampled deeper than max_penetration (m) in the floor or
    the walls."""
    for pose in result.q:
        for k, shape in enumerate(shapes):
            outline = world(shape, pose[3 * k : 3 * k + 3])
            for fixed in [FLOOR, *WALLS]:
                assert depth_inside(outline, fixed).max() <= max_penetration * (1.0 + 1e-9)


def run_at_most(steps):
    """A runner for :func:`pile` that stops a run after ``steps`` steps: a stalled run fails
    instead of hanging."""
    def run(folder):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = load_model(folder)
        state = initial_state(model, 0)

        def progress(t):
            if state.clock[K.STEPS] > steps:
                raise RunStopped(f"more than {steps} steps")

        return simulate(model, RunSettings(break_time=model.break_time), state=state, progress=progress)
    return run


def test_a_vertex_at_rest_beside_a_fast_sliding_one_keeps_the_step(tmp_path, monkeypatch):
    monkeypatch.setattr(test_concave_corners, "run_folder", run_at_most(40_000))  # 5,000 at maximumTimestep
    result, _ = pile(tmp_path / "pile", 304)
    assert not result.stopped
    assert result.state.clock[K.T] >= 1.5 - 1e-9
    assert result.state.clock[K.MAX_PENETRATION] <= 1e-8 * (1.0 + 1e-6)
    assert (-energy_residual(result)).max() <= 1e-6 * result.energy[0]


def test_a_spike_jammed_in_a_slot_takes_an_impact_without_collision(tmp_path, monkeypatch):
    monkeypatch.setattr(test_concave_corners, "run_folder", run_at_most(20_000))  # 1,500 at maximumTimestep
    result, shapes = pile(tmp_path / "pile", 704)
    assert not result.stopped
    assert result.state.clock[K.T] >= 1.5 - 1e-9
    assert result.state.clock[K.OVER_PENETRATIONS] == 0
    assert_out_of_the_box(result, shapes, 1e-5)
    assert (-energy_residual(result)).max() <= 1e-6 * result.energy[0]
