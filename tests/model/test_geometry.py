"""Polygon validation and mass properties against hand computations."""

import numpy as np
import pytest

from mbds.model.geometry import polygon_problems, polygon_properties

MASS1 = np.array([(0.07, 0.05), (0, 0.06), (-0.07, 0.05), (-0.07, -0.05), (0.07, -0.05), (0.07, 0.05)])


def test_2mass_body_by_rectangle_plus_triangle():
    """The 2mass body is a 0.14 x 0.10 rectangle with an isosceles triangle (base 0.14,
    height 0.01) on top; density 2500 kg/m^3 and thickness 0.02 m give 50 kg/m^2."""
    rho_t = 2500 * 0.02
    m_rect, m_tri = rho_t * 0.14 * 0.10, rho_t * 0.5 * 0.14 * 0.01
    y_rect, y_tri = 0.0, 0.05 + 0.01 / 3
    mass = m_rect + m_tri
    y_c = (m_rect * y_rect + m_tri * y_tri) / mass
    j_rect = m_rect * (0.14**2 + 0.10**2) / 12
    sides_sq = 0.14**2 + 2 * (0.07**2 + 0.01**2)
    j_tri = m_tri * sides_sq / 36  # polar moment of a triangle about its centroid
    j_c = j_rect + m_rect * (y_rect - y_c) ** 2 + j_tri + m_tri * (y_tri - y_c) ** 2
    props = polygon_properties(MASS1)
    assert props.area * rho_t == pytest.approx(0.735, rel=1e-12)
    assert props.area * rho_t == pytest.approx(mass, rel=1e-12)
    assert props.centroid == pytest.approx([0.0, y_c], abs=1e-15)
    assert props.second_moment * rho_t == pytest.approx(j_c, rel=1e-12)
    assert props.second_moment * rho_t == pytest.approx(1.8503e-3, rel=1e-4)


def test_disk_approximation_converges():
    angles = np.linspace(0, 2 * np.pi, 2001)
    angles[-1] = 0.0
    circle = np.column_stack([np.cos(angles), np.sin(angles)]) * 0.5 + [1.0, -2.0]
    props = polygon_properties(circle)
    assert props.area == pytest.approx(np.pi * 0.25, rel=1e-5)
    assert props.centroid == pytest.approx([1.0, -2.0], abs=1e-12)
    assert props.second_moment == pytest.approx(np.pi * 0.5**4 / 2, rel=1e-5)


def test_valid_shape_has_no_problems():
    assert polygon_problems(MASS1) == []


def test_not_closed():
    problems = polygon_problems(MASS1[:-1])
    assert problems and "not closed" in problems[0] and "point 4" in problems[0]


def test_clockwise_is_refused():
    problems = polygon_problems(MASS1[::-1])
    assert any("clockwise" in p for p in problems)


def test_self_intersection_names_edges():
    bow_tie = np.array([(0, 0), (1, 1), (1, 0), (0, 1), (0, 0)], dtype=float)
    problems = polygon_problems(bow_tie)
    assert any("self-intersecting: edge 0-1 crosses edge 2-3" in p for p in problems)


def test_repeated_point():
    shape = np.array([(0, 0), (1, 0), (1, 0), (1, 1), (0, 0)], dtype=float)
    assert "points 1 and 2 coincide" in polygon_problems(shape)[0]


def test_touching_edges_count_as_intersection():
    # a notch reaching to x = 1 is fine; reaching to x = 2 its tip touches the edge (2, 0)-(2, 1)
    shape = np.array([(0, 0), (2, 0), (2, 1), (0, 1), (0, 0.6), (1, 0.5), (0, 0.4), (0, 0)], dtype=float)
    assert polygon_problems(shape) == []
    pinched = np.array([(0, 0), (2, 0), (2, 1), (0, 1), (0, 0.6), (2, 0.5), (0, 0.4), (0, 0)], dtype=float)
    assert any("self-intersecting" in p for p in polygon_problems(pinched))
