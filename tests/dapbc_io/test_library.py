"""The DAP_BC library functions of mbds/kernel/dapbc_library.py, against the published formulas."""

from __future__ import annotations

import math

import pytest

from mbds.kernel.dapbc_library import (contact_flores, contact_lankarani_nikravesh, friction_anderson)


def test_contact_laws_at_first_contact_and_without_speed():
    """Eq. 11.42 (Lankarani and Nikravesh 1990) and 11.43 (Flores et al. 2011): at the first
    contact d' = d'0, so the factors are 1 + 3(1 - e^2)/4 and 1 + 8(1 - e)/(5e); with e = 1 both
    are purely elastic Hertz forces k d^1.5."""
    k, d, e = 2e9, 3e-5, 0.8
    assert contact_lankarani_nikravesh(d, 1.7, 1.7, k, e) == pytest.approx(k * d ** 1.5 * (1 + 0.75 * 0.36))
    assert contact_flores(d, 1.7, 1.7, k, e) == pytest.approx(k * d ** 1.5 * (1 + 8 * 0.2 / 4.0))
    for law in (contact_lankarani_nikravesh, contact_flores):
        assert law(d, -0.4, 1.7, k, 1.0) == pytest.approx(k * d ** 1.5)
        # a contact that began at rest has no damping term (instead of a division by zero)
        assert law(d, 0.3, 0.0, k, e) == pytest.approx(k * d ** 1.5)


def test_anderson_friction_limits():
    """Anderson et al. (2007): mu -> mu_s near v = 0+ (tanh saturated), mu -> mu_d for |v| >> v_s,
    odd in v."""
    mu_s, mu_d, v_s, p, k_t = 0.2, 0.15, 1e-3, 2.0, 1e6
    assert friction_anderson(mu_s, mu_d, v_s, p, k_t, 1e-5) == pytest.approx(mu_s, rel=1e-3)
    assert friction_anderson(mu_s, mu_d, v_s, p, k_t, 0.1) == pytest.approx(mu_d, rel=1e-12)
    assert friction_anderson(mu_s, mu_d, v_s, p, k_t, -0.1) == -friction_anderson(mu_s, mu_d, v_s, p, k_t, 0.1)
    assert friction_anderson(mu_s, mu_d, v_s, p, k_t, 0.0) == 0.0
    assert math.isfinite(friction_anderson(mu_s, mu_d, v_s, p, k_t, 1e3))
