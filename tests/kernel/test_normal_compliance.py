"""The retry with a normal compliance of a contact LCP whose normal rows are dependent
(docs/theory.md §3, "Normal rows that are dependent").

The LCP holds the normal rows of an impact's compression in a pile of polygons (seed 107 of the
pile in tests/physics/test_concave_corners.py, t = 0.1798 s), as the stepper built them. A vertex
of a polygon lies in the seam where a wall stands on the floor: it touches the floor's top face
(row 0) and the wall's bottom face (row 3), which lie on one line with opposite normals, so the
two rows are exact opposites, and it touches the wall's corner (rows 1 and 2). In a run that
reached this seam, Lemke's method ended on a ray on this LCP and on the impact's LCP with
friction, at every step size down to minimumTimestep; the impact was left unsolved, and the
vertex went 0.47 mm into the floor. With the normal compliance the impact's LCP with friction
solves.

Source: Poisson's compression phase stops every approaching contact with compressive impulses.
With a normal compliance c, a contact may go on approaching at c times its impulse, and the
impulses cannot add kinetic energy: with w = (A + c I) z + q, z.w = 0 gives
dT = z.q + z.A z / 2 = -z.A z / 2 - c |z|^2 <= 0 for the symmetric Delassus matrix A.
"""

import numpy as np

from mbds.kernel import layout as K
from mbds.kernel.contact_problem import STICK_COMPLIANCE, _normal_compliant_lemke
from mbds.kernel.lcp import SOLVED, lcp_workspace, lemke

A = np.array([
    [1.964483472633468, -1.1525262959631597, 2.0125703235959973, -1.964483472633468],
    [-1.1525262959631597, 1.9989640308450831, -1.2415359320351886, 1.1525262959631597],
    [2.012570323595997, -1.2415359320351882, 2.06462862407383, -2.012570323595997],
    [-1.964483472633468, 1.1525262959631597, -2.0125703235959973, 1.964483472633468],
])  # 1/kg
Q = np.array([-1.17848687697375e-07, 7.422265207736256e-08, -1.4485225903109523e-07, 1.17848687697375e-07])  # m/s
PIVOT_MIN, PIVOT_MAX, LEXICO = 1e-14, 1e-10, 1e-8  # the world file's defaults


def test_rows_in_a_seam_defeat_plain_lemke():
    np.testing.assert_array_equal(A[0], -A[3])
    assert Q[0] == -Q[3]
    fwork, iwork = lcp_workspace(4)
    status, _ = lemke(A.copy(), Q, np.zeros(4), np.zeros(4), PIVOT_MIN, PIVOT_MAX, LEXICO, 10_000, fwork, iwork)
    assert status != SOLVED


def test_the_normal_compliance_stops_the_seam_vertex_without_making_energy():
    settings = np.zeros(K.SETTINGS)
    settings[K.PIVOT_MIN], settings[K.PIVOT_MAX], settings[K.MAX_PIVOTS] = PIVOT_MIN, PIVOT_MAX, 10_000
    fwork, iwork = lcp_workspace(4)
    z, w = np.zeros(4), np.zeros(4)
    status, _ = _normal_compliant_lemke(A.copy(), Q, z, w, 4, settings, LEXICO, fwork, iwork)
    assert status == SOLVED
    assert np.all(z >= 0.0)
    compliance = STICK_COMPLIANCE * A.diagonal().max()
    velocities = A @ z + Q  # m/s after the impulses z (N s)
    assert np.all(velocities >= -compliance * z - 1e-9 * np.abs(Q).max())  # approach at most c z
    assert np.all(velocities[z == 0.0] >= -1e-9 * np.abs(Q).max())
    kinetic = z @ Q + 0.5 * z @ A @ z  # J: the change of kinetic energy
    assert kinetic <= 0.0
