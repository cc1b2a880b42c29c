"""Build the double pendulum striking a wall, only through mbds.build.

    python campaigns/double_pendulum/build_double_pendulum.py [FOLDER]

writes the model folder (default: this script's folder, where the model files live). Two steel
rods hang from a fixed pivot at the origin, the second from the end of the first; a steel bob
sits at the end of the second rod. Released from the left, the bob swings into a wall on the
right. The generalized coordinates are the rods' angles Rz (rad, measured from the x axis, -π/2
hanging down); every centre is a dependent coordinate. Each version of the wear job wears the
bob's outline inward by up to 0.1 mm where it lost the most energy.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import sympy

from mbds.build import ModelBuilder
from mbds.build import energies as E
from mbds.build import shapes
from mbds.build.script import run_build

STEEL = 7850.0  # kg/m³
THICKNESS = 0.01  # m
L1, L2 = 0.20, 0.15  # rod lengths (m)
WIDTH = 0.008  # rod width (m)
RADIUS = 0.02  # bob radius (m)
WALL_X = 0.12  # the wall's face (m)
START = (-np.pi / 2 - 0.8, -np.pi / 2 - 0.5)  # rod angles at release (rad)


def rod(length: float) -> np.ndarray:
    """A rod outline along its x axis, centred on the origin (m)."""
    return shapes.polygon([(-length / 2, -WIDTH / 2), (length / 2, -WIDTH / 2), (length / 2, WIDTH / 2),
                           (-length / 2, WIDTH / 2)])


def build(folder: Path) -> Path:
    """Write the double pendulum into ``folder``; returns its world file."""
    mb = ModelBuilder()
    g = mb.constant("gravity", 9.81)
    l1 = mb.constant("l1", L1)
    l2 = mb.constant("l2", L2)
    rod1 = mb.body("rod1", rod(L1), density=STEEL, thickness=THICKNESS, color=(0.6, 0.6, 0.6),
                   position=(0, 0, START[0]))
    rod2 = mb.body("rod2", rod(L2), density=STEEL, thickness=THICKNESS, color=(0.4, 0.4, 0.4),
                   position=(0, 0, START[1]))
    bob = mb.body("bob", shapes.circle(RADIUS, 48), density=STEEL, thickness=THICKNESS, color=(0.8, 0.1, 0.1))
    wall = mb.body("wall", shapes.polygon([(WALL_X, -0.5), (WALL_X + 0.05, -0.5), (WALL_X + 0.05, 0.1),
                                           (WALL_X, 0.1)]), density=STEEL, thickness=THICKNESS, color=(0.3, 0.3, 0.3))

    mb.generalized(rod1.Rz, rod2.Rz)
    c1, s1 = sympy.cos(rod1.Rz), sympy.sin(rod1.Rz)
    c2, s2 = sympy.cos(rod2.Rz), sympy.sin(rod2.Rz)
    mb.dependent(rod1.x, l1 / 2 * c1)
    mb.dependent(rod1.y, l1 / 2 * s1)
    mb.dependent(rod2.x, l1 * c1 + l2 / 2 * c2)
    mb.dependent(rod2.y, l1 * s1 + l2 / 2 * s2)
    mb.dependent(bob.x, l1 * c1 + l2 * c2)
    mb.dependent(bob.y, l1 * s1 + l2 * s2)
    mb.dependent(bob.Rz, rod2.Rz)

    for body in (rod1, rod2, bob):
        mb.kinetic_energy(E.rigid_body_kinetic(body))
        mb.potential_energy(E.gravity(body.m, body.y, g))

    mb.contact(bob, wall, friction=0.2, restitution_normal=0.8)
    mb.watch(bob, "all", direction_inside=1, max_change=1e-4)
    mb.world(minimum_timestep=1e-10, maximum_timestep=1e-5, maximum_penetration=1e-6,
             history_multiple_of_maximum_timestep=100, break_time=1.0)
    return mb.write(folder, "double_pendulum")


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    run_build(build, target)
