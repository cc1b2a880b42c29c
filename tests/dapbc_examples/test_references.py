"""The plain numpy references of benchmarks/dapbc_reference.py checked against analytic results,
so that the comparisons in test_models.py compare mbds with something known to be right."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

from benchmarks.dapbc_reference import GRAVITY, MODELS, Reference, State, funct_c, reference_rhs

TIGHT = dict(method="DOP853", rtol=1e-12, atol=1e-12)


def integrate(ref: Reference, y0, t_end, **kw):
    return solve_ivp(ref.rhs, (0.0, t_end), y0, **(TIGHT | kw))


@pytest.mark.parametrize("name", sorted(MODELS))
def test_initial_conditions_are_consistent(name):
    """The corrected initial state satisfies the constraints on positions and velocities."""
    ref = Reference(name)
    _, y0, _ = reference_rhs(name)
    n = y0.size // 2
    phi, D, nu, _ = ref.rows(y0[:n], y0[n:], 0.0)
    if phi.size:
        assert np.abs(phi).max() < 1e-12
        assert np.abs(D @ y0[n:] - nu).max() < 1e-12


def test_sp_corrected_initial_conditions_match_the_manual():
    """DAP_BC manual, Sec. B.1.1: corrected coordinates x 1, 0.2, 0 and 1.25, -0.23301, 0.5236
    (printed to five significant digits) and zero velocities."""
    _, y0, _ = reference_rhs("SP")
    printed = np.array([1.0, 0.2, 0.0, 1.25, -0.23301, 0.5236])
    assert np.abs(y0[:6] - printed).max() < 5e-5
    assert np.all(y0[6:] == 0.0)


def test_sp_small_oscillations_have_the_linearised_frequencies():
    """About its equilibrium (slider at x = L0 = 0.6 m, pendulum hanging) the sliding pendulum is
    a two-degree-of-freedom oscillator in (x1, phi2) with mass matrix
    [[m1 + m2, m2 l], [m2 l, J2 + m2 l^2]] and stiffness diag(k, m2 g l), l = 0.5 m (pivot to
    centre).  Started in one eigenmode at 1e-5 amplitude, the reference comes back to its
    initial state after one period of that mode."""
    m1, m2, J2, k, l = 5.0, 2.0, 0.2, 20.0, 0.5
    mass = np.array([[m1 + m2, m2 * l], [m2 * l, J2 + m2 * l * l]])
    stiffness = np.diag([k, m2 * GRAVITY * l])
    omega2, modes = eigh(stiffness, mass)
    ref = Reference("SP")
    for w2, mode in zip(omega2, modes.T):
        amp = 1e-5 * mode / np.abs(mode).max()
        x1, th = 0.6 + amp[0], amp[1]
        pivot = np.array([x1, 0.2])
        q = np.array([x1, 0.2, 0.0, pivot[0] + l * np.sin(th), pivot[1] - l * np.cos(th), th])
        y0 = np.concatenate([q, np.zeros(6)])
        period = 2 * np.pi / np.sqrt(w2)
        sol = integrate(ref, y0, period)
        assert np.abs(sol.y[[0, 5], -1] - y0[[0, 5]]).max() < 1e-3 * np.abs(amp).max()
        half = integrate(ref, y0, period / 2)  # half a period later: the opposite displacement
        assert np.allclose(half.y[[0, 5], -1] - [0.6, 0.0], -amp, atol=1e-3 * np.abs(amp).max())


def test_sp_energy_is_conserved():
    """SP has only a spring, gravity and ideal joints: the total energy stays constant."""
    ref = Reference("SP")
    _, y0, _ = reference_rhs("SP")
    sol = integrate(ref, y0, 4.0, t_eval=np.linspace(0, 4, 21))
    energy = np.array([ref.energy(y)[2] for y in sol.y.T])
    assert np.abs(energy - energy[0]).max() < 1e-9


def test_rod_falls_freely_before_the_first_contact():
    """Until its lower end (0.2929 m up at t = 0) reaches the ground the rod is in free fall:
    y = 1 - 6 t - g t^2 / 2, x and phi constant."""
    ref = Reference("Rod")
    _, y0, _ = reference_rhs("Rod")
    t = np.linspace(0, 0.045, 10)  # contact at about 0.048 s
    sol = integrate(ref, y0, t[-1], t_eval=t)
    assert np.allclose(sol.y[1], 1 - 6 * t - GRAVITY * t ** 2 / 2, rtol=0, atol=1e-12)
    assert np.allclose(sol.y[[0, 2]], [[0.0], [np.pi / 4]], rtol=0, atol=1e-12)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # overflow in rejected trial steps in contact
def test_rod_bounces_off_the_ground():
    """The lower end lands first, at 6 m/s plus what gravity adds over its 0.2929 m fall; the
    upper end lands later; the rod leaves with less energy than it arrived with (e = 0.95);
    the solution with located impacts converges."""
    ref = Reference("Rod")
    _, y0, (_, t_end) = reference_rhs("Rod")
    t = np.linspace(0, t_end, 41)
    y = ref.solve(y0, t)
    ends = [end for end, _, _ in ref.impacts]
    assert ends[0] == 0 and 1 in ends
    _, t_hit, rate = ref.impacts[0]
    assert 1 - 6 * t_hit - GRAVITY * t_hit ** 2 / 2 == pytest.approx(np.cos(np.pi / 4), abs=1e-10)  # centre height
    assert rate == pytest.approx(6 + GRAVITY * t_hit, rel=1e-10)
    energy = np.array([ref.energy(s)[2] for s in y])
    assert energy[-1] < energy[0] - 1.0
    # converged: a tenfold looser tolerance moves no state by 1e-6 (it moves them by 1.0e-7 to
    # 1.5e-7 with OpenBLAS' Haswell, SkylakeX and Sandybridge kernels, whose round-off moves the
    # 1e-12 solution itself by up to 6.5e-9). At 1e-10 the step sequence through the stiff Hertz
    # contacts depends on that round-off: 1.2e-7 to 5.3e-5 from the 1e-12 solution by kernel.
    assert np.abs(Reference("Rod").solve(y0, t, 1e-11, 1e-11) - y).max() < 1e-6


def test_cart_a_rolls_at_the_driven_speed():
    """Cart_A has no degree of freedom: phi2 = -2 pi t and rolling without slip give
    x = x0 + 2 pi R t for every body (R = 0.1 m), at rest vertically."""
    ref = Reference("Cart_A")
    _, y0, _ = reference_rhs("Cart_A")
    t = np.linspace(0, 1, 6)
    sol = integrate(ref, y0, 1.0, t_eval=t)
    for k, x0 in enumerate((0.5, 0.2, 0.8)):
        assert np.allclose(sol.y[3 * k], x0 + 0.2 * np.pi * t, rtol=0, atol=1e-9)
        assert np.allclose(sol.y[3 * k + 1], sol.y[3 * k + 1, 0], rtol=0, atol=1e-9)
    assert np.allclose(sol.y[5], -2 * np.pi * t, rtol=0, atol=1e-9)


def test_funct_c_meets_the_manual_conditions():
    """Type c (manual Eq. 8.3): f, f' continuous; f'(t_end) = dfdt_end; f'' = 0 at both ends;
    f' keeps its end value afterwards."""
    f = funct_c(0.5, 0.3, 2.5, -2 * np.pi)
    assert f(0.5) == (0.3, 0.0, 0.0)
    assert f(0.5 + 1e-9)[1] == pytest.approx(0.0, abs=1e-12)
    _, fd, fdd = f(2.5 - 1e-12)
    assert fd == pytest.approx(-2 * np.pi, rel=1e-9) and fdd == pytest.approx(0.0, abs=1e-8)
    assert f(3.5)[0] == pytest.approx(f(2.5)[0] - 2 * np.pi, rel=1e-12)
    # f' integrates to f
    t = np.linspace(0.5, 2.5, 20001)
    fd = np.array([f(s)[1] for s in t])
    assert np.trapezoid(fd, t) == pytest.approx(f(2.5)[0] - 0.3, rel=1e-7)


def test_cart_b_follows_the_type_c_driver():
    """Cart_B: the cart moves by -R (f(t) - f(0)) since the wheels roll without slip."""
    ref = Reference("Cart_B")
    _, y0, _ = reference_rhs("Cart_B")
    f = funct_c(0.0, 0.0, 2.0, -2 * np.pi)
    t = np.linspace(0, 3, 7)
    sol = integrate(ref, y0, 3.0, t_eval=t)
    assert np.allclose(sol.y[0], 0.5 - 0.1 * np.array([f(s)[0] for s in t]), rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", ["Cart_A", "Cart_B", "Cart_C", "Cart_D"])
def test_cart_energy_balance(name):
    """Weight is the carts' only conservative force and the joints are ideal, so the energy
    changes by the work of the driver (lam^T nu: the multipliers times the prescribed rates) and
    of the user forces (motor torque, drag): E(t) - E(0) = integral of lam^T nu + h_user . q'."""
    ref = Reference(name)
    _, y0, _ = reference_rhs(name)
    t = np.linspace(0, 3.0, 601)
    y = ref.solve(y0, t)
    n = y0.size // 2
    power = []
    for tk, yk in zip(t, y):
        _, lam = ref.accelerations(tk, yk)
        _, _, nu, _ = ref.rows(yk[:n], yk[n:], tk)
        h_user = np.zeros(n)
        if ref.model.user is not None:
            ref.model.user(State(yk[:n], yk[n:]), tk, h_user, {})
        power.append(lam @ nu + h_user @ yk[n:])
    work = np.concatenate([[0.0], np.cumsum(np.diff(t) * (np.array(power[1:]) + power[:-1]) / 2)])
    energy = np.array([ref.energy(s)[2] for s in y])
    if name != "Cart_A":  # Cart_A runs at constant speed from the start; the others speed up
        assert np.abs(energy - energy[0]).max() > 1.0
    assert np.allclose(energy - energy[0], work, rtol=0, atol=1e-5 * max(np.abs(work).max(), 1.0))
