"""The compliant retry of a contact LCP whose stick rows coincide (docs/theory.md §3, "Stick rows
that coincide").

The LCP is the contact-force LCP of a regular pentagon (9.24 kg) lying on one face on a
horizontal floor, friction 0.853, both corners stick candidates, as the stepper built it
(tests/physics/test_resting_flat.py, "pentagon at rest", t = 0.4114 s). Rows: the two normal
accelerations, the two stick rows, the two cone rows. Unknowns: λ_N, λ_0R = λ_T + μ λ_N, and the
slack of the cone. The stick block's determinant is 7.9e-15 against entries of 0.29. With the
run's tolerances, Lemke's end point failed its solution check on it at every step.

By statics, a body lying on a horizontal floor under its weight alone needs no friction force.
The normal forces must leave the normal accelerations zero. The friction forces of the two
coinciding rows must then be zero, and the contacts must not slide.
"""

import numpy as np

from mbds.kernel import layout as K
from mbds.kernel.contact_problem import STICK_COMPLIANCE, _compliant_lemke
from mbds.kernel.lcp import SOLVED, lcp_workspace

A = np.array([
    [0.31955450502499605, 0.12516792150252126, -0.13377509686989195, -0.13377518078953549, 0.0, 0.0],
    [-0.10303092423826193, 0.09135542827347484, 0.13377493789038167, 0.13377502180992548, 0.0, 0.0],
    [-0.38315791970487423, -0.1156079834614446, 0.29238712242227516, 0.2923872379276504, 1.0, 0.0],
    [-0.3831581021413618, -0.11560799805880663, 0.2923872379276504, 0.2923873534330982, 0.0, 1.0],
    [1.7058399889090554, 0.0, -1.0, 0.0, 0.0, 0.0],
    [0.0, 1.7058399889090554, 0.0, -1.0, 0.0, 0.0],
])
Q = np.array([-9.81, -9.81, -6.624579082756733e-24, -6.623990656315413e-24, 0.0, 0.0])
MU = 0.5 * A[4, 0]  # the cone rows hold 2 mu lambda_N - lambda_0R >= 0


def test_the_compliant_retry_finds_the_resting_forces():
    settings = np.zeros(K.SETTINGS)
    settings[K.PIVOT_MIN], settings[K.PIVOT_MAX], settings[K.MAX_PIVOTS] = 1e-14, 1e-10, 1e5
    fwork, iwork = lcp_workspace(6)
    z, w = np.zeros(6), np.zeros(6)
    status, _ = _compliant_lemke(A.copy(), Q, z, w, 2, 2, np.array([0, 1]), settings, 1e-8, fwork, iwork)
    assert status == SOLVED
    residual = A @ z + Q  # on the LCP without the compliance
    assert np.all(z[:2] > 0.0)
    assert np.abs(residual[:2]).max() <= 1e-8 * np.abs(Q).max()  # m/s²: no normal acceleration
    friction = z[2:4] - MU * z[:2]  # lambda_T (N)
    assert np.abs(friction).max() <= 1e-5 * MU * z[:2].min()
    # the compliance acts on the friction force lambda_T, which is zero here: the stick rows do not
    # slide (a compliance on lambda_0R = mu lambda_N would leave them sliding by c mu lambda_N)
    compliance = STICK_COMPLIANCE * max(A[2, 2], A[3, 3])
    assert np.abs(residual[2:4]).max() <= 1e-3 * compliance * MU * z[:2].min()
