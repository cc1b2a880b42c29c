"""Joints, forces and driver functions of the DAP_BC manual (Tables B.4-B.6) against analytic
motions (the book: Nikravesh, Planar Multibody Dynamics, 2nd ed., Ch. 7 and 8)."""

import numpy as np
import pytest

from mbds import dapbc
from mbds.io.dapbc.records import Funct
from mbds.kernel.dapbc_functions import funct_value
from mbds.model.dapbc.functs import funct_table
from tests.dapbc_core.infiles import write_model

TIGHT = dict(rtol=1e-10, atol=1e-12)


@pytest.fixture(scope="module")
def elements(tmp_path_factory):
    """Body 1: pinned at its centre (rev), rot-sda k = 8 N m/rad and constant torque T = 0.8
    N m, J = 0.5: phi = 0.1 + 0.2 cos(4 t).  Bodies 2 and 3: a rigid pair pushed by f = (3, 0) N
    at body 2's centre, m = 2 + 3 kg, on the line of the pair's mass centre: a = (0.6, 0).
    Body 4: on a sliding joint along x, pushed by flocal = (2, 0) N, m = 4 kg: a = 0.5."""
    folder = write_model(
        tmp_path_factory.mktemp("elements") / "elements",
        inBodies=[dict(m=1.0, J=0.5, p=0.3), dict(m=2.0, J=1.0, r=[2.0, 0.0]), dict(m=3.0, J=1.0, r=[2.5, 0.0]),
                  dict(m=4.0, J=1.0, r=[0.0, -2.0])],
        inPoints=[dict(Bindex=0, sPlocal=[0, 0]), dict(Bindex=1, sPlocal=[0, 0]), dict(Bindex=4, sPlocal=[0, 0]),
                  dict(Bindex=0, sPlocal=[0, -2])],
        inUvectors=[dict(Bindex=0, ulocal=[1, 0]), dict(Bindex=4, ulocal=[1, 0])],
        inJoints=[dict(type="rev", iPindex=2, jPindex=1), dict(type="rigid", iBindex=3, jBindex=2),
                  dict(type="tran", iPindex=3, jPindex=4, iUindex=2, jUindex=1)],
        inForces=[dict(type="rot-sda", iBindex=1, jBindex=0, k=8.0), dict(type="T", iBindex=1, T=0.8),
                  dict(type="f", iBindex=2, f=[3.0, 0.0]), dict(type="flocal", iBindex=4, flocal=[2.0, 0.0])])
    return dapbc.simulate(folder, final_time=1.0, report_step=0.1, **TIGHT)


def test_rotational_spring_and_torque(elements):
    t = elements["time"].values
    assert np.allclose(elements["p"].values[:, 0], 0.1 + 0.2 * np.cos(4 * t), rtol=0, atol=1e-8)
    assert np.allclose(elements["pdd"].values[:, 0], -0.8 * 4 * np.cos(4 * t), rtol=0, atol=1e-6)


def test_rigid_pair_under_a_constant_force(elements):
    t = elements["time"].values
    assert np.allclose(elements["r"].values[:, 1, 0], 2.0 + 0.3 * t ** 2, rtol=0, atol=1e-9)
    assert np.allclose(elements["r"].values[:, 2, 0] - elements["r"].values[:, 1, 0], 0.5, rtol=0, atol=1e-10)
    assert np.allclose(elements["p"].values[:, 1:3], 0.0, rtol=0, atol=1e-10)
    rigid_x = list(elements["constraint_name"].values).index("joint 2 rigid x")
    # the rigid joint pushes body 3 (m = 3 kg) at 0.6 m/s^2: Lam = 1.8 N (M q'' - D^T Lam = h)
    assert np.allclose(elements["Lam"].values[:, rigid_x], 1.8, rtol=0, atol=1e-8)


def test_body_fixed_force_on_a_slider(elements):
    t = elements["time"].values
    assert np.allclose(elements["r"].values[:, 3, 0], 0.25 * t ** 2, rtol=0, atol=1e-9)
    assert np.allclose(elements["rdd"].values[:, 3, 0], 0.5, rtol=0, atol=1e-9)


def test_rot_sda_potential_energy(elements):
    assert np.allclose(elements["eng"].values[:, 1], 4.0 * elements["p"].values[:, 0] ** 2, rtol=0, atol=1e-12)


@pytest.fixture(scope="module")
def driven(tmp_path_factory):
    """A 2 kg slider on a sliding joint along x whose distance from the origin follows a
    type-b function from 1 m to 2 m over 1 s (a rel-tran driver)."""
    return write_model(
        tmp_path_factory.mktemp("driven") / "driven",
        inBodies=[dict(m=2.0, J=1.0, r=[1.0, 0.0])],
        inPoints=[dict(Bindex=0, sPlocal=[0, 0]), dict(Bindex=1, sPlocal=[0, 0])],
        inUvectors=[dict(Bindex=0, ulocal=[1, 0]), dict(Bindex=1, ulocal=[1, 0])],
        inJoints=[dict(type="tran", iPindex=2, jPindex=1, iUindex=2, jUindex=1),
                  dict(type="rel-tran", iPindex=2, jPindex=1, iFunct=1)],
        inFuncts=[dict(type="b", t_start=0.0, f_start=1.0, t_end=1.0, f_end=2.0)],
        inForces=[dict(type="weight")])


def quintic(t):
    """Type b from 1 to 2 over 1 s: 1 + 10 t^3 - 15 t^4 + 6 t^5 and its derivatives."""
    s = np.clip(t, 0.0, 1.0)
    inside = t < 1.0
    return (1 + 10 * s ** 3 - 15 * s ** 4 + 6 * s ** 5, inside * (30 * s ** 2 - 60 * s ** 3 + 30 * s ** 4),
            inside * (60 * s - 180 * s ** 2 + 120 * s ** 3))


def test_kinematic_analysis_of_a_driven_slider(driven):
    ds = dapbc.simulate(driven, analysis="kinematic", final_time=1.5, report_step=0.1)
    x, v, a = quintic(ds["time"].values)
    assert np.allclose(ds["r"].values[:, 0, 0], x, rtol=0, atol=1e-12)
    assert np.allclose(ds["rd"].values[:, 0, 0], v, rtol=0, atol=1e-10)
    assert np.allclose(ds["rdd"].values[:, 0, 0], a, rtol=0, atol=1e-9)
    assert np.isnan(ds["Lam"].values).all()


def test_inverse_dynamics_gives_the_driver_force(driven):
    """The rel-tran row (d.d - f^2)/2 has D = (x, 0, 0), so M q'' - D^T Lam = h gives its
    multiplier (the driver force per metre of d) m x''/x; the sliding joint's normal row has
    D = (0, 1, -x) and carries the weight: Lam = m g."""
    ds = dapbc.simulate(driven, analysis="inverse", final_time=1.5, report_step=0.1)
    x, _, a = quintic(ds["time"].values)
    assert np.allclose(ds["Lam"].values[:, 2], 2.0 * a / x, rtol=0, atol=1e-9)
    assert np.allclose(ds["Lam"].values[:, 0], 2.0 * 9.81, rtol=0, atol=1e-9)


def test_driver_function_types_meet_their_end_conditions():
    """Manual Table B.6 / book Eqs. 8.1-8.3: type a's value; type b reaches f_end with zero
    first and second derivatives; type c reaches dfdt_end with zero second derivative at t_end
    and keeps that slope."""
    a, b, c = (Funct(type="a", coeff=np.array([1.0, 2.0, 3.0])),
               Funct(type="b", t_start=0.5, f_start=0.3, t_end=2.0, f_end=1.5),
               Funct(type="c", t_start=0.5, f_start=0.2, t_end=2.0, dfdt_end=1.5))
    table = funct_table([a, b, c])
    assert np.allclose(funct_value(table[0], 2.0), (1 + 4 + 12, 2 + 12, 6))
    assert np.allclose(funct_value(table[1], 2.0), (1.5, 0.0, 0.0), atol=1e-12)
    assert np.allclose(funct_value(table[1], 0.5), (0.3, 0.0, 0.0), atol=1e-12)
    f_end, rate, second = funct_value(table[2], 2.0)
    assert np.isclose(rate, 1.5) and abs(second) < 1e-12
    assert np.allclose(funct_value(table[2], 3.0), (f_end + 1.5, 1.5, 0.0))
    h = 1e-6  # third derivative zero at t_end and at t_start (central differences of f'')
    for t in (2.0 - h, 0.5 + h):
        third = (funct_value(table[2], t + h)[2] - funct_value(table[2], t - h)[2]) / (2 * h)
        assert abs(third) < 1e-3
    h = 1e-4
    # derivatives are those of the values (central differences inside the span)
    for row in table[1:]:
        for t in (0.9, 1.4):
            f0, f1 = funct_value(row, t - h), funct_value(row, t + h)
            value = funct_value(row, t)
            assert np.isclose((f1[0] - f0[0]) / (2 * h), value[1], atol=1e-6)
            assert np.isclose((f1[1] - f0[1]) / (2 * h), value[2], atol=1e-6)
