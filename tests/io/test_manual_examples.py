"""Every example file of the manual's chapters 2 and 3 parses, with the manual's meaning."""

import warnings
from pathlib import Path

import numpy as np
import pytest

from mbds.io.ini import Located
from mbds.io.text import MAXINT, read_text
from mbds.io.watches import WatchItem
from tests.io.formats import FORMATS

MANUAL = Path(__file__).resolve().parents[1] / "data" / "manual"
FILES = sorted(p for p in MANUAL.iterdir() if p.suffix[1:] in FORMATS)


def parse(name: str):
    path = MANUAL / name
    parser = FORMATS[path.suffix[1:]][0]
    with warnings.catch_warnings():
        warnings.simplefilter("error" if name != "example.wtc" else "ignore")
        return parser(read_text(path), path)


@pytest.mark.parametrize("path", [p for p in FILES if p.name != "example.wtc"], ids=lambda p: p.name)
def test_manual_file_parses_without_warnings(path):
    parse(path.name)


def test_unused_cycle_section_is_warned_about():
    """The manual's .wtc example has [rect3:1] with reshapingCycles = 1: never used."""
    with pytest.warns(UserWarning, match=r"example.wtc:36: \[rect3:1\] is never used"):
        FORMATS["wtc"][0](read_text(MANUAL / "example.wtc"), MANUAL / "example.wtc")


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_round_trip(path):
    parser, formatter = FORMATS[path.suffix[1:]]
    first = parse(path.name)
    again = parser(formatter(first), path)
    assert again == first
    assert formatter(again) == formatter(first)


def test_world_defaults_and_manual_spelling():
    world = parse("defaults.wld")
    s = world.settings
    assert s.number_of_coordinates == 1
    assert (s.lcp_pivot_tolerance_min, s.lcp_pivot_tolerance_max, s.lcp_lexico_zero_tolerance) == (1e-14, 1e-10, 1e-8)
    assert s.zero_velocity_tolerance == 1e-18 and s.maximum_displacement_factor == 0.5
    assert s.break_time == Located("1")
    assert [b.text for b in world.bodies] == ["rect.bdy", "circle.bdy"]
    woodpecker = parse("WoodpeckerToy.wld")
    assert woodpecker.settings.number_of_coordinates == 4
    assert len(woodpecker.bodies) == 7
    assert woodpecker.resolve("current.cns").name == "WoodpeckerToy.cns"


def test_job_values():
    job = parse("defaults.job")
    assert job.versions == [1, 5, 9]
    assert job.settings.max_minutes_for_job == MAXINT
    wear = parse("wearballs.job")
    assert wear.versions == list(range(14))
    assert wear.settings.create_next_version_at_end and wear.settings.max_minutes_for_jobs == 300
    assert wear.world_path().name == "wearballs.wld"


def test_body_values():
    rect = parse("rect.bdy")
    assert rect.main.name == "rect" and rect.main.virtual_to_body == ""
    assert rect.main.skin_thickness == 0.001 and rect.main.correct_origin
    assert rect.mass.mass == 1 and rect.mass.inertia_zz == 0.004
    assert rect.position.y == 1.1 and rect.velocity.y == 1.1
    mass1 = parse("mass1.bdy")
    assert mass1.main.density == 2500 and mass1.position.rz == 3.1459 and mass1.velocity.y == -1
    assert mass1.mass is None


def test_shape_points():
    shape = parse("mass1.exs")
    expected = [(0.07, 0.05), (0, 0.06), (-0.07, 0.05), (-0.07, -0.05), (0.07, -0.05), (0.07, 0.05)]
    assert np.array_equal(shape.points, np.array(expected))


def test_coordinates_with_mixed_quotes():
    gc = parse("2Mass.gc")
    assert [str(c) for c in gc.coordinates] == ["b'mass1'x[t]", "b'mass1'y[t]", "b'mass1'Rz[t]"]
    example = parse("example.gc")
    assert example.coordinates[3].kind == "g" and example.coordinates[3].name == "relative1"


def test_dependent_coordinates_blocks():
    dc = parse("example.dc")
    bird_x, bird_y = dc.coordinates
    assert str(bird_x.coordinate) == "b'bird'x[t]"
    assert [e.text for e in bird_x.definition] == ["c'lG + c'lM", "0", "0"]
    assert [e.text for e in bird_x.jacobian] == ["0", "0", "0"]
    assert bird_x.jacobian_scalar.text == "c'lG + c'lM"
    assert len(bird_y.definition) == 1
    woodpecker = parse("WoodpeckerToy.dc").coordinates[0]
    assert woodpecker.definition[0].text.startswith("c`lG*Cos[")
    assert len(woodpecker.jacobian) == 4


def test_constants_and_expressions():
    assert parse("example.cns").values == {"force1x": 1.0, "force1y": 2.0, "gravityz": 9.81}
    hv = parse("example.hv")
    assert hv.expressions[1].text == "c'force1y + c'gravityz b'rect'm"
    assert parse("2Mass.me").expressions[0].text.startswith("(b'mass1'm*")


def test_mass_matrix_rows_split_by_spaces_and_tabs():
    spaces = parse("2Mass.mmx")
    tabs = parse("example.mmx")
    assert [[e.text for e in row] for row in spaces.rows] == [
        ["b'mass1'm", "0", "0"],
        ["0", "b'mass1'm", "0"],
        ["0", "0", "b'mass1`Jzz"],
    ]
    assert [len(row) for row in tabs.rows] == [3, 3, 3]


def test_contact_sections():
    cop = parse("example.cop")
    pair, everything = cop.sections
    assert (pair.first, pair.second) == ("rect1", "rect2")
    assert pair.law.friction.text == "0.5-1/vRel"
    assert (everything.first, everything.second) == ("rect1", None)
    woodpecker = parse("WoodpeckerToy.cop")
    assert [s.title for s in woodpecker.sections] == ["stick-ringSideR", "stick-ringSideL", "stick-bird"]
    assert woodpecker.sections[2].law.restitution_normal.text == "0.5"


def test_watches_every_option():
    wtc = parse("example.wtc")
    assert wtc.constants_update.bodies == ["brushpin1", "brushpin2", "brushpin3"]
    assert wtc.constants_update.max_change == 0.2e-6
    assert wtc.change_constants.changes == [-1.0, -0.03]
    assert wtc.reshape_window.standard_deviation_range == (-100.0, 100.0)
    assert wtc.body_balanced_update.max_change == 0.1e-6
    by_title = {w.title: w for w in wtc.bodies}
    assert by_title["rect1"].items == [WatchItem(1, 1), WatchItem(2, 2), WatchItem(5, 10)]
    assert by_title["rect3"].items == [WatchItem(None, None)]
    assert by_title["rect3:1"].items == [WatchItem(6, 15)]
    assert by_title["rect3:1"].options.max_change == [1e-6, -1e-6]
    assert by_title["rect4"].items == [WatchItem(None, None, combined=True)]
    assert by_title["rect5"].items == [WatchItem(1, 3, combined=True), WatchItem(4, 5, absolute=True)]
    assert [w.title for w in [wtc.section_for("rect3", v) for v in (0, 1, 2)]] == ["rect3:0"] * 3
    assert by_title["rect5"].items[1].groups(10) == [[4], [5]]
    assert by_title["rect4"].items[0].groups(4) == [[0, 1, 2, 3]]
