"""The examples rebuilt from their energies by the scripts under campaigns/ equal the
hand-written model files: expressions at random states to 1e-12, every other file by its
parsed contents, and the runs bit for bit."""

import dataclasses
import warnings
from pathlib import Path

import numpy as np
import pytest

from mbds.expr.codegen import generate_source
from mbds.model.load import assemble_model
from tests.build.compare import CAMPAIGNS, expression_differences, load_script, read_quietly
from tests.physics.models import run_folder

EXAMPLES = ["2mass", "wearballs", "woodpecker"]


def woodpecker_variant() -> str:
    """The bird position of the example's own woodpecker.dc: the beak variant declares c'lS."""
    constants = (CAMPAIGNS / "woodpecker" / "woodpecker.cns").read_text()
    return "beak" if "c'lS" in constants else "exact"


@pytest.fixture(scope="module")
def rebuilt(tmp_path_factory) -> dict[str, Path]:
    folders = {}
    for name in EXAMPLES:
        script = load_script(CAMPAIGNS / name / f"build_{name}.py")
        folder = tmp_path_factory.mktemp(name)
        args = (woodpecker_variant(),) if name == "woodpecker" else ()
        script.build(folder, *args)
        folders[name] = folder
    return folders


@pytest.mark.parametrize("name", EXAMPLES)
def test_equations_equal_the_hand_written_ones(rebuilt, name):
    assert expression_differences(read_quietly(rebuilt[name]), read_quietly(CAMPAIGNS / name)) == {}


@pytest.mark.parametrize("name", EXAMPLES)
def test_other_files_equal_the_hand_written_ones(rebuilt, name):
    built, written = read_quietly(rebuilt[name]), read_quietly(CAMPAIGNS / name)
    settings = [dataclasses.replace(f.world.settings, break_time=None) for f in (built, written)]
    assert settings[0] == settings[1]
    assert float(built.world.settings.break_time.text) == float(written.world.settings.break_time.text)
    assert [b.text for b in built.world.bodies] == [b.text for b in written.world.bodies]
    assert built.coordinates == written.coordinates
    assert [c.coordinate for c in built.dependent.coordinates] == [c.coordinate for c in written.dependent.coordinates]
    assert built.constants == written.constants
    assert built.shapes == written.shapes
    for ours, theirs in zip(built.bodies, written.bodies):
        assert ours.main == theirs.main
        assert ours.mass == theirs.mass
        for pose in ("position", "velocity"):  # the files round dependent start values to 10 digits
            a, b = getattr(ours, pose), getattr(theirs, pose)
            assert np.allclose([a.x, a.y, a.rz], [b.x, b.y, b.rz], rtol=0, atol=1e-10), (ours.main.name, pose)
    laws = [[(s.first, s.second, *(str(v) for v in vars(s.law).values())) for s in f.contacts.sections]
            for f in (built, written)]
    assert laws[0] == laws[1]
    watches = [[(w.title, w.options, w.items) for w in f.watches.bodies] for f in (built, written)]
    assert watches[0] == watches[1]


@pytest.mark.parametrize("name", EXAMPLES)
def test_generated_code_is_the_same_but_for_the_energy(rebuilt, name):
    """Same code means bit-identical motion. Only the woodpecker's energy function differs:
    its .me file groups the terms by hand, ((m_ring + m_bird) ẏ² + ...)/2, the builder writes
    T + V as the energies are declared; the two sums round differently in the last bits."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # 2mass: an origin off the centroid, in both
        built, written = (assemble_model(read_quietly(f)) for f in (rebuilt[name], CAMPAIGNS / name))
    ours, theirs = (generate_source(m.expressions) for m in (built, written))
    if name != "woodpecker":
        assert ours == theirs
    else:
        assert ours != theirs
        assert _without_energy(ours) == _without_energy(theirs)
    assert np.array_equal(built.parameters.values, written.parameters.values)
    assert np.array_equal(built.q0, written.q0) and np.array_equal(built.qd0, written.qd0)


def _without_energy(source: str) -> str:
    start = source.index("def mechanical_energy")
    end = source.index("\n@", start)
    return source[:start] + source[end:]


@pytest.mark.parametrize("name, break_time", [
    ("2mass", 0.5),
    ("wearballs", 0.3),
    # two compilations (the energy function differs); the generated-code test covers the motion
    pytest.param("woodpecker", 0.05, marks=pytest.mark.slow),
])
def test_runs_are_bit_identical(rebuilt, name, break_time):
    ours, theirs = run_folder(rebuilt[name], break_time), run_folder(CAMPAIGNS / name, break_time)
    for field in ("time", "q", "u", "a", "lost", "drive", "watches", "events"):
        assert np.array_equal(getattr(ours, field), getattr(theirs, field), equal_nan=True), field
    if name == "woodpecker":
        assert np.abs(ours.energy - theirs.energy).max() <= 1e-15 * np.abs(theirs.energy).max()
    else:
        assert np.array_equal(ours.energy, theirs.energy)


@pytest.mark.parametrize("variant", ["exact", "small-angle", "beak"])
def test_every_woodpecker_bird_position_builds_a_model_mbds_reads(tmp_path, variant):
    script = load_script(CAMPAIGNS / "woodpecker" / "build_woodpecker.py")
    script.build(tmp_path, variant)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = assemble_model(read_quietly(tmp_path))
    sides = [f"b'ringSide{s}'{c}[t]" for s in "UL" for c in ("x", "y", "Rz")] if variant == "beak" else []
    assert [str(c) for c in model.dependent] == ["b'bird'x[t]", "b'bird'y[t]", *sides]
    if variant == "small-angle":  # y = y_ring + lM Rz_ring + lG Rz_bird: J = (1, lM, lG), j = 0
        dc = read_quietly(tmp_path).dependent.coordinates[1]
        assert [e.text for e in dc.jacobian] == ["1", "c'lM", "c'lG"] and dc.jacobian_scalar.text == "0"


def test_the_four_dof_woodpecker_is_the_shipped_campaign(tmp_path):
    """``--four-dof`` writes the manual's seven-body model (section 2.3.2 world file order, ring x
    generalized) with the same expressions as campaigns/woodpecker4dof."""
    script = load_script(CAMPAIGNS / "woodpecker" / "build_woodpecker.py")
    script.build(tmp_path, "beak", True)
    ours, theirs = read_quietly(tmp_path), read_quietly(CAMPAIGNS / "woodpecker4dof")
    assert expression_differences(ours, theirs) == {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = assemble_model(ours)
    assert [b.name for b in model.bodies] == ["ring", "stick", "bird", "ringF", "foot", "ringSideR", "ringSideL"]
    assert [str(c) for c in model.coordinates] == ["b'ring'x[t]", "b'ring'y[t]", "b'ring'Rz[t]", "b'bird'Rz[t]"]
