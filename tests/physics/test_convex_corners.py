"""No vertex passes into a body through a convex corner.

A vertex in the exterior wedge of a convex corner (beyond the ends of both edges that meet
there) faces neither edge, so no vertex-edge contact sees it. The step control trusts every
vertex within a pair's detection margin to be reported (docs/theory.md, "Step control"); a tip
thrown at a corner along the corner's bisector was not, and it went through the corner within
one step, deeper than the skin, and on through the block. Detection now reports such a vertex
as a corner contact, open, at its distance from the corner (docs/theory.md §2), and the step
control stops it at the corner, where it meets the edges.

The depths here are measured from the sampled poses and the shapes, by a point-in-polygon
test and the distance to the outline, independently of the kernel. The models share one
structure (a free polygon and a fixed block, no gravity), so one compiled stepper serves all.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mbds.kernel import layout as K
from tests.physics.models import (
    FreeBody, add_fixed_body, energy_residual, regular_polygon, run_folder, write_free_bodies,
)
from tests.physics.test_concave_corners import depth_inside, world
from tests.physics.test_tunnelling import contact_laws, dt_maxima, penetrations, polygon_mass

pytestmark = pytest.mark.physics

BLOCK = np.array([(-0.2, -0.2), (0.0, -0.2), (0.0, 0.0), (-0.2, 0.0)])
"""A fixed block whose top right corner is at the origin (m)."""
DIAMOND = np.array([(0.0, 0.0), (0.03, 0.03), (0.0, 0.06), (-0.03, 0.03)])
"""A square turned by 45 degrees, its lowest corner first (m)."""
START = 5.37e-3
"""Distance (m) of a thrown polygon's tip from the corner at the start: not a whole number of
steps of travel, since a tip that ends a step exactly on the corner meets its edges by chance."""
DT_MIN = 1e-10  # s: the world files' minimumTimestep
ENERGY_GAIN = 1e-6
"""Largest rise of energy + lost work, as a fraction of the kinetic energy thrown in."""


def thrown_at_the_corner(folder, shape, heading, offset, speed, spin, dt_max, max_penetration, friction,
                         restitution):
    """A free polygon ``shape`` (k, 2; m, its first point leading) whose first point starts START
    from the block's corner in the direction ``heading`` (rad from +x; between 0 and pi/2 the
    corner's exterior wedge), moved sideways by ``offset`` (m), thrown back along that direction
    at ``speed`` (m/s) with ``spin`` (rad/s), for the time it takes to travel 2 cm: (result, the
    shape about its centroid)."""
    mass, inertia, centred = polygon_mass(shape)
    direction = np.array([np.cos(heading), np.sin(heading)])
    tip = START * direction + offset * np.array([-direction[1], direction[0]])
    body = FreeBody("body", centred, mass, inertia, position=(tip[0] - centred[0, 0], tip[1] - centred[0, 1], 0.0),
                    velocity=(-speed * direction[0], -speed * direction[1], spin))
    folder = write_free_bodies(folder, [body], [("body", "block")], floor=False, gravity=0.0, friction=friction,
                               restitution=restitution, dt_max=dt_max, max_penetration=max_penetration,
                               break_time=0.02 / speed, world={"writeToHistoryEachTimeStep": "1",
                                                               "minimumTimestep": str(DT_MIN)})
    add_fixed_body(folder, "block", BLOCK)
    return run_folder(folder), centred


def deepest(result, shape):
    """The deepest (m) that a point of the polygon went into the block, or a corner of the block
    into the polygon, at any sample."""
    return max(max(depth_inside(world(shape, pose), BLOCK).max(), depth_inside(BLOCK, world(shape, pose)).max())
               for pose in result.q)


@pytest.mark.parametrize("dt_max, max_penetration", [(1e-4, 1e-7), (1e-3, 1e-5)])
def test_a_diamond_thrown_tip_first_at_the_corner_does_not_pass_through_it(tmp_path, dt_max, max_penetration):
    """The diamond's tip flies at 1 m/s along the bisector of the block's corner, straight at
    it. Before, it passed the corner unseen and went on into the block, 1 cm deep by the end of
    the run (maximumTimestep 1e-4 s, maximumPenetration 1e-7 m). Now it stops within
    maximumPenetration of the corner, one impact turns it back, and it leaves with less energy
    than it came with (e = 0.5)."""
    result, shape = thrown_at_the_corner(tmp_path / "diamond", DIAMOND, 0.25 * np.pi, 0.0, 1.0, 0.0, dt_max,
                                         max_penetration, friction=0.3, restitution=0.5)
    assert deepest(result, shape) <= max_penetration
    assert result.state.clock[K.IMPACTS] == 1
    assert result.state.clock[K.OVER_PENETRATIONS] == 0
    tip = world(shape, result.q[-1])[0]
    assert np.hypot(*tip) > 1e-3  # gone from the corner
    assert result.energy[-1] < 0.9 * result.energy[0]
    assert energy_residual(result).min() >= -ENERGY_GAIN * result.energy[0]


@settings(max_examples=30, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    sides=st.integers(3, 8),
    heading=st.floats(0.05, 0.5 * np.pi - 0.05),
    offset=st.floats(-2e-3, 2e-3),
    speed=st.floats(0.2, 3.0),
    spin=st.floats(-30.0, 30.0),
    dt_max=dt_maxima,
    max_penetration=penetrations,
    **contact_laws,
)
def test_no_polygon_thrown_at_a_corner_goes_into_the_block(tmp_path_factory, sides, heading, offset, speed, spin,
                                                           dt_max, max_penetration, friction, restitution):
    """Regular polygons of 3 to 8 sides, a corner leading, thrown at the block's corner from
    anywhere in its exterior wedge, spinning, at the coarse steps and small penetrations the
    manual allows, with the default skin: no point of either body goes deeper into the other
    than maximumPenetration, or than what one minimumTimestep of motion adds, and no energy is
    made."""
    shape = regular_polygon(sides, 0.03)
    # turn the polygon so that its first corner points at the block's corner
    turn = np.arctan2(-np.sin(heading), -np.cos(heading)) - np.arctan2(shape[0, 1], shape[0, 0])
    c, s = np.cos(turn), np.sin(turn)
    shape = shape @ np.array([[c, s], [-s, c]])
    result, centred = thrown_at_the_corner(tmp_path_factory.mktemp("corner") / "model", shape - shape[0], heading,
                                           offset, speed, spin, dt_max, max_penetration, friction, restitution)
    radius = np.hypot(centred[:, 0], centred[:, 1]).max()
    one_min_step = (np.abs(result.u[:, :2]).sum(axis=1) + np.abs(result.u[:, 2]) * radius).max() * DT_MIN
    assert deepest(result, centred) <= max_penetration + one_min_step
    assert result.state.clock[K.MAX_PENETRATION] <= max_penetration + one_min_step
    assert energy_residual(result).min() >= -ENERGY_GAIN * result.energy[0]
