"""An oblique impact with friction and tangential restitution against the impact law of
docs/theory.md §4, computed here independently for one contact, and the treatment of the
manual's ``parameterNi`` (ν), which mbds reads but does not use (docs/theory.md, "The
tangential restitution parameter ν").

The body is a 64-sided polygon disc whose lowest vertex lies straight below its centre, so the
single contact has uncoupled directions: the normal impulse does not turn the disc
(D_NT = 0), and the tangential one acts with D_TT = 1/m + R²/J."""

import numpy as np
import pytest

from tests.physics.models import BodyOnFloor, energy_residual, regular_polygon, run_folder

pytestmark = pytest.mark.physics

RADIUS = 0.05  # m, circumradius of the disc
MASS = 1.0  # kg
INERTIA = 0.5 * MASS * RADIUS**2  # kg m²
GAP = 1e-3  # m, height of the lowest vertex above the floor at the start
APPROACH = 1.0  # m/s, normal approach speed
MU = 0.15  # friction coefficient
E_N = 0.5  # normal restitution


def disc(tangential: float, spin: float, e_t: float, nu: float, folder):
    """Write the disc model moving at (tangential, -APPROACH) m/s with ``spin`` rad/s into
    ``folder``, with restitutionTangent ``e_t`` and parameterNi ``nu``; return the folder. A
    spinning disc starts turned back so that its lowest vertex is straight below the centre
    when it touches."""
    tilt = -spin * GAP / APPROACH
    model = BodyOnFloor(regular_polygon(64, RADIUS), MASS, INERTIA, position=(0.0, RADIUS + GAP, tilt),
                        velocity=(tangential, -APPROACH, spin), gravity=(0.0, 0.0), friction=MU, restitution=E_N,
                        break_time=GAP / APPROACH + 1e-3, max_penetration=1e-8, dt_max=1e-5)
    folder = model.write(folder)
    cop = folder / "model.cop"
    cop.write_text(cop.read_text().replace("restitutionTangent = 0", f"restitutionTangent = {e_t!r}")
                   .replace("parameterNi = 0", f"parameterNi = {nu!r}"))
    return folder


def poisson_impact(gamma_t: float, e_t: float) -> tuple[float, float]:
    """Normal and tangential impulse (N s) of one contact with D_NT = 0 hit at normal speed
    APPROACH and tangential relative velocity ``gamma_t`` (m/s), by docs/theory.md §4:

    compression: Λ_NC = m v_n; Λ_TC sticks (γ_TC = 0) if |γ_TA|/D_TT ≤ μ Λ_NC, else it slides
    (Λ_TC = -μ Λ_NC sgn γ_TA); expansion: Λ_NE = ε_N Λ_NC, Λ_TE = ε_T Λ_TC + ΔΛ_T, where the
    increment ΔΛ_T obeys Coulomb's law with the bound μ Λ_NE on the velocity that the preset
    impulse ε_T Λ_TC leaves."""
    d_tt = 1.0 / MASS + RADIUS**2 / INERTIA
    lam_nc = MASS * APPROACH
    lam_tc = -gamma_t / d_tt
    if abs(lam_tc) > MU * lam_nc:
        lam_tc = -MU * lam_nc * np.sign(gamma_t)
    gamma_c = gamma_t + d_tt * lam_tc
    lam_ne = E_N * lam_nc
    left = gamma_c + d_tt * e_t * lam_tc  # tangential velocity after the preset expansion impulse
    increment = -left / d_tt
    if abs(increment) > MU * lam_ne:
        increment = -MU * lam_ne * np.sign(left)
    return lam_nc + lam_ne, lam_tc + e_t * lam_tc + increment


CASES = [  # (v_x m/s, spin rad/s, ε_T): what the impact does
    (0.3, 0.0, 0.0),  # sticks in both phases
    (0.3, 0.0, 0.3),  # sticks in compression; the released ε_T Λ_TC is held by friction
    (0.3, 0.0, 0.9),  # sticks in compression; the contact's tangential velocity reverses
    (0.5, 0.0, 0.6),  # slides through compression, sticks in expansion
    (1.0, 0.0, 0.6),  # slides through both phases
    (0.2, 30.0, 0.8),  # spinning disc: slides through both phases
]


@pytest.mark.parametrize("vx, spin, e_t", CASES)
def test_oblique_impact_with_tangential_restitution(tmp_path, vx, spin, e_t):
    result = run_folder(disc(vx, spin, e_t, 0.0, tmp_path))
    # the contact point (0, -R) of the disc moves at v_x + ω R along +x
    lam_n, lam_t = poisson_impact(vx + spin * RADIUS, e_t)
    expected = (vx + lam_t / MASS, E_N * APPROACH, spin + RADIUS * lam_t / INERTIA)
    np.testing.assert_allclose(result.u[-1], expected, rtol=1e-9, atol=1e-12)
    assert lam_n == pytest.approx((1.0 + E_N) * MASS * APPROACH)
    before = 0.5 * MASS * (vx**2 + APPROACH**2) + 0.5 * INERTIA * spin**2
    after = 0.5 * MASS * (expected[0] ** 2 + expected[1] ** 2) + 0.5 * INERTIA * expected[2] ** 2
    assert result.lost[-1] == pytest.approx(before - after, rel=1e-9)
    assert np.abs(energy_residual(result)).max() < 1e-12


def test_the_reversal_case_does_reverse(tmp_path):
    """The third case is the one where ε_T shows: the contact point's tangential velocity
    changes sign (0.3 m/s before, -0.045 m/s after: ε_T γ_TA less D_TT μ ε_N Λ_NC)."""
    result = run_folder(disc(0.3, 0.0, 0.9, 0.0, tmp_path))
    vx, _, omega = result.u[-1]
    assert vx + omega * RADIUS == pytest.approx(-0.9 * 0.3 + 3.0 * MU * E_N * MASS * APPROACH, rel=1e-9)


def test_parameter_ni_is_read_but_does_not_change_the_impact(tmp_path):
    """ν ≠ 0 gives bit-identical results to ν = 0: the law of §4 has no ν (the Pfeiffer–Glocker
    ν-law could not be recovered from the sources; docs/theory.md)."""
    plain = run_folder(disc(0.3, 0.0, 0.9, 0.0, tmp_path / "nu0"))
    with_nu = run_folder(disc(0.3, 0.0, 0.9, 0.7, tmp_path / "nu07"))
    np.testing.assert_array_equal(with_nu.u, plain.u)
    np.testing.assert_array_equal(with_nu.q, plain.q)
    np.testing.assert_array_equal(with_nu.lost, plain.lost)
