"""Vertex-edge contact detection against a brute-force reference."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mbds.kernel.contact_problem import HELD_FRACTION
from mbds.kernel.detection import (
    CORNER_GAP, DEEP, bounding_boxes, detect_contacts, tracked_depth, vertex_edge, world_points,
)
from mbds.kernel.layout import Contacts
from mbds.model.arrays import concave_corners


MAX_PEN = 1e-6
"""maximumPenetration (m) of the detections here: corner contacts are at least CORNER_GAP x this."""


def circle(radius, n, rough=0.0, seed=0):
    rng = np.random.default_rng(seed)
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = radius * (1 + rough * rng.uniform(-1, 1, n))
    pts = np.column_stack([r * np.cos(angles), r * np.sin(angles)])
    return np.vstack([pts, pts[:1]])


def detect(shapes, pose, pairs, resisting, skin, margin, capacity=10000, max_pen=MAX_PEN):
    points = np.vstack(shapes)
    start = np.concatenate([[0], np.cumsum([len(s) for s in shapes])]).astype(np.int64)
    world = np.empty_like(points)
    world_points(pose, np.column_stack([np.cos(pose[:, 2]), np.sin(pose[:, 2])]), points, start, world)
    boxes = np.empty((len(shapes), 4))
    bounding_boxes(world, start, boxes)
    out_i = [np.empty(capacity, dtype=np.int64) for _ in range(5)]
    xi, gap = np.empty(capacity), np.empty(capacity)
    normal, point = np.empty((capacity, 2)), np.empty((capacity, 2))
    work = np.empty(3 * len(points) + 2050, dtype=np.int64)
    reflex = [concave_corners(s) for s in shapes]
    count = detect_contacts(
        world, start, np.concatenate(reflex), np.array([r.any() for r in reflex]), boxes,
        np.array(pairs, dtype=np.int64), np.array(resisting, dtype=np.bool_), np.array(skin, dtype=float),
        np.full(len(pairs), margin), max_pen, *out_i, xi, gap, normal, point, work, np.empty((len(points), 5)),
    )
    if count < 0:
        return None, world, start
    found = {(int(out_i[2][k]), int(out_i[4][k])): (xi[k], gap[k], normal[k].copy()) for k in range(count)}
    return found, world, start


def inside(point, polygon) -> bool:
    """Whether ``point`` lies inside the closed ``polygon`` (even-odd rule, by matplotlib)."""
    from matplotlib.path import Path

    return bool(Path(polygon).contains_point(point, radius=0.0))


def brute_force(world, start, vb, eb, skin, margin, max_pen=MAX_PEN):
    """Every vertex of vb over an edge of eb (0 <= xi <= 1, reaching skin + margin beyond an end at
    a concave corner) with -skin < gap <= margin; one deeper than DEEP x
    skin only when inside eb; of a vertex's contacts, those in front of their faces and, behind
    their faces, those within DEEP x skin of the largest gap behind a face. A vertex past the
    end of an edge at a convex corner, beyond the start of the next edge and within the margin
    of the corner, is a corner contact at its distance from the corner (at least CORNER_GAP x
    max_pen)."""
    found = {}
    polygon = world[start[eb]:start[eb + 1]]
    concave = concave_corners(polygon)
    for i in range(start[vb], start[vb + 1] - 1):
        mine = {}
        for j in range(start[eb], start[eb + 1] - 1):
            q0, q1 = world[j], world[j + 1]
            t = (q1 - q0) / np.linalg.norm(q1 - q0)
            xi = t @ (world[i] - q0) / np.linalg.norm(q1 - q0)
            gap = np.array([t[1], -t[0]]) @ (world[i] - q0)
            length = np.linalg.norm(q1 - q0)
            lo = -(skin + margin) / length if concave[j - start[eb]] else 0.0
            hi = 1.0 + (skin + margin) / length if concave[j + 1 - start[eb]] else 1.0
            if xi > 1.0 and not concave[j + 1 - start[eb]]:
                following = world[j + 2] if j + 2 < start[eb + 1] else world[start[eb] + 1]
                distance = np.linalg.norm(world[i] - q1)
                if (world[i] - q1) @ (following - q1) < 0 and distance <= margin:
                    mine[(i, j)] = (xi, max(distance, CORNER_GAP * max_pen))
            elif lo <= xi <= hi and -skin < gap <= margin and (gap >= -DEEP * skin or inside(world[i], polygon)):
                mine[(i, j)] = (xi, gap)
        behind = [gap for _, gap in mine.values() if gap <= 0]
        best = max(behind, default=0.0)
        found |= {key: value for key, value in mine.items() if value[1] > 0 or value[1] >= best - DEEP * skin}
    return found


def test_square_corner_on_floor():
    floor = np.array([(-1, -0.1), (1, -0.1), (1, 0), (-1, 0), (-1, -0.1)], dtype=float)
    square = np.array([(-0.05, -0.05), (0.05, -0.05), (0.05, 0.05), (-0.05, 0.05), (-0.05, -0.05)])
    tilt = 0.1
    drop = 0.05 * (np.cos(tilt) + np.sin(tilt)) - 1e-6  # lowest corner 1 um into the floor
    pose = np.array([[0, 0, 0], [0.2, drop, tilt]], dtype=float)
    found, world, start = detect([floor, square], pose, [(0, 1)], [(True, True)], [1e-3, 1e-3], 0.0)
    assert len(found) == 1
    (vertex, edge), (xi, gap, normal) = next(iter(found.items()))
    assert start[1] <= vertex < start[2] and edge == 2  # floor's top edge runs from point 2 to 3
    assert gap == pytest.approx(-1e-6, abs=1e-12)
    assert normal == pytest.approx([0, 1])


@pytest.mark.parametrize("depth", [1e-4, 1e-6, 0.0, -1e-6, -5e-6])
def test_a_vertex_in_a_notch_touches_both_walls(depth):
    """A spike's tip in the notch of a concave corner, 2 mm in front of the notch's wall and
    ``depth`` (m) in front of its floor (negative: behind it, in the body). The floor is a
    contact whether the tip is in front of it or behind it, and so is the wall, whose band
    reaches the skin plus the margin beyond the corner: a tip sliding along the floor a little
    behind it meets the wall before it passes the corner. (A rule that kept only the contacts near the largest
    gap dropped the floor while the tip was in front of both, and with bands that stopped at the
    corner the wall never saw a tip behind the floor: either way a tip slid into the body.)"""
    # an L-shaped block: the notch x < 0, y > 0 has the wall x = 0 (facing -x, from point 3 to 4)
    # and the floor y = 0 (facing +y, from point 4 to 5); the spike points into the corner
    block = np.array([(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (0.0, 0.1), (0.0, 0.0), (-0.1, 0.0), (-0.1, -0.1)])
    spike = np.array([(0.0, 0.0), (-0.02, 0.03), (-0.03, 0.02), (0.0, 0.0)])  # tip at its origin
    pose = np.array([[0.0, 0.0, 0.0], [-0.002, depth, 0.0]])
    skin, margin = 1e-3, 3e-3
    found, world, start = detect([block, spike], pose, [(0, 1)], [(True, True)], [skin, skin], margin)
    tip = start[1]
    tip_contacts = {edge: gap for (vertex, edge), (_, gap, _) in found.items() if vertex == tip}
    floor_edge, wall_edge = 4, 3
    assert tip_contacts[floor_edge] == pytest.approx(depth, abs=1e-15)
    assert tip_contacts[wall_edge] == pytest.approx(0.002, abs=1e-15)
    assert set(found) == set(brute_force(world, start, 1, 0, skin, margin) | brute_force(world, start, 0, 1, skin,
                                                                                                   margin))


BLOCK = np.array([(-0.2, -0.2), (0.0, -0.2), (0.0, 0.0), (-0.2, 0.0), (-0.2, -0.2)])
"""A block whose top right corner, where its right side (from point 1 to 2) meets its top (from
point 2 to 3), is at the origin (m)."""
DIAMOND = np.array([(0.0, 0.0), (0.03, 0.03), (0.0, 0.06), (-0.03, 0.03), (0.0, 0.0)])
"""A square turned by 45 degrees, its lowest corner at its origin (m)."""


@pytest.mark.parametrize("where, gap, normal", [
    ((3e-4, 4e-4), 5e-4, (0.6, 0.8)),  # in the corner's exterior wedge, within the margin
    ((1e-7, 1e-7), CORNER_GAP * MAX_PEN, (np.sqrt(0.5), np.sqrt(0.5))),  # nearer than the smallest gap
    ((8e-4, 8e-4), None, None),  # beyond the margin
])
def test_a_tip_in_the_exterior_wedge_of_a_convex_corner_is_a_corner_contact(where, gap, normal):
    """A diamond's tip above and right of a block's corner faces neither the block's top nor its
    side, so no vertex-edge contact sees it. Within the margin it is a corner contact with the
    edge that ends at the corner (the side), at its distance from the corner (the tip of a
    diamond thrown at the corner passed through it unseen: nothing limited its step), never
    nearer than CORNER_GAP x maxPen, which is above the gap at which a resting contact is held:
    a corner contact is open. The block's corner, in the diamond's own exterior wedge at the
    tip, is one for the diamond's lower right edge."""
    pose = np.array([[0.0, 0.0, 0.0], [where[0], where[1], 0.0]])
    skin, margin = 1e-4, 1e-3
    found, world, start = detect([BLOCK, DIAMOND], pose, [(0, 1)], [(True, True)], [skin, skin], margin)
    assert set(found) == set(brute_force(world, start, 1, 0, skin, margin) | brute_force(world, start, 0, 1, skin,
                                                                                                   margin))
    tip = start[1]
    if gap is None:
        assert found == {}
        return
    xi, reported, direction = found[(tip, 1)]
    assert xi > 1.0 and reported == pytest.approx(gap, rel=1e-12)
    assert direction == pytest.approx(normal, abs=1e-12)
    assert set(found) == {(tip, 1), (2, start[1] + 3)}  # the block's corner against the diamond's lower right edge
    assert CORNER_GAP > HELD_FRACTION


def test_a_tip_facing_the_top_beside_the_corner_touches_the_top():
    """Left of the corner's exterior wedge the tip faces the block's top: a vertex-edge contact."""
    pose = np.array([[0.0, 0.0, 0.0], [-2e-4, 1e-4, 0.0]])
    found, world, start = detect([BLOCK, DIAMOND], pose, [(0, 1)], [(True, False)], [1e-4, 1e-4], 1e-3)
    assert found[(start[1], 2)][1] == pytest.approx(1e-4, abs=1e-15) and len(found) == 1


@pytest.mark.parametrize("where, depth", [
    ((-3e-4, -1e-4), 1e-4),  # through the top: as deep as below it
    ((-1e-4, -3e-4), 1e-4),  # through the side: as deep as left of it
    ((2e-4, -1e-4), 0.0),  # below the corner, right of the side: outside
])
def test_tracked_depth_follows_a_tip_past_the_end_of_its_edge(where, depth):
    """A corner contact's tip (on the block's side, past its end) moves through the corner into
    the block: its depth is its distance from the nearer of the side and the top. Outside the
    block it is not counted."""
    pose = np.array([[0.0, 0.0, 0.0], [3e-4, 4e-4, 0.0]])
    skin, margin = 1e-4, 1e-3
    found, world, start = detect([BLOCK, DIAMOND], pose, [(0, 1)], [(True, False)], [skin, skin], margin)
    assert list(found) == [(start[1], 1)]
    count = 1
    contacts = Contacts(pair=np.zeros(count, np.int64), vb=np.ones(count, np.int64),
                        vertex=np.array([start[1]]), eb=np.zeros(count, np.int64), edge=np.array([1]),
                        xi=np.zeros(count), gap=np.zeros(count), normal=np.zeros((count, 2)),
                        point=np.zeros((count, 2)), work=np.zeros(1, np.int64), frames=np.zeros((1, 5)),
                        order=np.zeros(count, np.int64))
    moved = np.array([[0.0, 0.0, 0.0], [where[0], where[1], 0.0]])
    points = np.vstack([BLOCK, DIAMOND])
    world = np.empty_like(points)
    world_points(moved, np.column_stack([np.cos(moved[:, 2]), np.sin(moved[:, 2])]), points, start, world)
    reflex = np.concatenate([concave_corners(BLOCK), concave_corners(DIAMOND)])
    assert tracked_depth(world, start, reflex, np.full(2, skin), np.full(1, margin), contacts,
                         count) == pytest.approx(depth, abs=1e-15)


@pytest.mark.parametrize("seed", range(5))
def test_rough_disks_match_brute_force(seed):
    a = circle(0.05, 400, rough=0.01, seed=seed)
    b = circle(0.04, 300, rough=0.01, seed=seed + 10)
    pose = np.array([[0, 0, 0.3 * seed], [0.0895, 0.002 * seed, -0.2]])
    skin, margin = 2e-3, 1e-4
    found, world, start = detect([a, b], pose, [(0, 1)], [(True, True)], [skin, skin], margin)
    expected = brute_force(world, start, 1, 0, skin, margin) | brute_force(world, start, 0, 1, skin, margin)
    assert expected, "the test geometry must produce contacts"
    assert set(found) == set(expected)
    for key, (xi, gap) in expected.items():
        assert found[key][0] == pytest.approx(xi, abs=1e-12) and found[key][1] == pytest.approx(gap, abs=1e-15)


@pytest.mark.parametrize("points", [24, 48, 400])
def test_contacts_hold_the_geometry_that_contact_tracking_recomputes(points):
    """A vertex-edge contact's xi, gap and normal as detection reports them (edges in buckets or, where only
    a few are near, tested by every vertex) are those vertex_edge gives for its vertex and edge
    bit for bit: a step's contact tracking (contact_geometry) starts from the same numbers."""
    a = circle(0.05, points, rough=0.002, seed=points)
    b = circle(0.04, points, rough=0.002, seed=points + 1)
    pose = np.array([[0, 0, 0.1], [0.089, 0.003, -0.2]])  # 1 mm of overlap: contacts at every resolution
    skin, margin = 2e-3, 1e-4
    found, world, start = detect([a, b], pose, [(0, 1)], [(True, True)], [skin, skin], margin)
    expected = brute_force(world, start, 1, 0, skin, margin) | brute_force(world, start, 0, 1, skin, margin)
    assert expected and set(found) == set(expected)
    reflex = np.concatenate([concave_corners(a), concave_corners(b)])
    for (vertex, edge), (xi, gap, normal) in found.items():
        if xi <= 1.0 or reflex[edge + 1]:  # (a corner contact, past a convex end, is never closed: not tracked)
            assert (xi, gap, *normal) == vertex_edge(world, vertex, edge)


@settings(max_examples=60, deadline=None)
@given(
    points=st.integers(3, 120),
    rough=st.floats(0.0, 0.3),
    seed=st.integers(0, 10_000),
    distance=st.floats(0.05, 0.095),
    angles=st.tuples(st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi), st.floats(-np.pi, np.pi)),
    skin=st.floats(1e-5, 5e-3),
    margin=st.floats(0.0, 1e-3),
)
def test_star_polygons_match_brute_force(points, rough, seed, distance, angles, skin, margin):
    """Random star-shaped (often non-convex) polygons of 3 to 120 points, at random relative
    poses, skins and margins: detection finds exactly the contacts of the brute-force search."""
    a = circle(0.05, points, rough=rough, seed=seed)
    b = circle(0.04, max(3, points // 2), rough=rough, seed=seed + 1)
    pose = np.array([[0, 0, angles[0]], [distance * np.cos(angles[1]), distance * np.sin(angles[1]), angles[2]]])
    found, world, start = detect([a, b], pose, [(0, 1)], [(True, True)], [skin, skin], margin)
    expected = brute_force(world, start, 1, 0, skin, margin) | brute_force(world, start, 0, 1, skin, margin)
    assert set(found) == set(expected)
    for key, (xi, gap) in expected.items():
        assert found[key][0] == pytest.approx(xi, abs=1e-12) and found[key][1] == pytest.approx(gap, abs=1e-15)


def test_resisting_flags_select_directions():
    a, b = circle(0.05, 64), circle(0.05, 64)
    pose = np.array([[0, 0, 0], [0.0995, 0, 0.05]])
    both, world, start = detect([a, b], pose, [(0, 1)], [(True, True)], [1e-3, 1e-3], 0.0)
    first_only, _, _ = detect([a, b], pose, [(0, 1)], [(True, False)], [1e-3, 1e-3], 0.0)
    assert both and first_only
    assert all(start[0] <= edge < start[1] for (_, edge) in first_only)  # edges of body 0 only
    assert set(first_only) < set(both)


def test_far_apart_bodies_have_no_contact_and_capacity_overflow_is_reported():
    a, b = circle(0.05, 64), circle(0.05, 64)
    far = np.array([[0, 0, 0], [1, 0, 0]], dtype=float)
    found, _, _ = detect([a, b], far, [(0, 1)], [(True, True)], [1e-3, 1e-3], 0.0)
    assert found == {}
    overlapping = np.array([[0, 0, 0], [0.0995, 0, 0.05]])
    overflow, _, _ = detect([a, b], overlapping, [(0, 1)], [(True, True)], [1e-3, 1e-3], 0.0, capacity=1)
    assert overflow is None
