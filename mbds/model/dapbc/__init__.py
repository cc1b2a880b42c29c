"""DAP_BC models as mbds systems: one registered class per joint and force element, emitting
sympy expressions that mbds.expr.dapbc_codegen compiles."""

from mbds.model.dapbc.forces import FORCES, register_force
from mbds.model.dapbc.joints import JOINTS, register_joint
from mbds.model.dapbc.system import DapbcSystem, build_system

__all__ = ["DapbcSystem", "FORCES", "JOINTS", "build_system", "register_force", "register_joint"]
