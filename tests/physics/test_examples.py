"""The example models: energy balance, reproducible randomized runs and the woodpecker's
limit cycle."""

import numpy as np
import pytest

from tests.physics.limit_cycle import cycle_figures, velocity_jumps
from tests.physics.models import CAMPAIGNS, energy_residual, run_folder

pytestmark = pytest.mark.physics

BALANCE_TOLERANCE = 1e-8
"""Largest |E_me(0) - E_me(t) - lost(t) + drive(t)| allowed, relative to the energy scale of the
run (the largest of |E_me|, lost and drive work). Measured: 2mass 1e-14, wearballs 5e-10,
woodpecker (0.3 s) 2e-9."""


@pytest.mark.parametrize("name, break_time", [("2mass", 0.5), ("wearballs", 0.5), ("woodpecker", 0.3)])
def test_energy_balance_of_the_examples(name, break_time):
    result = run_folder(CAMPAIGNS / name, break_time)
    assert result.time[-1] == pytest.approx(break_time)
    assert result.lost[-1] > 0.0
    scale = max(np.abs(result.energy).max(), np.abs(result.lost).max(), np.abs(result.drive).max())
    residual = energy_residual(result)
    print(f"{name}: energy scale {scale:.4g} J, largest balance residual {np.abs(residual).max() / scale:.2e}")
    assert np.abs(residual).max() < BALANCE_TOLERANCE * scale


def test_same_seed_gives_bit_identical_runs():
    runs = [run_folder(CAMPAIGNS / "wearballs", 0.3, seed=seed, lexico_range=(1e-9, 1e-7)) for seed in (11, 11, 12)]
    first, again, other = runs
    for name in ("time", "q", "u", "a", "energy", "lost", "drive", "watches", "events"):
        assert np.array_equal(getattr(first, name), getattr(again, name), equal_nan=True), name  # NaN: no temperature
    assert np.array_equal(first.state.clock, again.state.clock)
    assert not np.array_equal(first.state.rng, other.state.rng)  # the other seed drew other tolerances


SKIP = 1.0  # s of transient left out of the woodpecker figures
PERIOD_SPREAD = 0.02  # largest relative deviation of a period from their mean


def test_woodpecker_settles_into_a_periodic_motion():
    """Swings are counted between upward crossings of the bird angle through -0.05 rad, and a
    period is the smallest number of swings after which their durations repeat; the small-angle
    reference (benchmarks/woodpecker_reference.py) has a period of one swing of 146 ms."""
    result = run_folder(CAMPAIGNS / "woodpecker", 2.0)
    impacts = velocity_jumps(result.time, result.u, result.a, (1.0, 0.01, 0.015), 1e-3)
    figures = cycle_figures(result.time, result.q, impacts, SKIP)
    print("\n".join(figures.lines()))
    assert len(figures.periods) >= 3
    assert figures.spread() < PERIOD_SPREAD
    assert figures.bird_limits[1] == pytest.approx(0.1203, abs=2e-3)  # the beak reaches the pole
