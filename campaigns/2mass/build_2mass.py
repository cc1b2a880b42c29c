"""Build the 2Mass model (manual section 2.2, Figure 2.5) from its energies.

    python campaigns/2mass/build_2mass.py [FOLDER]

writes the model folder (default: ``built`` beside this script). A block (mass1) with three
degrees of freedom falls on a fixed slab (mass2).
"""

from __future__ import annotations

import sys
from pathlib import Path

from mbds.build import ModelBuilder
from mbds.build import energies as E
from mbds.build import shapes
from mbds.build.script import run_build


def build(folder: Path) -> Path:
    """Write the 2Mass model into ``folder``; returns its world file."""
    mb = ModelBuilder()
    gravity = mb.constant("gravity", 9.81)
    mass1 = mb.body(
        "mass1",
        shapes.polygon([(0.07, 0.05), (0.0, 0.06), (-0.07, 0.05), (-0.07, -0.05), (0.07, -0.05)]),
        density=2500, thickness=0.02, color=(0, 1, 0), position=(-0.005, 0.15, 3.1459), velocity=(0, -1, 0),
    )
    mass2 = mb.body(
        "mass2", shapes.polygon([(-0.5, -0.1), (0.5, -0.1), (0.5, 0.0), (-0.5, 0.0)]),
        density=2500, thickness=0.02, color=(0.5, 0.5, 0.5),
    )
    mb.generalized(mass1.x, mass1.y, mass1.Rz)
    mb.kinetic_energy(E.rigid_body_kinetic(mass1))
    mb.potential_energy(E.gravity(mass1.m, mass1.y, gravity))
    mb.contact(mass1, mass2, friction=0.1, restitution_normal=0.7, restitution_tangent=0.2)
    mb.watch(mass1, "0-2")
    mb.world(minimum_timestep=1e-10, maximum_timestep=5e-4, maximum_penetration=1e-5, break_time=0.5)
    return mb.write(folder, "2mass")


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "built"
    run_build(build, target)
