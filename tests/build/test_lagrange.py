"""Lagrange's equations derived by the builder against closed-form results."""

import numpy as np
import pytest
import sympy

from mbds.build import ModelBuilder, delta, variation
from mbds.build import energies as E
from mbds.build import shapes
from mbds.expr import symbols as S

pytestmark = pytest.mark.physics
t = S.T
SQUARE = shapes.polygon([(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)])


def same(a, b) -> bool:
    return sympy.simplify(sympy.expand(a - b)) == 0


def test_simple_pendulum():
    """Point mass m on a massless rod of length l, angle φ from the downward vertical:
    m l² φ̈ = −m g l sin φ (Goldstein, Classical Mechanics, 3rd ed., section 1.6)."""
    mb = ModelBuilder()
    m, l, g = mb.constant("m", 0.5), mb.constant("l", 0.3), mb.constant("g", 9.81)
    phi = mb.free("phi", 0.4)
    mb.generalized(phi)
    x, y = l * sympy.sin(phi), -l * sympy.cos(phi)
    mb.kinetic_energy(E.point_mass_kinetic(m, x, y))
    mb.potential_energy(E.gravity(m, y, g))
    eq = mb.derive()
    assert same(eq.mass_matrix[0][0], m * l**2)
    assert same(eq.h_vector[0], -m * g * l * sympy.sin(phi))
    dphi = sympy.diff(phi, t)
    assert same(eq.energy, m * l**2 * dphi**2 / 2 - m * g * l * sympy.cos(phi))
    assert eq.q0.tolist() == [0.4]


def test_moving_frame_gives_the_inertial_force():
    """A mass at x = q + A sin ωt: T = ½ m (q̇ + Aω cos ωt)², so m q̈ = m A ω² sin ωt."""
    mb = ModelBuilder()
    m, a, w = mb.constant("m", 1.0), mb.constant("A", 0.01), mb.constant("w", 3.0)
    q = mb.free("q")
    mb.generalized(q)
    mb.kinetic_energy(E.point_mass_kinetic(m, q + a * sympy.sin(w * t), 0))
    eq = mb.derive()
    assert same(eq.mass_matrix[0][0], m)
    assert same(eq.h_vector[0], m * a * w**2 * sympy.sin(w * t))


def test_spring_damper_force_and_torque():
    """A body on springs: h = −k(x − l0) − c ẋ + F (x); torque and the moment of a force at a
    body point r = R(φ) p about the origin, r × F (y, Rz)."""
    mb = ModelBuilder()
    k, l0, c = mb.constant("k", 100.0), mb.constant("l0", 0.1), mb.constant("c", 2.0)
    fx, fy, torque = mb.constant("fx", 1.0), mb.constant("fy", -2.0), mb.constant("M", 0.3)
    body = mb.body("block", SQUARE, mass=2.0, inertia=0.01)
    mb.generalized(body.x, body.y, body.Rz)
    mb.kinetic_energy(E.rigid_body_kinetic(body))
    mb.potential_energy(E.spring(k, body.x, l0))
    mb.potential_energy(E.torsional_spring(k, body.Rz))
    mb.dissipation(E.damper(c, body.x))
    px, py = 0.05, 0.02
    mb.virtual_work(E.force(fx, fy, *body.point(px, py)))
    mb.virtual_work(E.torque(torque, body))
    eq = mb.derive()
    phi = body.Rz
    rx = sympy.cos(phi) * px - sympy.sin(phi) * py
    ry = sympy.sin(phi) * px + sympy.cos(phi) * py
    assert same(eq.h_vector[0], -k * (body.x - l0) - c * sympy.diff(body.x, t) + fx)
    assert same(eq.h_vector[1], fy)
    assert same(eq.h_vector[2], -k * phi + torque + rx * fy - ry * fx)
    assert [[same(eq.mass_matrix[i][j], e) for j, e in enumerate(row)]
            for i, row in enumerate([[body.m, 0, 0], [0, body.m, 0], [0, 0, body.Jzz]])] == [[True] * 3] * 3


def test_virtual_work_of_a_dependent_coordinate_goes_through_its_jacobian():
    """A force F along a dependent coordinate c = l sin φ acts on φ with Q = F ∂c/∂φ."""
    mb = ModelBuilder()
    l, f = mb.constant("l", 0.2), mb.constant("F", 5.0)
    arm = mb.body("arm", SQUARE, mass=1.0, inertia=0.02)
    tip = mb.body("tip", SQUARE, mass=1.0, inertia=0.02)
    mb.generalized(arm.Rz)
    mb.dependent(tip.y, l * sympy.sin(arm.Rz))
    mb.dependent(tip.x, tip.y * 2)  # a dependent coordinate of a dependent coordinate
    mb.kinetic_energy(E.rigid_body_kinetic(arm))
    mb.virtual_work(f * variation(tip.y) + f * delta(tip.x))
    eq = mb.derive()
    assert same(eq.h_vector[0], 3 * f * l * sympy.cos(arm.Rz))
    x = eq.dependent[1]
    assert same(x.position, 2 * l * sympy.sin(arm.Rz))
    assert same(x.jacobian[0], 2 * l * sympy.cos(arm.Rz))
    assert same(x.scalar, -2 * l * sympy.sin(arm.Rz) * sympy.diff(arm.Rz, t) ** 2)


def test_double_pendulum_against_its_closed_form():
    """Two uniform rods (m1, J1, l1; m2, J2, l2) and a bob (mb, Jb) at the end of the second,
    angles θ1, θ2 from the x axis. With a = l1 l2 (m2/2 + mb):
    M = [[J1 + m1 l1²/4 + (m2 + mb) l1², a cos(θ1 − θ2)], [·, J2 + m2 l2²/4 + mb l2² + Jb]],
    h1 = −a sin(θ1 − θ2) θ̇2² − g l1 (m1/2 + m2 + mb) cos θ1,
    h2 = a sin(θ1 − θ2) θ̇1² − g l2 (m2/2 + mb) cos θ2 (Lagrange's equations, e.g. Greenwood,
    Principles of Dynamics, 2nd ed., section 6.3)."""
    from tests.build.compare import CAMPAIGNS, load_script

    script = load_script(CAMPAIGNS / "double_pendulum" / "build_double_pendulum.py")
    eq = _derived(script)
    r1, r2, bob = (f"b'{n}'" for n in ("rod1", "rod2", "bob"))
    m1, j1, m2, j2, mb_, jb = (S.mass_property(n, p) for n in ("rod1", "rod2", "bob") for p in ("m", "Jzz"))
    l1, l2, g = S.constant("l1"), S.constant("l2"), S.constant("gravity")
    th1, th2 = S.body_coordinate("rod1", "Rz"), S.body_coordinate("rod2", "Rz")
    a = l1 * l2 * (m2 / 2 + mb_)
    expected_m = [[j1 + m1 * l1**2 / 4 + (m2 + mb_) * l1**2, a * sympy.cos(th1 - th2)],
                  [a * sympy.cos(th1 - th2), j2 + m2 * l2**2 / 4 + mb_ * l2**2 + jb]]
    expected_h = [-a * sympy.sin(th1 - th2) * sympy.diff(th2, t) ** 2 - g * l1 * (m1 / 2 + m2 + mb_) * sympy.cos(th1),
                  a * sympy.sin(th1 - th2) * sympy.diff(th1, t) ** 2 - g * l2 * (m2 / 2 + mb_) * sympy.cos(th2)]
    for i in range(2):
        assert same(eq.h_vector[i], expected_h[i])
        for j in range(2):
            assert same(eq.mass_matrix[i][j], expected_m[i][j])
    assert r1 and r2 and bob


def _derived(script):
    """The equations of a build script's model, derived without writing it."""
    import mbds.build.builder as builder

    captured = {}
    original = builder.ModelBuilder.write

    def keep(self, folder, name):
        captured["equations"] = self.derive()
        return folder

    builder.ModelBuilder.write = keep
    try:
        script.build("unused")
    finally:
        builder.ModelBuilder.write = original
    return captured["equations"]


def test_start_state_and_dependent_start_values():
    mb = ModelBuilder()
    l = mb.constant("l", 0.5)
    arm = mb.body("arm", SQUARE, mass=1.0, inertia=0.02, position=(0, 0, 0.3), velocity=(0, 0, 2.0))
    tip = mb.body("tip", SQUARE, mass=1.0, inertia=0.02)
    mb.generalized(arm.Rz)
    mb.dependent(tip.x, l * sympy.cos(arm.Rz))
    mb.kinetic_energy(E.rigid_body_kinetic(arm))
    eq = mb.derive()
    assert eq.q0.tolist() == [0.3] and eq.qd0.tolist() == [2.0]
    assert eq.dependent[0].start == pytest.approx((0.5 * np.cos(0.3), -0.5 * np.sin(0.3) * 2.0), rel=1e-15)
