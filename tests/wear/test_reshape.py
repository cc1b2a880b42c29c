"""Reshaping and constants updates against hand computations."""

import numpy as np
import pytest

from mbds.errors import ModelError
from mbds.io.folder import read_model_files
from mbds.io.watches import ReshapeWindow
from mbds.model.geometry import polygon_properties
from mbds.wear.plan import plan_wear
from mbds.wear.reshape import directions, displacements, loss_window

# an octagon-like square with 8 points, counter-clockwise, side 2, centred at the origin
SQUARE = [(-1, -1), (0, -1), (1, -1), (1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0)]


def write_model(folder, wtc: str, bodies=("a", "b"), cns="c'k = 1\nc'm = 2\n"):
    """A model with bodies of the 8-point square shape (body 'a' moves, others fixed)."""
    folder.mkdir(parents=True, exist_ok=True)
    xs = " ".join(str(x) for x, _ in SQUARE + SQUARE[:1])
    ys = " ".join(str(y) for _, y in SQUARE + SQUARE[:1])
    lines = ["[main]", "numberOfGeneralizedCoordinates = 1", "[bodies]"]
    for i, name in enumerate(bodies):
        lines.append(f"body{i} = {name}.bdy")
        (folder / f"{name}.bdy").write_text(
            f"[main]\nname = {name}\nshapeFile = {name}.exs\ndensity = 1\nthickness = 1\n[startPosition]\nx = {3 * i}\n"
        )
        (folder / f"{name}.exs").write_text(f"points = 9\n%%data\n{xs}\n{ys}\n%%enddata\n")
    (folder / "m.wld").write_text("\n".join(lines) + "\n")
    (folder / "m.gc").write_text("b'a'y[t]\n")
    (folder / "m.mmx").write_text("b'a'm\n")
    (folder / "m.hv").write_text("0\n")
    (folder / "m.cns").write_text(cns)
    (folder / "m.wtc").write_text(wtc)
    return read_model_files(folder)


def test_single_max_change_moves_the_top_point_exactly(tmp_path):
    files = write_model(tmp_path / "m", "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 0.01\n")
    loss = np.array([0.0, 2.0, 4.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    plan = plan_wear(files, {"a": loss, "b": np.zeros(8)}, version=0)
    (wear,) = plan.bodies
    assert wear.displacement == pytest.approx(0.01 * loss / 4.0)
    moved = np.linalg.norm(wear.shape[:-1] - np.array(SQUARE, dtype=float), axis=1)
    assert moved[2] == pytest.approx(0.01)  # the point of highest loss moves by exactly maxChange
    assert np.all(moved[loss == 0] == 0.0)  # points that lost nothing stay
    # inward: the corner (1, -1) moves along (-1, 1)/sqrt(2), the edge point (0, -1) along +y
    assert wear.shape[2] == pytest.approx(np.array([1, -1]) + 0.01 * np.array([-1, 1]) / np.sqrt(2))
    assert wear.shape[1] == pytest.approx([0, -1 + 0.005])
    assert np.array_equal(wear.shape[-1], wear.shape[0])
    assert polygon_properties(wear.shape).area < 4.0


def test_range_wears_high_loss_points_and_grows_unloaded_ones(tmp_path):
    files = write_model(tmp_path / "m", "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 1e-3,-1e-3\n")
    loss = np.array([0.0, 0.0, 8.0, 4.0, 0.0, 0.0, 0.0, 0.0])
    (wear,) = plan_wear(files, {"a": loss}, version=0).bodies
    mean = loss.mean()  # 1.5
    expected = np.where(loss > mean, 1e-3 * (loss - mean) / (8.0 - mean), -1e-3 * (mean - loss) / (mean - 0.0))
    assert wear.displacement == pytest.approx(expected)
    assert wear.displacement[2] == pytest.approx(1e-3)  # most loaded: worn inward by the full amount
    assert wear.displacement[0] == pytest.approx(-1e-3)  # unloaded: grows outward by the full amount


def test_cut_hi_low_values_clips_the_outlier():
    """10 values; cutting 10 % at each end leaves 1..8; the outlier 100 is clipped to 8."""
    loss = np.array([0.0, 1, 2, 3, 4, 5, 6, 7, 8, 100])
    window = loss_window(loss, ReshapeWindow(cut_hi_low_values=10.0))
    assert (window.low, window.high, window.mean) == (1.0, 8.0, 4.5)
    clipped, moves = displacements(loss, window, [0.1])
    assert clipped.tolist() == [1, 1, 2, 3, 4, 5, 6, 7, 8, 8]
    assert moves == pytest.approx(0.1 * clipped / 8.0)
    _, plain = displacements(loss, loss_window(loss, ReshapeWindow()), [0.1])
    assert plain == pytest.approx(0.1 * loss / 100.0)  # without the cut the outlier dominates


def test_standard_deviation_range_narrows_the_window():
    loss = np.array([0.0, 0.0, 1.0, 1.0, 2.0, 2.0])
    mean, sigma = loss.mean(), loss.std()  # 1, sqrt(2/3)
    window = loss_window(loss, ReshapeWindow(standard_deviation_range=(-0.5, 0.5)))
    assert window.low == pytest.approx(mean - 0.5 * sigma) and window.high == pytest.approx(mean + 0.5 * sigma)
    clipped, moves = displacements(loss, window, [1.0])
    assert moves == pytest.approx(np.clip(loss, mean - 0.5 * sigma, mean + 0.5 * sigma) / (mean + 0.5 * sigma))


def test_body_balanced_update(tmp_path):
    wtc = (
        "[bodyBalancedUpdate]\nbody = a,b\nmaxChange = 0.02\n"
        "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 0.5\n"
        "[b]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 0.5\n"
    )
    files = write_model(tmp_path / "m", wtc)
    loss_a = np.array([0.0, 0.0, 6.0, 3.0, 0.0, 0.0, 0.0, 0.0])
    loss_b = np.array([0.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    plan = plan_wear(files, {"a": loss_a, "b": loss_b}, version=0)
    by_body = {w.body: w for w in plan.bodies}
    largest = max(abs(w.displacement).max() for w in plan.bodies)
    assert largest == pytest.approx(0.02)
    assert by_body["a"].displacement.max() == pytest.approx(0.02)
    assert by_body["b"].displacement.max() == pytest.approx(0.02 * 2.0 / 6.0)  # less than alone (0.02)


def test_reshaping_cycles_choose_sections(tmp_path):
    wtc = (
        "[common]\nreshapingCycles = 2\n"
        "[a:0]\ncontactWatch = 2\ndirectionInside = 1\nmaxChange = 0.01\n"
        "[a:1]\ncontactWatch = 6\ndirectionInside = 1\nmaxChange = 0.03\n"
    )
    files = write_model(tmp_path / "m", wtc)
    loss = np.ones(8)
    for version, point, amount in ((0, 2, 0.01), (1, 6, 0.03), (2, 2, 0.01), (3, 6, 0.03)):
        (wear,) = plan_wear(files, {"a": loss}, version=version).bodies
        assert wear.points.tolist() == [point] and wear.displacement[0] == pytest.approx(amount)


def test_direction_axes_and_outside():
    shape = np.array(SQUARE + SQUARE[:1], dtype=float)
    assert directions(shape, np.array([1]), -1, (0, 0)) == pytest.approx(np.array([[0, -1]]))
    assert directions(shape, np.array([1, 3]), 0, (3, 4)) == pytest.approx(np.array([[0.6, 0.8], [0.6, 0.8]]))


def test_reshaping_that_breaks_the_shape_is_refused(tmp_path):
    files = write_model(tmp_path / "m", "[a]\ncontactWatch = all\ndirectionInside = 1\nmaxChange = 1.5\n")
    loss = np.array([0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0])  # opposite edge points pushed through
    with pytest.raises(ModelError, match=r"a.exs: reshaping body 'a' would break its shape: self-intersecting"):
        plan_wear(files, {"a": loss}, version=0)


def test_constants_update_then_change(tmp_path):
    wtc = (
        "[constantsUpdate]\nbody = a,b\nconstant = c'k,c'm\nmaxChange = 0.5\n"
        "[changeConstants]\nconstant = c'k\nchange = -0.25\n"
    )
    files = write_model(tmp_path / "m", wtc)
    plan = plan_wear(files, {"a": np.full(8, 1.0), "b": np.full(8, 0.5)}, version=0)
    # totals: a = 8, b = 4 -> k += 0.5 * 8/8 then -0.25; m += 0.5 * 4/8
    assert plan.constants_before == {"k": 1.0, "m": 2.0}
    assert plan.constants_after == pytest.approx({"k": 1.0 + 0.5 - 0.25, "m": 2.0 + 0.25})
    assert plan.bodies == []


def test_unknown_constant_is_reported(tmp_path):
    files = write_model(tmp_path / "m", "[changeConstants]\nconstant = c'q\nchange = 1\n")
    with pytest.raises(ModelError, match=r"m.wtc: the watches file changes constant c'q"):
        plan_wear(files, {"a": np.zeros(8)}, version=0)
