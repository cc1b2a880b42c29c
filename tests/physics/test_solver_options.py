"""World-file solver options that act only when the contact problem goes wrong: an LCP that ends
in a ray (Painlevé's paradox), the pivot limit, and ZeroVelocityTolerance, with the log lines
that logLCPUnboundedRay and logLCPMaxNumberOfIterations ask for."""

import warnings

import numpy as np
import pytest

from mbds.data.legacy import event_alerts
from mbds.kernel import layout as K
from mbds.model.load import load_model
from tests.physics.models import BodyOnFloor, rectangle, regular_polygon, run_folder

pytestmark = pytest.mark.physics

LENGTH, THICKNESS, MASS = 1.0, 0.01, 1.0  # m, m, kg
THETA = np.radians(60.0)


def painleve_rod(friction: float, **world) -> BodyOnFloor:
    """A thin uniform rod at THETA to the floor, its lower end on the floor sliding away from
    its upper end at 1 m/s, under gravity."""
    shape = rectangle(LENGTH, THICKNESS)
    c, s = np.cos(THETA), np.sin(THETA)
    lowest = -(shape @ np.array([[c, s], [-s, c]]))[:, 1].min()
    return BodyOnFloor(shape, MASS, MASS * (LENGTH**2 + THICKNESS**2) / 12.0, position=(0.0, lowest, THETA),
                       velocity=(-1.0, 0.0, 0.0), friction=friction, break_time=0.02,
                       extra={key: str(value) for key, value in world.items()})


def codes(result) -> np.ndarray:
    return result.events[:, 1].astype(int) if len(result.events) else np.zeros(0, int)


def alerts(folder, result) -> list[str]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return event_alerts(result.events, load_model(folder))


def painleve_limit(theta: float) -> float:
    """The friction coefficient above which the sliding rod's contact problem has no solution:
    the normal acceleration of the contact point is b + a lambda_N with
    a = (1 + 3 cos² theta - 3 mu sin theta cos theta) / m for the uniform rod, negative for
    mu > (1 + 3 cos² theta) / (3 sin theta cos theta) (Painlevé 1895; Stewart, SIAM Review 42,
    2000, Sec. 3: the rod's example; 4/3 at its smallest, here 1.347)."""
    return (1.0 + 3.0 * np.cos(theta) ** 2) / (3.0 * np.sin(theta) * np.cos(theta))


@pytest.mark.parametrize("logged", [1, 0])
def test_painleve_paradox_ends_the_force_lcp_in_a_ray(tmp_path, logged):
    """Above Painlevé's friction limit the LCP of the contact forces has no solution: Lemke's
    method ends in an unbounded ray, counted as an LCP failure and logged when
    logLCPUnboundedRay = 1; the run goes on (the contact resolves by an impact) to its end."""
    assert painleve_limit(THETA) < 2.0
    folder = painleve_rod(2.0, logLCPUnboundedRay=logged).write(tmp_path)
    result = run_folder(folder)
    assert (codes(result) == K.EVENT_LCP_RAY).any()
    assert result.state.clock[K.LCP_FAILURES] >= 1 and result.complete
    rays = [line for line in alerts(folder, result) if "LCP unbounded ray" in line]
    assert bool(rays) == bool(logged)


def test_below_painleves_limit_the_rod_slides_without_failure(tmp_path):
    assert painleve_limit(THETA) > 1.0
    result = run_folder(painleve_rod(1.0, logLCPUnboundedRay=1).write(tmp_path))
    assert not (codes(result) == K.EVENT_LCP_RAY).any() and result.state.clock[K.LCP_FAILURES] == 0


@pytest.mark.parametrize("logged", [1, 0])
def test_the_pivot_limit_is_logged_when_asked(tmp_path, logged):
    """A pivot limit of 1 cannot solve the LCP of a ball resting on the floor: each attempt stops
    at the limit, the step counts an LCP failure, and logLCPMaxNumberOfIterations = 1 logs it."""
    shape = regular_polygon(16, 0.05)
    model = BodyOnFloor(shape, 1.0, 0.5 * 0.05**2, position=(0.0, 0.05 + 1e-3, 0.0), break_time=0.05,
                        dt_min=1e-6, extra={"logLCPMaxNumberOfIterations": str(logged)})
    folder = model.write(tmp_path)
    result = run_folder(folder, max_pivots=1)
    assert (codes(result) == K.EVENT_LCP_MAX_PIVOTS).any()
    assert result.state.clock[K.LCP_FAILURES] >= 1
    limits = [line for line in alerts(folder, result) if "maximum number of iterations" in line]
    assert bool(limits) == bool(logged)
    assert not [line for line in alerts(folder, result) if "unbounded ray" in line]


@pytest.mark.parametrize(("speed", "fast"), [(2e-3, True), (0.5e-3, False)])
def test_zero_velocity_tolerance_decides_what_is_an_impact(tmp_path, speed, fast):
    """Without gravity a block approaches the floor at ``speed``; ZeroVelocityTolerance = 1e-3 m/s,
    maximumPenetration 1e-7 m. Faster than the tolerance, the impact law applies as the contact
    closes; slower, the approach counts as none until a maximum step would take the contact
    beyond maximumPenetration, and the impact law applies there. Either way e = 1 sends the
    block back at its speed, after one impact."""
    model = BodyOnFloor(rectangle(0.1, 0.02), 1.0, 1.0 * (0.1**2 + 0.02**2) / 12.0,
                        position=(0.0, 0.01 + 2e-5, 0.0), velocity=(0.0, -speed, 0.0), gravity=(0.0, 0.0),
                        restitution=1.0, break_time=0.1, extra={"ZeroVelocityTolerance": "1e-3"})
    result = run_folder(model.write(tmp_path))
    assert result.state.clock[K.IMPACTS] == 1
    assert result.u[-1, 1] == pytest.approx(speed, rel=1e-9)
    deepest = -(result.q[:, 1].min() - 0.01)  # m
    if fast:
        assert deepest < 1e-12
    else:
        assert 0.5e-7 < deepest <= 1e-7 * (1 + 1e-6)
