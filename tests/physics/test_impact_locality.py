"""An impact changes the velocities of the bodies it couples, and of no other body.

Source: the impulses of an impact act through the contact directions and the mass matrix,
u+ = u- + M^-1 W Lambda (Pfeiffer and Glocker, "Multibody Dynamics with Unilateral Contacts",
Wiley 1996, ch. 6; docs/theory.md §4): with M block diagonal over free bodies, a body with no
contact in the impacting group (mbds.kernel.components) gets no impulse, whatever its own
contacts do in that step.

Two boxes on the floor, 1 m apart, ZeroVelocityTolerance 0.01 m/s, maximumTimestep 1 ms: box A
touches the floor and sinks into it at 5 mm/s, slower than the tolerance (no impact of its own
for about 19 ms, until maximumPenetration would be passed within a maximum step) and faster than
the rest velocity, 0.01 maximumPenetration / maximumTimestep = 1 mm/s (below which the speed
left at rest decays, docs/theory.md §3); box B falls from 0.123 mm and
strikes the floor at 49 mm/s after 5 ms. A's velocity must not change at B's impact. (When an
impact took every closed contact, A's sinking contacts were part of B's impact and A was stopped
there.)
"""

import numpy as np
import pytest

from tests.physics.models import FreeBody, rectangle, run_folder, write_free_bodies

pytestmark = pytest.mark.physics

WIDTH, HEIGHT, MASS, SINK, DROP = 0.1, 0.05, 1.0, -0.005, 1.2263e-4  # m, m, kg, m/s, m


def test_a_body_outside_the_impacting_group_keeps_its_velocity(tmp_path):
    inertia = MASS * (WIDTH**2 + HEIGHT**2) / 12.0
    boxes = [FreeBody("a", rectangle(WIDTH, HEIGHT), MASS, inertia, (-0.5, HEIGHT / 2, 0.0), (0.0, SINK, 0.0)),
             FreeBody("b", rectangle(WIDTH, HEIGHT), MASS, inertia, (0.5, HEIGHT / 2 + DROP, 0.0))]
    folder = write_free_bodies(tmp_path / "boxes", boxes, [("a", "floor"), ("b", "floor")], floor=True, gravity=9.81,
                               friction=0.5, restitution=0.5, dt_max=1e-3, max_penetration=1e-4, break_time=0.012,
                               world={"ZeroVelocityTolerance": "0.01", "writeToHistoryMultipleOfMaximumTimestep": "1"})
    result = run_folder(folder)
    t, vy_a, vy_b = result.time, result.u[:, 1], result.u[:, 4]
    struck = np.flatnonzero(vy_b > 0.0)  # B bounces (e = 0.5)
    assert len(struck), "box B did not strike the floor"
    assert 0.004 < t[struck[0]] < 0.007
    assert np.abs(vy_a[t <= 0.011] - SINK).max() < 1e-9  # A sinks on, unaffected by B's impact
