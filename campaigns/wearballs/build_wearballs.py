"""Build the WearBalls model (manual section 2.4) from its energies.

    python campaigns/wearballs/build_wearballs.py [FOLDER]

writes the model folder (default: ``built`` beside this script). Five steel balls fall on a
ground that the dependent coordinate y = A sin(ωt) shakes, next to a fixed wall; every ball
wears by up to 2 mm per version where it loses the most energy.
"""

from __future__ import annotations

import sys
from pathlib import Path

import sympy

from mbds.build import ModelBuilder
from mbds.build import energies as E
from mbds.build import shapes
from mbds.build.script import run_build

BALLS = [  # radius (m), colour, start (x, y, Rz)
    (0.030, (1, 0, 0), (0.04, 0.037156, 0.0)),
    (0.025, (0, 0.6, 0), (0.105, 0.045376, 0.05)),
    (0.035, (0, 0, 1), (0.175, 0.057008, 0.1)),
    (0.025, (1, 0.6, 0), (0.245, 0.060613, 0.15)),
    (0.030, (0.6, 0, 0.8), (0.31, 0.060808, 0.2)),
]
SEGMENTS = 48
DIGITS = 9  # the outlines are written with 9 decimals (nm)


def build(folder: Path) -> Path:
    """Write the WearBalls model into ``folder``; returns its world file."""
    mb = ModelBuilder()
    gravity = mb.constant("gravity", 9.81)
    amplitude = mb.constant("amplitude", 0.005)
    omega = mb.constant("omega", 62.83185307)
    balls = [
        mb.body(f"ball{i}", shapes.circle(r, SEGMENTS).round(DIGITS), density=7850, thickness=0.01,
                color=color, position=start, correct_origin=True)
        for i, (r, color, start) in enumerate(BALLS, start=1)
    ]
    ground = mb.body("ground", shapes.polygon([(0, -0.04), (0.5, -0.04), (0.5, 0), (0, 0)]), density=7850,
                     thickness=0.01, color=(0.5, 0.5, 0.5), position=(0.002, 0, 0.08))
    wall = mb.body("wall", shapes.polygon([(-0.03, -0.1), (0, -0.1), (0, 0.3), (-0.03, 0.3)]), density=7850,
                   thickness=0.01, color=(0.3, 0.3, 0.3))
    for ball in balls:
        mb.generalized(ball.x, ball.y, ball.Rz)
    mb.dependent(ground.y, amplitude * sympy.sin(omega * sympy.Symbol("t", real=True)))
    for ball in balls:
        mb.kinetic_energy(E.rigid_body_kinetic(ball))
        mb.potential_energy(E.gravity(ball.m, ball.y, gravity))
    for ball in balls:
        mb.contact(ball, ground, friction=0.3, restitution_normal=0.6)
    for ball in balls:
        mb.contact(ball, wall, friction=0.2, restitution_normal=0.5)
    for i, first in enumerate(balls):
        for second in balls[i + 1 :]:
            mb.contact(first, second, friction=0.2, restitution_normal=0.7)
    for ball in balls:
        mb.watch(ball, "all", direction_inside=1, max_change=0.002)
    mb.world(minimum_timestep=1e-10, maximum_timestep=1e-4, maximum_penetration=1e-5,
             history_multiple_of_maximum_timestep=10, break_time=1.5)
    return mb.write(folder, "wearballs")


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "built"
    run_build(build, target)
