"""The neutral description of a DAP_BC model: coordinates, parameters, compiled functions and
the numbers the kernels take, built from the records of mbds.io.dapbc.

The joints and force elements emit sympy expressions (mbds.model.dapbc.joints, .forces); here
they are turned into the equations of the book's body-coordinate formulation (Nikravesh,
Planar Multibody Dynamics, 2nd ed., Ch. 7 and 13):

    M q'' - D^T lam = h,   D q'' = gamma,   D = dPhi/dq,   D q' = nu = -dPhi/dt,
    gamma = -(D q')_q q' - 2 (D q')_f f' - Phi_ff f'^2 - Phi_f f''

(f: the driver functions of time), and compiled (mbds.expr.dapbc_codegen).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

import numpy as np
import sympy

from mbds.errors import ModelError
from mbds.expr.dapbc_codegen import DapbcExpressions, compile_dapbc
from mbds.io.dapbc.records import DapbcModel
from mbds.io.dapbc.user_force import FORCE_FIELD_COUNT, UserForceCode, force_field_table, user_force_code
from mbds.kernel.dapbc_layout import DapbcData
from mbds.model.dapbc.drawing import drawing_variables
from mbds.model.dapbc.forces import FORCES
from mbds.model.dapbc.functs import funct_table
from mbds.model.dapbc.joints import JOINTS
from mbds.model.dapbc.symbolic import Symbols
from mbds.model.system import SystemSource


@dataclass(frozen=True)
class DapbcSystem:
    """A DAP_BC model ready to analyse: its compiled module (see mbds.expr.dapbc_codegen), the
    kernel data, initial coordinates and velocities (3 per body: x, y, phi), the number of
    constraints with a name for each, the number of contact-state slots, the parameter labels
    where it came from and what a drawing of it needs (mbds.model.dapbc.drawing). ``model`` holds the records it was built from, for the front-end
    only (a campaign variant changes a field there and builds again); the analyses and the
    outputs read ``source`` and the arrays, never the records."""

    model: DapbcModel
    module: ModuleType
    data: DapbcData
    q0: np.ndarray
    qd0: np.ndarray
    constraint_names: list[str]
    n_state: int
    parameter_labels: list[str]
    source: SystemSource
    drawing: tuple[dict, dict, dict]

    @property
    def n_points(self) -> int:
        return self.data.point_body.size

    @property
    def n(self) -> int:
        return self.q0.size

    @property
    def nc(self) -> int:
        return len(self.constraint_names)


def initial_coordinates(model: DapbcModel) -> tuple[np.ndarray, np.ndarray]:
    """(q0, qd0) from the bodies' r, p, r_d, p_d."""
    q = np.concatenate([[*b.r, b.p] for b in model.bodies]).astype(float)
    qd = np.concatenate([[*b.r_d, b.p_d] for b in model.bodies]).astype(float)
    return q, qd


def _rigid_offset(model: DapbcModel, joint) -> np.ndarray:
    """d0 of a rigid joint: r_i - r_j in body j's frame at the initial coordinates."""
    def pose(b):
        return (np.zeros(2), 0.0) if b == 0 else (model.bodies[b - 1].r, model.bodies[b - 1].p)
    (ri, _), (rj, pj) = pose(joint.iBindex), pose(joint.jBindex)
    c, s = np.cos(pj), np.sin(pj)
    return np.array([[c, s], [-s, c]]) @ (ri - rj)


def equations(model: DapbcModel) -> tuple[DapbcExpressions, Symbols, list[str], UserForceCode | None]:
    """The model's equations as sympy expressions, its symbols, the constraint names and its
    user force."""
    s = Symbols(model)
    phi, names = [], []
    for index, joint in enumerate(model.joints, start=1):
        element = JOINTS[joint.type](joint, index, {"rigid_d0": _rigid_offset(model, joint)})
        rows = element.rows(s)
        phi += rows
        names += [f"joint {index} {joint.type} {name}" for name in element.names]
    q, qd = s.q, s.qd
    Phi = sympy.Matrix(phi) if phi else sympy.zeros(0, 1)
    D = Phi.jacobian(q) if phi else sympy.zeros(0, s.n)
    f_symbols = [f for f, _, _ in s.functions]
    rates = {f: fd for f, fd, _ in s.functions}
    second = {f: fdd for f, _, fdd in s.functions}
    nu, gamma = [], []
    for k in range(len(phi)):
        used = [f for f in f_symbols if Phi[k].has(f)]
        Dqd = (D[k, :] * qd)[0]
        nu.append(sympy.expand(-sum((sympy.diff(Phi[k], f) * rates[f] for f in used), sympy.Integer(0))))
        g = -(sympy.Matrix([Dqd]).jacobian(q) * qd)[0]
        for f in used:
            g -= 2 * sympy.diff(Dqd, f) * rates[f] + sympy.diff(Phi[k], f) * second[f]
            for f2 in used:
                g -= sympy.diff(Phi[k], f, f2) * rates[f] * rates[f2]
        gamma.append(g)
    mass = [s.parameter(body.m, f"body {b} m") for b, body in enumerate(model.bodies, start=1)]
    h_before, h_after = [sympy.Integer(0)] * s.n, [sympy.Integer(0)] * s.n
    potential = sympy.Integer(0)
    user_seen = False
    for index, force in enumerate(model.forces, start=1):
        if force.type == "user":
            user_seen = True
            continue
        potential += FORCES[force.type](force, index).add(s, h_after if user_seen else h_before, mass)
    code = user_force_code(model) if user_seen else None
    if user_seen and code is None:
        pos = next(f for f in model.forces if f.type == "user").where("type")
        raise ModelError("a force of type 'user' needs user_force.m (or user_force.py) in the model folder",
                         *((pos.file, pos.line) if pos else ()))
    expressions = DapbcExpressions(
        n=s.n, phi=list(Phi), jacobian=[list(D.row(k)) for k in range(len(phi))], nu=nu, gamma=gamma,
        forces_before=h_before, forces_after=h_after, potential=potential,
        user_imports=code.imports if code else None, user_source=code.function_source if code else None)
    return expressions, s, names, code


def build_system(model: DapbcModel) -> DapbcSystem:
    """Compile (or load from the cache) the model's module and gather its numbers."""
    expressions, s, names, code = equations(model)
    module = compile_dapbc(expressions)
    q0, qd0 = initial_coordinates(model)
    mass = np.ravel([[b.m, b.m, b.J] for b in model.bodies]).astype(float)
    data = DapbcData(
        par=np.array(s.values, float),
        mass=mass,
        functs=funct_table(model.functs),
        point_body=np.array([p.Bindex - 1 for p in model.points], np.int64),
        point_local=np.array([p.sPlocal for p in model.points], float).reshape(-1, 2),
        force_fields=force_field_table(model.forces).reshape(-1, FORCE_FIELD_COUNT),
        has_user=int(code is not None),
    )
    return DapbcSystem(model, module, data, q0, qd0, names, code.n_state if code else 0, list(s.labels),
                       dapbc_source(model), drawing_variables(model))


def dapbc_source(model: DapbcModel) -> SystemSource:
    """The folder's name and path and its in-files (with user_force.m or .py where present)."""
    extra = [p for p in (model.user_force_file, model.user_force_py) if p is not None]
    return SystemSource(model.folder.name, model.folder, tuple([*model.files.values(), *extra]))
