"""The stepper's array layout, defined once: indices into its flat arrays and the named bundles
of arrays it takes, with their constructors.

The kernel and the output modules both read this module; nothing here is compiled. The
bundles are namedtuples, which numba passes to compiled functions like tuples with names.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

VECTOR, MATRIX = "float64[::1]", "float64[:, ::1]"  # C-contiguous, in numba signature strings
MODEL_FUNCTIONS = {
    "mass_matrix": f"void({VECTOR}, float64, {VECTOR}, {MATRIX})",
    "h_vector": f"void({VECTOR}, {VECTOR}, float64, {VECTOR}, {VECTOR})",
    "dependent_state": f"void({VECTOR}, {VECTOR}, {VECTOR}, float64, {VECTOR}, {VECTOR}, {VECTOR}, {VECTOR})",
    "dependent_jacobian": f"void({VECTOR}, {VECTOR}, float64, {VECTOR}, {MATRIX}, {VECTOR})",
    "mechanical_energy": f"float64({VECTOR}, {VECTOR}, float64, {VECTOR})",
    "contact_law": f"void(int64, float64, float64, {VECTOR}, {VECTOR})",
}
"""A model's generated functions (mbds.expr.codegen) with their numba signatures, in the order of
the rows of the function table the stepper takes (mbds.kernel.function_table)."""

# settings array: steps (s), penetration (m), velocity (m/s), LCP tolerances, flags; the passes
# of the step loop one call of advance may make before it returns (so callers look at Ctrl-C,
# time limits and progress at least that often)
DT_MIN, DT_MAX, MAX_PEN, ZERO_VELOCITY, PIVOT_MIN, PIVOT_MAX, LEXICO, LEXICO_LOW, LEXICO_HIGH = range(9)
GO_BACK, SAMPLE_EVERY, SAMPLE_AT_COLLISION, SAMPLE_EACH_STEP, MAX_PIVOTS, PASSES_PER_CALL, SETTINGS = range(9, 16)

# clock array: time and step (s), counters, lost and drive work (J), penetrations (m)
T, DT, NEXT_SAMPLE, STEPS, IMPACTS, REJECTED, LOST, DRIVE_WORK, MAX_PENETRATION = range(9)
LCP_FAILURES, OVER_PENETRATIONS, LAST_PENETRATION, CLOCK = range(9, 13)

# statuses of advance
REACHED, HISTORY_FULL, EVENTS_FULL, CAPACITY, NOT_FINITE, PASSES_DONE = range(6)

# event codes (events array rows: time, code, value, value)
EVENT_LCP_RAY, EVENT_LCP_MAX_PIVOTS, EVENT_LCP_FAILURE, EVENT_OVER_PENETRATION, EVENT_BAD_LAW, EVENT_SINGULAR_MASS = range(6)

# columns of per-point values: impulses (N s) and lost work (J) since the last sample, the last
# contact angle (rad), the temperature (deg C; NaN where no contact pair has a temperature model)
IMP_N, IMP_T, IMP_X, IMP_Y, WORK, ANGLE, TEMP, POINT_COLUMNS = range(8)

# columns of the per-point heat model: heating (deg C per J), cooling rate (1/s), ambient (deg C)
HEATING, COOLING, AMBIENT, HEAT_COLUMNS = range(4)

# float columns of the per-contact records kept for going back (integer columns: vertex,
# edge start and edge end points; the closing point of a shape is never used)
R_XI, R_IMP_N, R_IMP_T, R_IMP_X, R_IMP_Y, R_LOSS, R_ANGLE, RECORD_COLUMNS = range(8)

ModelArrays = namedtuple(
    "ModelArrays",
    "binding binding_index start_pose carrier offset points point_start point_reflex concave skin factor "
    "radius pair_bodies pair_law pair_resisting pair_temperature pair_heated point_heat watch_start watch_points p",
)
"""The model's kernel arrays (see mbds.model.arrays.KernelArrays); p: its parameters."""

Bodies = namedtuple("Bodies", "world boxes pose vel B bhat beta trig dpos dvel dacc djac dsc zero margin motion")
"""Body kinematics at one state: world points (m), bounding boxes, poses, velocities, the
Jacobians B and their derivative terms, cosine and sine of each body's angle, dependent
coordinates, detection margins (m) and speed bounds (see mbds.kernel.motion)."""

Contacts = namedtuple("Contacts", "pair vb vertex eb edge xi gap normal point work frames order")
"""Detected vertex-edge contacts: pair, vertex body and point, edge body and start point,
edge parameter xi, gap (m), unit normal out of the edge body, contact point (m); work, frames:
detection scratch (the second for edge tangents, lengths and the ends of their bands); order:
0, 1, 2, ... (the index list of all contacts, for functions that take a list of contacts)."""

Rows = namedtuple("Rows", "WN WT what_n what_t wbar_n wbar_t gd_n gd_t laws law_out")
"""Contact rows: W_N, W_T, the velocity and acceleration terms, relative velocities (m/s) and
the law of each contact (mu, eN, eT, nu); law_out: scratch for one law evaluation."""

Dynamics = namedtuple("Dynamics", "M L profile M_factored hv minv_h YN YT")
"""Mass matrix, its Cholesky factor, the factor's nonzero envelope (mbds.kernel.linalg.envelope)
and the matrix L was factorised from (NaN: none yet), h, M^-1 h and M^-1 W_N, M^-1 W_T of the
contacts."""

Problem = namedtuple(
    "Problem",
    (
        "column hrow span active stick sign jammed group root grouped masks A_flat bvec z w state memory memory_count"
        " gram fwork iwork"
    ),
)
"""The LCPs being set up and solved: contact set (active, stick, sign; jammed: in a group whose
contact-force LCP failed at its last solve), its independent groups
(mbds.kernel.components: bounds, scratch and the nonzero columns of W and Y rows), matrices,
vectors, the contact states (mbds.kernel.active_set) being tried and those remembered for the 2
impact LCPs and the contact-force LCPs (rows: vertex, edge, state; a fourth slot collects those of
the groups being solved), scratch (gram: for mbds.kernel.redundancy)."""

Forces = namedtuple(
    "Forces", "lam_n lam_t lam_n1 lam_t1 imp_n imp_t gam_n gam_t gap0 compression_loss a1 a2 q_star u_star",
)
"""Contact forces (N) at the end and start of a step, impulses (N s), velocities before a
phase, the gaps at the step's start (m), compression losses (J), accelerations at both ends and
Heun's predictor state."""

# slots of the rollback: the starts of the last three steps, LAST_SLOT the most recent
ROLLBACK_SLOTS = 3
LAST_SLOT = ROLLBACK_SLOTS - 1

Rollback = namedtuple(
    "Rollback", "q u clock temperature records_int records_float record_count last_sample cap tracked pending",
)
"""The starts of the last ROLLBACK_SLOTS steps (slot LAST_SLOT: the last, 0: the oldest:
coordinates, clock and point temperatures) and their contact records, for going back (a record
count of -1: the slot cannot be gone back to); the time of the last history sample (s); the
longest next step (s) after a step was rejected; how many contacts of the last step are checked
at its end; the depth (m) they were found at by a pass that ran out of contact capacity, for
its rerun in a larger workspace (NaN: none)."""

Workspace = namedtuple("Workspace", "bodies contacts rows dynamics problem forces rollback")
"""All scratch arrays of the stepper."""

History = namedtuple("History", "time q u a energy lost drive watch count")
"""History samples: time (s), q, u, q'', energy, lost and drive work (J), watched points, count."""

Events = namedtuple("Events", "data count")
"""Event rows (time, code, value, value) and their count."""


def workspace(n: int, m: int, nb: int, points: int, pairs: int, capacity: int, fwork, iwork) -> Workspace:
    """Scratch arrays for n coordinates, m dependent coordinates, nb bodies, ``points`` shape
    points, ``pairs`` contact pairs and up to ``capacity`` simultaneous contacts (LCPs of size
    up to 3 * capacity, and room besides for the normal rows of an impact's contacts, see
    mbds.kernel.impact; with the LCP solver's scratch fwork, iwork)."""
    c, size = capacity, 3 * capacity
    f = np.zeros
    bodies = Bodies(
        f((points, 2)), f((nb, 4)), f((nb, 3)), f((nb, 3)), f((nb, 3, n)), f((nb, 3)), f((nb, 3)), f((nb, 2)),
        f(m), f(m), f(m), f((m, n)), f(m), f(n), f(pairs), f((nb, 4)),
    )
    i = np.int64
    contacts = Contacts(
        f(c, i), f(c, i), f(c, i), f(c, i), f(c, i), f(c), f(c), f((c, 2)), f((c, 2)), f(3 * points + 2050, i),
        f((points, 5)), np.arange(c, dtype=i),
    )
    rows = Rows(f((c, n)), f((c, n)), f(c), f(c), f(c), f(c), f(c), f(c), f((c, 4)), f(4))
    dynamics = Dynamics(f((n, n)), f((n, n)), f((2, n), i), np.full((n, n), np.nan), f(n), f(n), f((c, n)),
                        f((c, n)))
    problem = Problem(
        f((c, n)), f(c, i), f((c, 4), i), f(c, i), f(c, np.bool_), f(c), f(c, np.bool_), f(c + 1, i), f(c, i),
        f(c, i),
        f((2, c, (n + 63) // 64), np.uint64), f(size * size + c * c), f(size), f(size), f(size), f(c, i),
        f((4, c, 3), i), f(3, i), f((n + 2, n)), fwork, iwork,
    )
    forces = Forces(f(c), f(c), f(c), f(c), f(c), f(c), f(c), f(c), f(c), f(c), f(n), np.full(n, np.nan), f(n), f(n))
    s = ROLLBACK_SLOTS
    rollback = Rollback(
        f((s, n)), f((s, n)), f((s, CLOCK)), f((s, points)), f((s, 2 * c, 3), i), f((s, 2 * c, RECORD_COLUMNS)),
        np.full(s, -1, dtype=i), np.full(1, -np.inf), np.full(1, np.inf), f(1, i), np.full(1, np.nan),
    )
    return Workspace(bodies, contacts, rows, dynamics, problem, forces, rollback)


def history_buffers(n: int, watches: int, length: int) -> History:
    """History arrays for ``length`` samples of n coordinates and ``watches`` watched points."""
    f = np.zeros
    return History(f(length), f((length, n)), f((length, n)), f((length, n)), f(length), f(length), f(length),
                   f((length, watches, POINT_COLUMNS)), np.zeros(1, dtype=np.int64))
