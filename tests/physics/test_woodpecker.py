"""The woodpecker toy's limit cycle against its published values.

Sources: Leine, Glocker, van Campen, "Nonlinear dynamics and modeling of various wooden toys
with impact and friction", J. Vib. Control 9 (2003): period 0.1452 s; Siconos' Woodpecker
example (siconos-tutorials, ``Woodpecker.ref``, same constants): period 0.1461 s, descent of
the sleeve 0.133 m/s, bird angle -0.530 .. 0.120 rad, sleeve angle +-0.1036 rad.
"""

import pytest

from tests.physics.limit_cycle import cycle_figures, velocity_jumps
from tests.physics.models import CAMPAIGNS, run_folder

pytestmark = pytest.mark.physics

SKIP = 1.0  # s of transient left out
PUBLISHED_PERIOD = (0.1452, 0.1461)  # s: Leine et al. 2003, Siconos Woodpecker.ref
SICONOS = {"descent": 0.133, "bird": (-0.530, 0.120), "ring": 0.1036}


@pytest.fixture(scope="module")
def figures():
    result = run_folder(CAMPAIGNS / "woodpecker", 2.0)
    impacts = velocity_jumps(result.time, result.u, result.a, (1.0, 0.01, 0.015), 1e-3)
    found = cycle_figures(result.time, result.q, impacts, SKIP)
    print("\n".join(found.lines()))
    return found


def test_the_limit_cycle_has_period_one_with_five_impacts(figures):
    """The published cycle repeats after one swing, with the beak striking once and five impacts
    in all (Leine et al. 2003, Fig. of the limit cycle; Siconos Woodpecker.ref)."""
    assert figures.swings == 1
    assert len(figures.periods) >= 5
    assert figures.spread() < 0.005
    assert figures.impacts_per_period == pytest.approx(5.0, abs=0.2)
    assert figures.bird_limits[1] == pytest.approx(SICONOS["bird"][1], rel=0.03)


def test_the_period_is_the_published_one(figures):
    assert PUBLISHED_PERIOD[0] * 0.99 <= figures.period <= PUBLISHED_PERIOD[1] * 1.01


def test_amplitudes_and_descent_match_the_siconos_reference(figures):
    assert figures.descent_speed == pytest.approx(SICONOS["descent"], rel=0.03)
    assert figures.bird_limits[0] == pytest.approx(SICONOS["bird"][0], rel=0.03)
    assert figures.bird_limits[1] == pytest.approx(SICONOS["bird"][1], rel=0.03)
    assert -figures.ring_limits[0] == pytest.approx(SICONOS["ring"], rel=0.03)
    assert figures.ring_limits[1] == pytest.approx(SICONOS["ring"], rel=0.03)
