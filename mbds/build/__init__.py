"""Building MBDS model folders from energies, coordinates and shapes (the manual's Mathematica
packages, section 2.3.1, in sympy). See ``docs/building-models.md``.

- :class:`ModelBuilder`: declare constants, bodies, coordinates, energies, virtual work,
  contacts and watches; :meth:`~ModelBuilder.derive` the equations; :meth:`~ModelBuilder.write`
  the model folder.
- :mod:`mbds.build.energies`: energies of rigid bodies, gravity, springs, dampers, forces.
- :mod:`mbds.build.shapes`: outlines from circles, ellipses and polygons.
"""

from mbds.build.builder import ModelBuilder
from mbds.build.declarations import Body, delta, variation
from mbds.build.lagrange import DependentEquations, Equations

__all__ = ["Body", "DependentEquations", "Equations", "ModelBuilder", "delta", "variation"]
