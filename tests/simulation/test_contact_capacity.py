"""A run's result does not depend on how many contacts its workspace holds at the start.

When detection finds more contacts than the workspace holds, the stepper stops, and the run
moves everything into a workspace twice as large (mbds.simulation.buffers.grown) and calls it
again, which redoes the pass. The larger workspace used to start empty: with no step left to go
back to, the step that had led to the state was accepted unchecked. In a pile of polygons (seed
359 of the pile in tests/physics/test_concave_corners.py, maximumPenetration 1e-5 m) a vertex
ended 1.15e-5 m deep in the floor there, with no over-penetration counted.
"""

import warnings

import numpy as np

from mbds.kernel import layout as K
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import CONTACT_CAPACITY, simulate
from tests.physics.test_concave_corners import pile

MAX_PENETRATION = 1e-5  # m: drawn by the pile's generator for seed 359


def test_a_pile_runs_the_same_whatever_contact_capacity_it_starts_with(tmp_path):
    tight, _ = pile(tmp_path / "pile", 359)  # starts with CONTACT_CAPACITY contacts
    assert tight.capacity > CONTACT_CAPACITY  # the workspace grew during the run
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(tmp_path / "pile")
    assert model.settings.maximum_penetration == MAX_PENETRATION
    roomy = simulate(model, RunSettings(break_time=model.break_time), capacity=1024)
    assert roomy.capacity == 1024
    for name in ("time", "q", "u", "energy", "lost"):
        np.testing.assert_array_equal(getattr(tight, name), getattr(roomy, name), err_msg=name)
    np.testing.assert_array_equal(tight.state.clock, roomy.state.clock)
    assert tight.state.clock[K.MAX_PENETRATION] <= MAX_PENETRATION
    assert tight.state.clock[K.OVER_PENETRATIONS] == 0
