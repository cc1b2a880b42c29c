"""Shape helpers: the manual's Circl, Elipse, Take, TranslateData and Join, and the checks."""

import numpy as np
import pytest

from mbds.build import shapes


def test_ellipse_has_n_plus_one_points_counter_clockwise_and_closed():
    points = shapes.ellipse(0.01, 0.02, 50)
    assert points.shape == (51, 2)
    assert np.array_equal(points[0], points[-1])
    assert points[0] == pytest.approx([0.01, 0.0])
    assert points[25] == pytest.approx([-0.01, 0.0], abs=1e-15)
    assert points[12] == pytest.approx([0.01 * np.cos(2 * np.pi * 12 / 50), 0.02 * np.sin(2 * np.pi * 12 / 50)])
    assert shapes.check_shape(points) == []


def test_circle_area_tends_to_pi_r_squared():
    """A regular n-gon inscribed in a circle of radius r has area n r² sin(2π/n) / 2."""
    from mbds.model.geometry import polygon_properties

    r, n = 0.03, 48
    assert polygon_properties(shapes.circle(r, n)).area == pytest.approx(n * r * r * np.sin(2 * np.pi / n) / 2, rel=1e-13)


def test_take_counts_from_one_and_includes_both_ends():
    data = np.arange(20.0).reshape(10, 2)
    assert np.array_equal(shapes.take(data, (2, 4)), data[1:4])
    with pytest.raises(ValueError, match="take"):
        shapes.take(data, (0, 3))
    with pytest.raises(ValueError, match="take"):
        shapes.take(data, (4, 11))


def test_translate_rotate_and_join():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    assert np.array_equal(shapes.translate(square, 0.5, -1.0), square + [0.5, -1.0])
    turned = shapes.rotate(square, np.pi / 2)
    assert turned == pytest.approx(np.array([[0.0, 0.0], [0.0, 1.0], [-1.0, 1.0]]))
    about = shapes.rotate(square, np.pi, about=(1.0, 0.0))
    assert about == pytest.approx(np.array([[2.0, 0.0], [1.0, 0.0], [1.0, -1.0]]))
    joined = shapes.join(square[:2], square[2:])
    assert np.array_equal(joined, square)


def test_bird_like_outline_from_ellipses_is_a_valid_shape():
    """Figure 2.8's recipe: the front of a body ellipse, most of a head circle above its back,
    the rest of the body, joined into one outline."""
    body = shapes.ellipse(0.02, 0.01, 50)
    head = shapes.translate(shapes.circle(0.008, 50), -0.012, 0.012)
    outline = shapes.join(shapes.take(body, (1, 14)), shapes.take(head, (4, 38)), shapes.take(body, (24, 50)))
    assert "not closed" in shapes.check_shape(outline)[0]
    assert shapes.check_shape(shapes.closed(outline)) == []


def test_open_clockwise_and_crossing_outlines_are_reported():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert "not closed" in shapes.check_shape(square)[0]
    assert "clockwise" in shapes.check_shape(shapes.closed(square[::-1]))[0]
    bow = shapes.closed(np.array([[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]))
    assert "self-intersecting" in shapes.check_shape(bow)[0]


def test_polygon_closes_and_closed_is_idempotent():
    square = shapes.polygon([(0, 0), (1, 0), (1, 1), (0, 1)])
    assert len(square) == 5 and np.array_equal(square[0], square[-1])
    assert np.array_equal(shapes.closed(square), square)
