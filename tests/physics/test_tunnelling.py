"""No vertex tunnels into the floor, whatever the settings the MBDS manual allows, and no
energy is made.

The step control (docs/theory.md, "Step control") bounds how far any point of a body can move
relative to another over a step (translation plus rotation times radius) and keeps every vertex
that could reach an edge within sight: a vertex ends a step at most maximumPenetration deep,
or, where that would need a step below minimumTimestep, at most what one minimumTimestep of
motion adds (the run then counts an over-penetration). The depths here are measured from the
sampled poses and the shape, independently of the kernel's own contact detection.

The same runs check the energy balance of docs/theory.md §5, E_me(0) − E_me(t) = W_lost(t) −
W_drive(t): without a drive, the mechanical energy plus the work lost in the contacts stays at
its start value, up to what the steps with contacts add in round-off and drift; no run may gain
energy.

All models share the structure of :mod:`tests.physics.models` (one compiled stepper); shapes,
start states and settings vary.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, regular_polygon, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
DENSITY = 1000.0  # kg/m² (per unit depth)
DT_MIN = 1e-10  # s
ENERGY_GAIN = 1e-6
"""Largest rise of energy + lost work, as a fraction of the run's energy scale (130 random runs of
these ranges, 0.3 s past the landing, stayed below 4.5e-8)."""


def polygon_mass(shape: np.ndarray) -> tuple[float, float, np.ndarray]:
    """(mass (kg), centroidal inertia (kg m²), shape about its centroid) of a uniform polygon."""
    x, y = shape[:, 0], shape[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * cross.sum()
    cx = ((x + xn) * cross).sum() / (6.0 * area)
    cy = ((y + yn) * cross).sum() / (6.0 * area)
    centred = shape - [cx, cy]
    x, y = centred[:, 0], centred[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    polar = ((x * x + x * xn + xn * xn + y * y + y * yn + yn * yn) * cross).sum() / 12.0
    return DENSITY * area, DENSITY * polar, centred


def lowest_vertex(shape: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Height (m) of the lowest vertex at every sampled pose q (samples, 3)."""
    c, s = np.cos(q[:, 2:3]), np.sin(q[:, 2:3])
    return (q[:, 1:2] + s * shape[:, 0] + c * shape[:, 1]).min(axis=1)


dt_maxima = st.floats(-5.0, -3.0).map(lambda e: 10.0**e)
"""maximumTimestep (s), 1e-5 … 1e-3, evenly in its logarithm."""
penetrations = st.floats(-9.0, -5.0).map(lambda e: 10.0**e)
"""maximumPenetration (m), 1e-9 … 1e-5, evenly in its logarithm (skins at their default)."""
contact_laws = {"friction": st.floats(0.0, 1.0), "restitution": st.floats(0.0, 0.8)}
"""Friction coefficient and normal restitution of the contact."""

shapes = st.one_of(
    st.builds(lambda long, aspect: rectangle(long / aspect, long),
              st.floats(0.05, 0.4), st.floats(1.0, 10.0)),
    st.builds(regular_polygon, st.integers(3, 12), st.floats(0.03, 0.2)),
)


@settings(max_examples=24, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    shape=shapes,
    tilt=st.floats(0.0, np.pi),
    drop=st.floats(0.0, 0.05),
    spin=st.floats(-10.0, 10.0),
    dt_max=dt_maxima,
    max_penetration=penetrations,
    **contact_laws,
)
def test_no_vertex_goes_deeper_than_the_allowed_penetration_nor_gains_energy(
    tmp_path_factory, shape, tilt, drop, spin, dt_max, max_penetration, friction, restitution,
):
    mass, inertia, shape = polygon_mass(shape)
    c, s = np.cos(tilt), np.sin(tilt)
    lowest = (s * shape[:, 0] + c * shape[:, 1]).min()
    fall = np.sqrt(2.0 * drop / G)
    folder = BodyOnFloor(
        shape, mass, inertia, position=(0.0, drop - lowest, tilt), velocity=(0.0, 0.0, spin), friction=friction,
        restitution=restitution, dt_min=DT_MIN, dt_max=dt_max, max_penetration=max_penetration,
        break_time=fall + 0.1,
    ).write(tmp_path_factory.mktemp("tunnel") / "model")
    result = run_folder(folder)
    depth = -lowest_vertex(shape, result.q).min()
    radius = np.hypot(shape[:, 0], shape[:, 1]).max()
    speed = np.abs(result.u[:, :2]).sum(axis=1) + np.abs(result.u[:, 2]) * radius
    one_min_step = (speed.max() + G * DT_MIN) * DT_MIN
    assert depth <= max_penetration + one_min_step
    assert result.state.clock[K.MAX_PENETRATION] <= max_penetration + one_min_step
    assert -lowest_vertex(shape, result.q[-1:])[0] <= max_penetration + one_min_step  # still on the floor
    # energy scale: what the run turns over, at least the work of lifting the body by 1 cm
    scale = max(result.energy[0] - result.energy.min(), mass * G * 0.01)
    assert (result.energy + result.lost - result.drive - result.energy[0]).max() <= ENERGY_GAIN * scale
