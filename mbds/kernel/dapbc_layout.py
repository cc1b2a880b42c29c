"""The bundles the DAP_BC kernels pass around, defined once."""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from mbds.kernel.layout import MATRIX, VECTOR

#: The numbers of one DAP_BC model (SI units):
#: par (n_par,) the element parameters of the generated functions; mass (3 nB,) the diagonal of
#: M (m, m, J per body); functs (nFunct, FUNCT_COLUMNS) the driver functions; point_body (nP,)
#: int64 0-based body of each point, -1 for the ground; point_local (nP, 2) body-fixed
#: coordinates; force_fields (nF, FORCE_FIELD_COUNT) the Force fields user forces read;
#: has_user 1 when the model has a user force.
DapbcData = namedtuple("DapbcData", "par mass functs point_body point_local force_fields has_user")

#: The positions and velocities of bodies and points at one instant, as DAP_BC's user forces
#: see them: r, r_d (nB, 2); p, p_d (nB,); A (nB, 2, 2); rP, rP_d, sP (nP, 2).
BodyArrays = namedtuple("BodyArrays", "r p r_d p_d A rP rP_d sP")

#: Where a resumable integration stands: clock = [t (s), |h| (s), threshold (unused: 0)],
#: counts = [next report index, function evaluations, accepted steps, rejected steps, done].
IntegratorState = namedtuple("IntegratorState", "y f0 clock counts")

NEXT_OUTPUT, NFEV, ACCEPTED, REJECTED, DONE = 0, 1, 2, 3, 4


def integrator_state(y0: np.ndarray) -> IntegratorState:
    """A fresh state at the first report time, before any evaluation."""
    return IntegratorState(np.array(y0, float), np.zeros(len(y0)), np.zeros(3), np.zeros(5, np.int64))

#: DAP_BC's post arrays over nt reports: qdd (nt, 3 nB), lam (nt, nConst), jac (nt, nConst,
#: 3 nB), rP and rPd (nt, nP, 2), eng (nt, 3: kinetic, potential, total; J).
DapbcPost = namedtuple("DapbcPost", "qdd lam jac rP rPd eng")


def post_arrays(nt: int, n: int, nc: int, n_points: int) -> DapbcPost:
    """Zeroed DapbcPost arrays."""
    return DapbcPost(np.zeros((nt, n)), np.zeros((nt, nc)), np.zeros((nt, nc, n)),
                     np.zeros((nt, n_points, 2)), np.zeros((nt, n_points, 2)), np.zeros((nt, 3)))


#: A DAP_BC model's generated functions (mbds.expr.dapbc_codegen) as numba's first-class function
#: values (from its function table, mbds.kernel.function_table), and nc, its number of constraint
#: equations: what mbds.kernel.dapbc_analyses passes to the equations.
DapbcFunctions = namedtuple(
    "DapbcFunctions",
    "constraints jacobian velocity_rhs acceleration_rhs forces_before forces_after user_force potential_energy nc",
)

_V, _M = VECTOR, MATRIX
#: The generated functions with their numba signatures, in the order of DapbcFunctions and of the
#: rows of a DAP_BC model's function table; the user force's arguments are those of
#: mbds.io.dapbc.user_force.SIGNATURE.
DAPBC_FUNCTIONS = {
    "constraints": f"void({_V}, float64, {_V}, {_M}, {_V})",
    "jacobian": f"void({_V}, float64, {_V}, {_M}, {_M})",
    "velocity_rhs": f"void({_V}, float64, {_V}, {_M}, {_V})",
    "acceleration_rhs": f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
    "forces_before": f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
    "forces_after": f"void({_V}, {_V}, float64, {_V}, {_M}, {_V})",
    "user_force": f"void(float64, {_M}, {_V}, {_M}, {_V}, float64[:, :, ::1], {_M}, {_M}, {_M}, {_M}, {_V}, {_M}, {_V})",
    "potential_energy": f"float64({_V}, {_V})",
}
