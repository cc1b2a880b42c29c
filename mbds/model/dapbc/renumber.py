"""A built DAP_BC system with another model's numbers, without sympy.

The generated code of a model depends on its structure only (element types and indices); each
number it uses is a parameter ``par[k]`` whose label names the element field it came from
(``force 1 k``, ``point 2 sPlocal x``, ``unit vector 1 ulocal y``, ``body 3 m``, ``joint 2 d0 x``).
So a model of the same structure (a campaign variant: other masses, stiffnesses, initial
conditions) needs no new equations: :func:`with_numbers` reads each labelled field from it and
gathers the kernel data as :func:`mbds.model.dapbc.system.build_system` does, in microseconds
instead of the half second that building the equations takes.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np

from mbds.io.dapbc.fields import field_kind
from mbds.io.dapbc.records import DapbcModel
from mbds.io.dapbc.user_force import FORCE_FIELD_COUNT, force_field_table
from mbds.model.dapbc.drawing import drawing_variables
from mbds.model.dapbc.functs import funct_table
from mbds.model.dapbc.system import DapbcSystem, _rigid_offset, initial_coordinates

_LABEL = re.compile(r"(body|point|unit vector|force|joint) (\d+) (\w+)(?: ([xy]))?")
_LISTS = {"body": "bodies", "point": "points", "unit vector": "uvectors", "force": "forces", "joint": "joints"}


def parameter_value(model: DapbcModel, label: str) -> float:
    """The number the parameter ``label`` takes in ``model``."""
    kind, index, name, axis = _LABEL.fullmatch(label).groups()
    element = getattr(model, _LISTS[kind])[int(index) - 1]
    value = _rigid_offset(model, element) if (kind, name) == ("joint", "d0") else getattr(element, name)
    return float(value[0 if axis == "x" else 1] if axis else value)


def same_structure(a: DapbcModel, b: DapbcModel) -> bool:
    """Whether two models have the same elements, types and indices (what the code depends on)."""
    def shape(model):
        return [(type(e).__name__, *(getattr(e, f) for f in e.field_names() if field_kind(e, f) in ("index", "text")))
                for kind in ("bodies", "points", "uvectors", "forces", "joints", "functs") for e in getattr(model, kind)]
    return shape(a) == shape(b) and (a.user_force_file, a.user_force_py) == (b.user_force_file, b.user_force_py)


def with_numbers(system: DapbcSystem, model: DapbcModel) -> DapbcSystem:
    """``system`` with the numbers of ``model``, a model of the same structure
    (:func:`same_structure`); the compiled module is shared."""
    q0, qd0 = initial_coordinates(model)
    data = system.data._replace(
        par=np.array([parameter_value(model, label) for label in system.parameter_labels], float),
        mass=np.ravel([[b.m, b.m, b.J] for b in model.bodies]).astype(float),
        functs=funct_table(model.functs),
        point_local=np.array([p.sPlocal for p in model.points], float).reshape(-1, 2),
        force_fields=force_field_table(model.forces).reshape(-1, FORCE_FIELD_COUNT),
    )
    return dataclasses.replace(system, model=model, data=data, q0=q0, qd0=qd0, drawing=drawing_variables(model))
