"""The world file's [generalizedStart] section (an mbds extension) sets the start values of free
coordinates g'name; files without it behave as the original program (start at 0, at rest)."""

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from mbds.errors import ModelError
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import simulate

ROOT = Path(__file__).resolve().parents[2]

WORLD = """[main]
numberOfGeneralizedCoordinates = 1
maximumTimestep = 1e-3
breakTime = 1
[bodies]
body1 = mass2.bdy
"""


def oscillator(folder: Path, start: str | None) -> Path:
    """A free coordinate g'phi with phi'' = -k phi (mass 1) beside a fixed body."""
    folder.mkdir(parents=True)
    for name in ("mass2.bdy", "mass2.exs"):
        shutil.copy(ROOT / "campaigns" / "2mass" / name, folder / name)
    world = WORLD + (f"[generalizedStart]\n{start}\n" if start is not None else "")
    files = {
        "osc.wld": world,
        "osc.cns": "c'k = 4\n",
        "osc.gc": "g'phi[t]\n",
        "osc.mmx": "1\n",
        "osc.hv": "-c'k*g'phi[t]\n",
        "osc.me": "(Derivative[1][g'phi][t]^2 + c'k*g'phi[t]^2)/2\n",
    }
    for name, text in files.items():
        (folder / name).write_text(text)
    return folder / "osc.wld"


def test_free_coordinates_start_at_rest_without_the_section(tmp_path):
    model = load_model(oscillator(tmp_path / "a", None), compile=False)
    assert model.q0.tolist() == [0.0] and model.qd0.tolist() == [0.0]


def test_start_values_and_the_motion_they_give(tmp_path):
    """phi(t) = A cos(w t) + (v0 / w) sin(w t), w = sqrt(k) = 2 rad/s (harmonic oscillator)."""
    model = load_model(oscillator(tmp_path / "b", "g'phi = 0.3, c'k/10"))
    assert model.q0.tolist() == [0.3] and model.qd0.tolist() == [0.4]
    result = simulate(model, RunSettings(1.0, 0))
    t = result.time
    exact = 0.3 * np.cos(2 * t) + 0.2 * np.sin(2 * t)
    np.testing.assert_allclose(result.q[:, 0], exact, atol=1e-6)
    assert math.isclose(result.energy[-1], result.energy[0], rel_tol=1e-6)


def test_position_only_starts_at_rest(tmp_path):
    model = load_model(oscillator(tmp_path / "c", "g'phi[t] = -0.1"), compile=False)
    assert model.q0.tolist() == [-0.1] and model.qd0.tolist() == [0.0]


@pytest.mark.parametrize(
    "entry, message",
    [
        ("g'psi = 1", "g'psi is not a free coordinate"),
        ("b'mass2'x = 1", "is not a free coordinate"),
        ("g'phi = 1, 2, 3", "needs 'position' or 'position, velocity'"),
        ("g'phi = c'unknown", "unknown constant"),
    ],
)
def test_bad_entries_name_the_world_file_and_line(tmp_path, entry, message):
    world = oscillator(tmp_path / "d", entry)
    with pytest.raises(ModelError) as caught:
        load_model(world, compile=False)
    assert message in str(caught.value) and f"{world}:8:" in str(caught.value)  # the entry, below [generalizedStart]
