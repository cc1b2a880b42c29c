"""The force elements' expressions (mbds.model.dapbc.forces) evaluated at a chosen state,
against the force laws of the manual's Table B.4 (the book's Sec. 7.5), without compiling."""

import sympy

from mbds.io.dapbc import read_dapbc_folder
from mbds.model.dapbc.system import equations
from tests.dapbc_core.infiles import write_model


def generalised_forces(folder, q, qd):
    expressions, symbols, _, _ = equations(read_dapbc_folder(folder))
    values = {s: v for s, v in zip(symbols.q, q)} | {s: v for s, v in zip(symbols.qd, qd)}
    values |= {sympy.Symbol(f"par[{k}]"): v for k, v in enumerate(symbols.values)}
    return [float(sympy.sympify(h).subs(values)) for h in expressions.forces_before]


def test_point_to_point_spring_damper_actuator(tmp_path):
    """Body 1's centre at (1, 0) moving at (0.5, 0), tied to the origin: L = 1, L' = 0.5, so the
    tension k (L - L0) + dc L' + f_a = 100 x 0.2 + 4 x 0.5 + 3 = 25 N pulls it towards -x;
    rot-sda k 10, theta0 0.1, dc 2, T_a 1 at phi = 0.3, phi' = 0.5 gives 10 x 0.2 + 2 x 0.5 + 1
    = 4 N m against phi; flocal (1, 0) at phi = 0.3 is (cos 0.3, sin 0.3) in x-y."""
    folder = write_model(
        tmp_path / "m", inBodies=[dict(m=1.0, J=1.0, r=[1.0, 0.0], p=0.3, r_d=[0.5, 0.0], p_d=0.5)],
        inPoints=[dict(Bindex=0, sPlocal=[0, 0]), dict(Bindex=1, sPlocal=[0, 0])],
        inForces=[dict(type="ptp", iPindex=2, jPindex=1, k=100.0, L0=0.8, dc=4.0, f_a=3.0),
                  dict(type="rot-sda", iBindex=1, jBindex=0, k=10.0, theta0=0.1, dc=2.0, T_a=1.0),
                  dict(type="flocal", iBindex=1, flocal=[1.0, 0.0])])
    h = generalised_forces(folder, [1.0, 0.0, 0.3], [0.5, 0.0, 0.5])
    assert abs(h[0] - (-25.0 + 0.955336489125606)) < 1e-12
    assert abs(h[1] - 0.29552020666133955) < 1e-12
    assert abs(h[2] - (-4.0)) < 1e-12


def test_weight_with_its_gravity_and_direction(tmp_path):
    """weight with gravity 3.7 along wgt = (1, 0): m g wgt on each body."""
    folder = write_model(tmp_path / "w", inBodies=[dict(m=2.0), dict(m=5.0)],
                         inForces=[dict(type="weight", gravity=3.7, wgt=[1.0, 0.0])])
    assert generalised_forces(folder, [0.0] * 6, [0.0] * 6) == [7.4, 0.0, 0.0, 18.5, 0.0, 0.0]
