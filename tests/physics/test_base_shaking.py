"""A block standing on a floor that is shaken horizontally: rest, rocking or sliding, by the
criteria for the initiation of rigid-body modes.

A rigid block of half-width b and half-height h on a base with horizontal acceleration of peak
a = A ω² stays at rest on the base while a < μ g and a < g b / h; it starts to rock when
a > g b / h with μ > b / h, and to slide when a > μ g with μ < b / h (Housner, Bull. Seism. Soc.
Am. 53, 1963, for the rocking threshold; Shenton, J. Eng. Mech. 122, 1996, for the three modes).
The floor is a driven body (a dependent coordinate x(t) = A sin ωt), and the block starts with
the floor's speed, so at rest it moves with the floor exactly.
"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import BodyOnFloor, rectangle, run_folder

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
HALF_WIDTH, HALF_HEIGHT, MASS = 0.05, 0.2, 1.0  # m, m, kg: b / h = 0.25
OMEGA = 4.0 * np.pi  # rad/s
ROCKING = G * HALF_WIDTH / HALF_HEIGHT / OMEGA**2  # m: the amplitude at which rocking starts


def shaken(folder, amplitude: float, friction: float, dt_max: float, max_penetration: float):
    """The block on the floor shaken with ``amplitude`` (m) for 1 s: (result, the block's slide
    on the floor (m) at each sample)."""
    a, w = amplitude, OMEGA
    block = BodyOnFloor(rectangle(2.0 * HALF_WIDTH, 2.0 * HALF_HEIGHT), MASS,
                        MASS * (HALF_WIDTH**2 + HALF_HEIGHT**2) / 3.0, position=(0.0, HALF_HEIGHT, 0.0),
                        velocity=(a * w, 0.0, 0.0), friction=friction, dt_max=dt_max,
                        max_penetration=max_penetration, break_time=1.0)
    folder = block.write(folder)
    (folder / "model.dc").write_text(
        f"%%%new%%%\nb'floor'x[t]\n%%definition\n{a!r}*Sin[{w!r}*t]\n{a * w!r}*Cos[{w!r}*t]\n"
        f"-({a * w * w!r}*Sin[{w!r}*t])\n%%J\n0\n0\n0\n%%j\n-({a * w * w!r}*Sin[{w!r}*t])\n")
    result = run_folder(folder)
    return result, result.q[:, 0] - a * np.sin(w * result.time)


SETTINGS = [(1e-4, 1e-7), (1e-3, 1e-5)]
"""(maximumTimestep s, maximumPenetration m): fine, and coarse with the default skin."""


@pytest.mark.parametrize("dt_max, max_penetration", SETTINGS)
def test_below_both_thresholds_the_block_moves_with_the_floor(tmp_path, dt_max, max_penetration):
    result, slide = shaken(tmp_path / "rest", 0.98 * ROCKING, 0.8, dt_max, max_penetration)
    assert np.abs(result.q[:, 2]).max() < 1e-12
    assert np.abs(result.q[:, 1] - HALF_HEIGHT).max() < 1e-12
    assert np.abs(slide).max() < 1e-6
    assert result.state.clock[K.IMPACTS] == 0


@pytest.mark.parametrize("dt_max, max_penetration", SETTINGS)
def test_above_the_rocking_threshold_the_block_rocks(tmp_path, dt_max, max_penetration):
    result, slide = shaken(tmp_path / "rock", 1.02 * ROCKING, 0.8, dt_max, max_penetration)
    assert np.abs(result.q[:, 2]).max() > 1e-5
    lowest = result.q[:, 1] - HALF_HEIGHT * np.cos(result.q[:, 2]) - HALF_WIDTH * np.abs(np.sin(result.q[:, 2]))
    assert lowest.min() > -max_penetration * 1.01  # a corner never sinks into the floor by more than allowed


@pytest.mark.parametrize("friction, slides", [(0.23, False), (0.22, True)])
def test_a_slender_friction_cone_lets_the_block_slide_without_rocking(tmp_path, friction, slides):
    """Peak base acceleration 0.225 g, below the rocking threshold 0.25 g."""
    result, slide = shaken(tmp_path / "slide", 0.9 * ROCKING, friction, 1e-4, 1e-7)
    assert np.abs(result.q[:, 2]).max() < 1e-12
    assert (np.abs(slide).max() > 1e-5) == slides
    if not slides:
        assert np.abs(slide).max() < 1e-8
