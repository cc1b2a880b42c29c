"""Build the woodpecker toy (manual section 2.3, Figure 2.6) from its energies.

    python campaigns/woodpecker/build_woodpecker.py [FOLDER] [--bird exact|small-angle|beak] [--four-dof]

writes the model folder (default: ``built`` beside this script). A ring (y, Rz) slides down a
fixed stick; the bird (Rz) hangs from the ring on a torsional spring. The equations of motion
are those of Slavič and Boltežar (2006): kinetic and potential energy linearised in the two
angles, the bird's centre at height y + lM Rz_ring + lG Rz_bird. Where the bird's outline is
for contacts is a separate choice, :data:`BIRD_POSITIONS`: ``exact`` places its centre on the
two arms (lM cos + lG cos, y + lM sin + lG sin); ``small-angle`` uses the same linearisation as
the energies; ``beak`` places it so that the beak tip (-lS, hS) follows the small-angle
kinematics of the reference while the outline rotates exactly, and carries the sleeve's inner
face on two dependent bodies whose corners follow the reference's kinematics too (the example's
files; this variant reproduces the published limit cycle). Further variants are one entry of
that table.

``--four-dof`` writes the manual's 4-DoF, seven-body model instead (campaigns/woodpecker4dof):
the ring's x is generalized too (the bird moves with it), both sleeve walls (``ringSideR`` on
the bird's side of the stick, ``ringSideL`` on the other) are rigid parts of the ring, and
``ringF`` (the ring's spring seat at the hinge) and ``foot`` (the bird's foot at the hinge) only
complete the picture. The bird is placed as in ``beak``; the walls turn exactly with the ring.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import sympy

from mbds.build import ModelBuilder
from mbds.build import energies as E
from mbds.build import shapes
from mbds.build.script import run_build

BIRD_OUTLINE = np.array([  # m, bird frame: tail, belly, beak, head, back
    [-0.0201, 0.02], [-0.013, 0.0186], [-0.012, 0.015], [-0.0115, 0.01], [-0.013, 0.005], [-0.0135, 0.0],
    [-0.012, -0.0045], [-0.007, -0.0075], [0.0, -0.008], [0.008, -0.0065], [0.014, -0.003], [0.022, -0.001],
    [0.022, 0.001], [0.013, 0.0035], [0.005, 0.007], [-0.003, 0.011], [-0.004, 0.016], [-0.006, 0.02],
    [-0.009, 0.022], [-0.012, 0.0218], [-0.013, 0.0214],
])


def _rectangle(x0, x1, y0, y1) -> np.ndarray:
    return shapes.polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])


def _exact(mb, ring, bird, lM, lG):
    return (lM * sympy.cos(ring.Rz) + lG * sympy.cos(bird.Rz),
            ring.y + lM * sympy.sin(ring.Rz) + lG * sympy.sin(bird.Rz))


def _small_angle(mb, ring, bird, lM, lG):
    return lM + lG, ring.y + lM * ring.Rz + lG * bird.Rz


def _beak(mb, ring, bird, lM, lG):
    hS = mb.constant("hS", 0.02)  # beak tip above the bird's centre (m)
    lS = mb.constant("lS", 0.0201)  # beak tip behind the bird's centre (m)
    c, s = sympy.cos(bird.Rz), sympy.sin(bird.Rz)
    return lM + lG - lS * (1 - c), ring.y + lM * ring.Rz + lG * bird.Rz + hS * (1 - c) - lS * (bird.Rz - s)


def _sleeve_corners(mb, ring):
    """The sleeve's inner face as two bodies turning with the ring, ringSideU (upper half) and
    ringSideL (lower half), placed so that their corners (r_M, +-h_M) follow the reference's
    small-angle kinematics: x = r_M -+ h_M sin(Rz), moving vertically with y' + r_M Rz'. Returns
    (body, watched corner point) pairs."""
    rM = mb.constant("rM", 0.0031)  # sleeve's inner radius (m)
    hM = mb.constant("hM", 0.0058)  # sleeve's half height (m)
    c, s = sympy.cos(ring.Rz), sympy.sin(ring.Rz)
    corners = []
    for name, sign, y0, y1, point in (("ringSideU", 1, 0.0, 0.0058, "3"), ("ringSideL", -1, -0.0058, 0.0, "0")):
        corner = mb.body(name, _rectangle(0.0031, 0.0041, y0, y1), density=1000, thickness=0.005, color=(1, 1, 0))
        mb.dependent(corner.x, rM * (1 - c))
        mb.dependent(corner.y, ring.y + rM * (ring.Rz - s) + sign * hM * (1 - c))
        mb.dependent(corner.Rz, ring.Rz)
        corners.append((corner, point))
    return corners


STICK_ENDS = {False: (-0.95, 0.05), True: (-1.6, 0.05)}
"""Bottom and top of the stick (m): below the sleeve's start (y = 0) the stick is long enough for
the sleeve to slide down for the whole run (1 s of the 3-DoF example, 10 s of the 4-DoF one at
the limit cycle's 0.13 m/s)."""

BIRD_POSITIONS = {"exact": _exact, "small-angle": _small_angle, "beak": _beak}
"""The bird's centre (x, y) (m) from the builder, the ring and bird bodies and the arms lM, lG
(a variant may declare constants of its own)."""


def build(folder: Path, bird_position: str = "exact", four_dof: bool = False) -> Path:
    """Write the woodpecker into ``folder`` with the bird placed by ``BIRD_POSITIONS[bird_position]``
    (the 4-DoF model of the manual with ``four_dof``); returns its world file."""
    mb = ModelBuilder()
    g = mb.constant("gravity", 9.81)
    lM = mb.constant("lM", 0.01)
    lG = mb.constant("lG", 0.015)
    k = mb.constant("spring", 0.0056)
    ring = mb.body("ring", _rectangle(0.0042, 0.0085, -0.0006, 0.0006), mass=0.0003, inertia=5e-9,
                   density=1000, thickness=0.005, color=(1, 1, 0), position=(0, 0, -0.1009), velocity=(0, -0.3411, 0))
    stick = mb.body("stick", _rectangle(-0.0025, 0.0025, *STICK_ENDS[four_dof]), density=700, thickness=0.005,
                    color=(0.6, 0.4, 0.2))
    bird = mb.body("bird", shapes.polygon(BIRD_OUTLINE), mass=0.0045, inertia=7e-7, density=1000,
                   thickness=0.005, color=(0, 0.4, 1), position=(0, 0, -0.2788), velocity=(0, 0, -7.4583))
    small_angle_contacts = bird_position == "beak" and not four_dof
    walls = [(0.0036 if small_angle_contacts else 0.0031, 0.0041)]  # the inner half is on the sides below
    if four_dof:
        mb.body("ringF", _rectangle(0.0085, 0.0105, -0.0015, 0.0015), virtual_to=ring, color=(1, 1, 0),
                position=(0, 0, -0.1009), velocity=(0, -0.3411, 0))
        mb.body("foot", _rectangle(-0.0165, -0.0135, -0.001, 0.001), virtual_to=bird, color=(0, 0.4, 1),
                position=(0, 0, -0.2788), velocity=(0, 0, -7.4583))
        walls.append((-0.0041, -0.0031))
    sides = [mb.body(name, _rectangle(*wall, -0.0058, 0.0058), virtual_to=ring, density=1000, thickness=0.005,
                     color=(1, 1, 0), position=(0, 0, -0.1009), velocity=(0, -0.3411, 0))
             for name, wall in zip(("ringSideR", "ringSideL"), walls)]

    mb.generalized(*([ring.x] if four_dof else []), ring.y, ring.Rz, bird.Rz)
    bird_x, bird_y = BIRD_POSITIONS[bird_position](mb, ring, bird, lM, lG)
    mb.dependent(bird.x, bird_x + ring.x if four_dof else bird_x)
    mb.dependent(bird.y, bird_y)
    corners = _sleeve_corners(mb, ring) if small_angle_contacts else []

    bird_height = ring.y + lM * ring.Rz + lG * bird.Rz  # linearised in the angles
    sleeve_x = ring.x if four_dof else 0  # the bird moves sideways with the ring
    mb.kinetic_energy(E.point_mass_kinetic(ring.m, sleeve_x, ring.y) + ring.Jzz * sympy.diff(ring.Rz) ** 2 / 2)
    mb.kinetic_energy(E.point_mass_kinetic(bird.m, sleeve_x, bird_height) + bird.Jzz * sympy.diff(bird.Rz) ** 2 / 2)
    mb.potential_energy(E.gravity(ring.m, ring.y, g) + E.gravity(bird.m, bird_height, g))
    mb.potential_energy(E.torsional_spring(k, ring.Rz - bird.Rz))

    for side in sides:
        mb.contact(stick, side, friction=0.3)
    mb.contact(stick, bird, friction=0.3, restitution_normal=0.5)
    for corner, _ in corners:
        mb.contact(stick, corner, friction=0.3)
    mb.watch(bird, "0")
    if corners:
        for corner, point in corners:
            mb.watch(corner, point)
    else:
        for side, inner in zip(sides, ("0,3", "1,2")):  # the inner corners of each wall
            mb.watch(side, inner)
    mb.world(minimum_timestep=1e-12, maximum_timestep=1e-5, maximum_penetration=1e-6,
             break_time=10.0 if four_dof else 1.0)
    return mb.write(folder, "woodpecker4dof" if four_dof else "woodpecker")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", type=Path, default=Path(__file__).resolve().parent / "built")
    parser.add_argument("--bird", choices=sorted(BIRD_POSITIONS), default="exact")
    parser.add_argument("--four-dof", action="store_true", help="the manual's 4-DoF, seven-body model")
    arguments = parser.parse_args()
    run_build(build, arguments.folder, arguments.bird, arguments.four_dof)
