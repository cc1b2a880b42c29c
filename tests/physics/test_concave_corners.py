"""No vertex passes into a body at a concave corner, and none into its neighbours in a pile of
non-convex polygons.

At a concave corner of a body the bands of its two edges (the vertices each edge sees, over
0 <= xi <= 1) leave a wedge that neither covers, behind both faces. A vertex sliding along one
face a little behind it (at rest, within maximumPenetration) enters that wedge at the corner,
and a tip that enters the notch in front of both faces is nearer one of them. mbds's detection
lets a band reach the skin plus the detection margin beyond a concave corner and keeps every
contact in front of its face (docs/theory.md §2). The depths here are measured from the sampled
poses and the shapes, by a point-in-polygon test and the distance to the outline, independently
of the kernel.
"""

import numpy as np
import pytest
from matplotlib.path import Path as Outline

from mbds.kernel import layout as K
from tests.physics.models import FreeBody, add_fixed_body, energy_residual, run_folder, write_free_bodies
from tests.physics.test_tunnelling import polygon_mass

pytestmark = pytest.mark.physics

G = 9.81  # m/s²
L_BLOCK = np.array([(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (0.0, 0.1), (0.0, 0.0), (-0.1, 0.0)])
"""A fixed block with a notch x < 0, y > 0: the wall x = 0 and the floor y = 0 meet at a concave
corner at the origin (m)."""


def depth_inside(points: np.ndarray, outline: np.ndarray) -> np.ndarray:
    """How deep (m) each of ``points`` (k, 2) lies inside the closed polygon ``outline`` (m, 2):
    its distance to the outline when inside, else 0."""
    a = outline
    b = np.roll(outline, -1, axis=0)
    ab = b - a
    t = np.clip(((points[:, None, :] - a) * ab).sum(-1) / (ab * ab).sum(-1), 0.0, 1.0)
    nearest = a + t[..., None] * ab
    distance = np.linalg.norm(points[:, None, :] - nearest, axis=-1).min(axis=1)
    return np.where(Outline(outline).contains_points(points), distance, 0.0)


def world(shape: np.ndarray, pose: np.ndarray) -> np.ndarray:
    """Body-frame ``shape`` (k, 2) moved to the world by ``pose`` (x, y, Rz)."""
    c, s = np.cos(pose[2]), np.sin(pose[2])
    return shape @ np.array([[c, s], [-s, c]]) + pose[:2]


def into_the_notch(folder, shape, start, velocity, dt_max, max_penetration):
    """A free polygon ``shape`` (k, 2; m) with its first point at ``start`` (m) and moving with
    ``velocity`` (m/s, m/s, rad/s), over the L-shaped block, frictionless, e = 0, for 0.1 s:
    (result, the shape about its centroid, as the body holds it)."""
    mass, inertia, centred = polygon_mass(shape)
    tip = centred[0]
    body = FreeBody("body", centred, mass, inertia, position=(start[0] - tip[0], start[1] - tip[1], 0.0),
                    velocity=velocity)
    folder = write_free_bodies(folder, [body], [("body", "block")], floor=False, gravity=G, friction=0.0,
                               restitution=0.0, dt_max=dt_max, max_penetration=max_penetration, break_time=0.1,
                               world={"writeToHistoryEachTimeStep": "1"})
    add_fixed_body(folder, "block", L_BLOCK)
    return run_folder(folder), centred


SETTINGS = [(1e-4, 1e-7), (1e-3, 1e-5)]  # (maximumTimestep s, maximumPenetration m), default skins


@pytest.mark.parametrize("dt_max, max_penetration", SETTINGS)
def test_a_wedge_sliding_along_the_floor_stops_at_the_wall(tmp_path, dt_max, max_penetration):
    """A wedge on its flat bottom, its sharp front corner leading, slides at 1 m/s into the wall.
    Its front corner slides a little behind the floor; with bands that stopped at the corner,
    the wall never saw it and it went 0.6 mm into the wall and then 14 mm down into the block
    (maximumTimestep 1e-4 s)."""
    wedge = np.array([(0.0, 0.0), (-0.01, 0.01), (-0.03, 0.01), (-0.03, 0.0)])
    result, shape = into_the_notch(tmp_path / "wedge", wedge, (-0.02, 0.0), (1.0, 0.0, 0.0), dt_max, max_penetration)
    depth = max(depth_inside(world(shape, pose), L_BLOCK).max() for pose in result.q)
    assert depth <= max_penetration
    front = np.array([world(shape, pose)[0] for pose in result.q])
    assert front[:, 0].max() <= max_penetration  # stopped at the wall
    assert result.u[-1, 0] < 0.0  # and turned back by the impact


@pytest.mark.parametrize("dt_max, max_penetration", SETTINGS)
def test_a_spike_falling_into_the_corner_stays_out_of_both_faces(tmp_path, dt_max, max_penetration):
    """A triangle falls tip first onto the floor 0.5 mm from the wall: the tip is in front of both
    faces, and nearer the floor. A rule that kept only the contacts near the largest gap saw the
    wall alone, and the tip went 0.8 mm into the floor (maximumTimestep 1e-3 s)."""
    spike = np.array([(0.0, 0.0), (-0.02, 0.03), (-0.03, 0.02)])
    result, shape = into_the_notch(tmp_path / "spike", spike, (-5e-4, 0.02), (0.0, 0.0, 0.0), dt_max,
                                   max_penetration)
    depth = max(depth_inside(world(shape, pose), L_BLOCK).max() for pose in result.q)
    assert depth <= max_penetration
    assert result.state.clock[K.OVER_PENETRATIONS] == 0


def pile(folder, seed):
    """Three random polygons (convex, or star-shaped with concave corners) thrown spinning into a
    box of floor and two walls, with world settings and contact laws drawn from the same
    generator: (result, the polygons' body-frame shapes)."""
    rng = np.random.default_rng(seed)
    bodies = []
    for k in range(3):
        count = int(rng.integers(3, 40))
        angles = np.sort(rng.uniform(0.0, 2.0 * np.pi, count))
        radii = 0.05 * (rng.uniform(0.4, 1.0, count) if rng.random() < 0.4 else np.full(count, rng.uniform(0.5, 1.0)))
        shape = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)]) * [1.0, rng.uniform(0.2, 1.0)]
        mass, inertia, centred = polygon_mass(shape)
        bodies.append(FreeBody(f"p{k}", centred, mass, inertia,
                               position=(rng.uniform(-0.12, 0.12), 0.08 + 0.12 * k, rng.uniform(-3.0, 3.0)),
                               velocity=(rng.uniform(-1.0, 1.0), rng.uniform(-2.0, 0.0), rng.uniform(-30.0, 30.0))))
    names = [b.name for b in bodies]
    pairs = ([(a, "floor") for a in names] + [(a, w) for a in names for w in ("left", "right")]
             + [(names[i], names[j]) for i in range(3) for j in range(i + 1, 3)])
    dt_max, max_penetration = float(rng.choice([1e-4, 3e-4, 1e-3])), float(rng.choice([1e-8, 1e-7, 1e-6, 1e-5]))
    friction, restitution = float(rng.uniform(0.0, 1.0)), float(rng.uniform(0.0, 0.9))
    folder = write_free_bodies(folder, bodies, pairs, floor=True, gravity=G, friction=friction, restitution=restitution,
                               dt_max=dt_max, max_penetration=max_penetration, break_time=1.5)
    add_fixed_body(folder, "left", WALLS[0])
    add_fixed_body(folder, "right", WALLS[1])
    return run_folder(folder), [b.shape for b in bodies]


def reach_factor(shape: np.ndarray) -> float:
    """How far (in maximumPenetration) from a concave corner of ``shape`` a vertex stopped at most
    maximumPenetration behind both of its faces can lie: 1 / cos(τ/2) for the corner's turning
    angle τ (the largest of the shape's); 1 without concave corners. The contacts are vertex
    against edge, and each edge holds the vertex within maximumPenetration of its line."""
    before = shape - np.roll(shape, 1, axis=0)
    after = np.roll(shape, -1, axis=0) - shape
    cross = before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0]
    turn = np.arctan2(-cross, (before * after).sum(axis=1))  # clockwise turning angle (rad)
    sharpest = turn.max()
    return 1.0 / np.cos(0.5 * sharpest) if sharpest > 0.0 else 1.0


FLOOR = np.array([(5.0, 0.0), (-5.0, 0.0), (-5.0, -0.1), (5.0, -0.1)])
WALLS = [np.array([(-0.2, 0.0), (-0.2, 1.0), (-0.3, 1.0), (-0.3, 0.0)]),
         np.array([(0.3, 0.0), (0.3, 1.0), (0.2, 1.0), (0.2, 0.0)])]


def test_a_pile_of_star_polygons_keeps_every_vertex_out(tmp_path):
    """A pile (:func:`pile`, seed 59: maximumTimestep 1e-3 s, maximumPenetration 1e-5 m) in which
    a spike entered a neighbour's notch in front of both its faces: with only the contacts near
    the largest gap kept, it went 0.78 mm into the neighbour at t = 0.27 s. No vertex is sampled
    deeper than maximumPenetration in the box, nor deeper in another polygon than a vertex held
    within maximumPenetration of both faces of its sharpest concave corner can be
    (:func:`reach_factor`), and no energy is made."""
    result, shapes = pile(tmp_path / "pile", 59)
    max_penetration = 1e-5
    for pose in result.q:
        outlines = [world(shape, pose[3 * k : 3 * k + 3]) for k, shape in enumerate(shapes)]
        for k, outline in enumerate(outlines):
            for other in [FLOOR, *WALLS]:
                assert depth_inside(outline, other).max() <= max_penetration
            for j in range(3):
                if j != k:
                    assert depth_inside(outline, outlines[j]).max() <= max_penetration * reach_factor(shapes[j])
    assert result.state.clock[K.OVER_PENETRATIONS] == 0
    assert (-energy_residual(result)).max() <= 1e-6 * np.abs(result.energy).max()
