"""user_force.m compiled to numba: the manual's listings evaluated against the formulas by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbds.io.dapbc import read_dapbc_folder
from mbds.io.dapbc.records import Body, DapbcModel, Force, Point
from mbds.io.dapbc.user_force import (FORCE_FIELD_COUNT, FORCE_FIELDS, SIGNATURE, compile_user_force,
                                      force_field_table, user_force_code)
from tests.dapbc_io.folders import write_folder
from tests.dapbc_io.user_force_eval import evaluate, point_kinematics

CB_USER_FORCE = """function user_force
    include_global

% Anderson et al. friction model
mu_d = 0.15; mu_s = 0.2; k_v = 0.0;
v_s = 0.001; p = 2; k_t = 10000;
fy = 9.81; % normal force
v_conv = 0.1;
v = v_conv - Bodies(1).r_d(1);
ff = Friction_A(mu_s, mu_d, v_s, p, k_t, v);
fx = fy*(ff + k_v*v);
fs = [fx; 0];
Bodies(1).f = Bodies(1).f + fs;
"""

ROD_USER_FORCE = """function user_force
    include_global
    global pen1_d0 pen2_d0

% Parameters for the contact model
    k = 10^11; e = 0.95;

% Contact(Contact index, Point index, Body index, k, e, Model index)
% Point [1] on Body (1)
    Contact(1, 1, 1, k, e, MODEL)
% Point [2] on Body (1)
    Contact(2, 2, 1, k, e, MODEL)
"""


def rod_model() -> DapbcModel:
    """The manual's Rod (B.4.5): one body, points at (0, -1) and (0, 1) in its frame."""
    return DapbcModel(folder=".", bodies=[Body(m=1.0, J=0.01)],
                      points=[Point(Bindex=1, sPlocal=np.array([0.0, -1.0])),
                              Point(Bindex=1, sPlocal=np.array([0.0, 1.0]))],
                      forces=[Force(type="weight"), Force(type="user")])


@pytest.fixture(scope="module")
def cb_force():
    model = DapbcModel(folder=".", bodies=[Body()], points=[Point(), Point(Bindex=1)],
                       forces=[Force(type="ptp", iPindex=2, jPindex=1, k=10, L0=0.8), Force(type="weight"),
                               Force(type="user")])
    return model, compile_user_force(CB_USER_FORCE, model).load()


@pytest.mark.parametrize("x_d", [0.0, 0.0995, 0.1, 0.1004, 0.3])
def test_conveyor_belt_friction_is_andersons_law(cb_force, x_d):
    """Manual B.4.4 (CB): f_x = f_y (mu_d + (mu_s - mu_d) exp(-(|v|/v_s)^p)) tanh(k_t v) with
    v = v_conv - x', the friction law of Anderson, Soederberg and Bjoerklund (Tribol. Int. 40,
    2007, 580-587) as DAP_BC's Friction_A gives it (viscous term k_v v added by the user)."""
    model, force = cb_force
    f, n, _ = evaluate(force, model, r=[1.0, 0.2], p=[0.0], r_d=[x_d, 0.0], p_d=[0.0], f=[[3.0, -9.81]])
    v = 0.1 - x_d
    expected = 9.81 * (0.15 + 0.05 * math.exp(-((abs(v) / 0.001) ** 2))) * math.tanh(10000 * v)
    assert f[0, 0] == pytest.approx(3.0 + expected, rel=1e-14, abs=1e-15)
    assert f[0, 1] == -9.81 and n[0] == 0.0  # added into, nothing else touched


@pytest.fixture(scope="module", params=[1, 2], ids=["Eq. 11.42", "Eq. 11.43"])
def rod_force(request):
    code = compile_user_force(ROD_USER_FORCE.replace("MODEL", str(request.param)), rod_model())
    return request.param, code, code.load()


def penetration(model: DapbcModel, point: int, **state) -> tuple[float, float, float]:
    """Depth -y, rate -y' and moment arm x of A s' of a point (0-based), by the test's kinematics."""
    A, sP, rP, rP_d = point_kinematics(model, *(np.array(state[k], float).reshape(-1, 2) if k in ("r", "r_d")
                                                 else np.array(state[k], float) for k in ("r", "p", "r_d", "p_d")))
    return -rP[point, 1], -rP_d[point, 1], sP[point, 0]


def contact_law(law: int, depth: float, rate: float, rate0: float, k=1e11, e=0.95) -> float:
    """Eq. 11.42 (Lankarani and Nikravesh, J. Mech. Des. 112, 1990) and Eq. 11.43 (Flores et al.,
    Multibody Syst. Dyn. 25, 2011), written out by hand."""
    if law == 1:
        return k * depth ** 1.5 * (1 + 3 * (1 - e ** 2) / 4 * rate / rate0)
    return k * depth ** 1.5 * (1 + 8 * (1 - e) / (5 * e) * rate / rate0)


def test_rod_contact_keeps_the_first_contact_velocity(rod_force):
    """Manual B.4.5 (Rod): the penetration velocity at first contact is kept per contact and
    scales the damping term until the point leaves the ground."""
    law, code, force = rod_force
    model = rod_model()
    assert code.n_state == 4  # two contacts, two slots each
    state = np.zeros(code.n_state)
    phi = math.pi / 4
    # point 2 (upper end, contact 2) is 2 sin(phi) m above point 1 and never touches
    y = math.cos(phi) - 1e-5  # point 1 about 1e-5 m below the ground
    first = dict(r=[0.0, y], p=[phi], r_d=[0.0, -6.0], p_d=[0.0])
    f, n, state = evaluate(force, model, state=state, **first)
    depth0, rate0, arm = penetration(model, 0, **first)
    expected = contact_law(law, depth0, rate0, rate0)
    assert f[0, 1] == pytest.approx(expected, rel=1e-13)
    assert n[0] == pytest.approx(arm * expected, rel=1e-13)  # s_rot(sP)' [0; fy] = sP_x fy
    assert arm == pytest.approx(math.sin(phi))
    assert state[0] == 1.0 and state[1] == pytest.approx(6.0) and state[2] == 0.0
    # later in the same contact, rebounding: the damping term uses the kept rate0
    later = dict(r=[0.0, math.cos(phi) - 2e-5], p=[phi], r_d=[0.0, 3.0], p_d=[0.0])
    f, n, state = evaluate(force, model, state=state, **later)
    depth, rate, _ = penetration(model, 0, **later)
    assert rate == -3.0
    assert f[0, 1] == pytest.approx(contact_law(law, depth, rate, rate0), rel=1e-13)
    assert state[1] == rate0
    # the point leaves the ground: the flag clears, the force is zero
    f, n, state = evaluate(force, model, r=[0.0, 2.0], p=[phi], r_d=[0.0, 1.0], p_d=[0.0], state=state)
    assert f[0, 1] == 0.0 and state[0] == 0.0
    # a second impact at another speed starts a new rate0
    second = dict(first, r_d=[0.0, -2.0])
    f, n, state = evaluate(force, model, state=state, **second)
    assert state[1] == 2.0
    assert f[0, 1] == pytest.approx(contact_law(law, depth0, 2.0, 2.0), rel=1e-13)


def test_contacts_keep_separate_states(rod_force):
    """Both ends below ground: each contact index has its own rate0 (rotating rod, different speeds)."""
    law, code, force = rod_force
    model = rod_model()
    state = np.zeros(code.n_state)
    # horizontal (phi = pi/2), 1e-5 m below the ground and turning: the ends sink at different rates
    both = dict(r=[0.0, -1e-5], p=[math.pi / 2], r_d=[0.0, -1.0], p_d=[0.5])
    f, n, state = evaluate(force, model, state=state, **both)
    (d1, v1, arm1), (d2, v2, arm2) = penetration(model, 0, **both), penetration(model, 1, **both)
    assert (v1, v2) == pytest.approx((0.5, 1.5)) and (arm1, arm2) == pytest.approx((1.0, -1.0))
    assert state[1] == v1 and state[3] == v2
    f1, f2 = contact_law(law, d1, v1, v1), contact_law(law, d2, v2, v2)
    assert f[0, 1] == pytest.approx(f1 + f2, rel=1e-13)
    assert n[0] == pytest.approx(arm1 * f1 + arm2 * f2, rel=1e-12)


def test_friction_b_is_brown_and_mcphee():
    """Friction_B: F = f_n (mu_d tanh(4 v/v_t) + (mu_s - mu_d)(v/v_t)/((v/v_t)^2/4 + 3/4)^2)
    + mu_v v tanh(4 f_n/f_nt), Brown and McPhee, J. Comput. Nonlinear Dynam. 11 (2016) 054502."""
    model = DapbcModel(folder=".", bodies=[Body()], forces=[Force(type="user")])
    source = """Bodies(1).f(1) = Friction_B(0.3, 0.2, 0.01, 0.002, 5, Bodies(1).r_d(1), 12);
Bodies(1).f(2) = Friction_A(0.3, 0.2, 0.002, 2, 5000, Bodies(1).r_d(1), 12);
include_global
"""
    force = compile_user_force(source, model).load()
    for v in (-0.01, 0.0007, 0.002, 0.5):
        f, _, _ = evaluate(force, model, r=[0, 0], p=[0], r_d=[v, 0], p_d=[0])
        x = v / 0.002
        brown = 12 * (0.2 * math.tanh(4 * x) + 0.1 * x / (0.25 * x * x + 0.75) ** 2) + 0.01 * v * math.tanh(4 * 12 / 5)
        anderson = 12 * (0.2 + 0.1 * math.exp(-((abs(v) / 0.002) ** 2))) * math.tanh(5000 * v)
        assert f[0, 0] == pytest.approx(brown, rel=1e-13)
        assert f[0, 1] == pytest.approx(anderson, rel=1e-13)


AA_MP_USER_FORCE = """function user_force
    include_global

    % Unilateral spring-damper representing the radial tire force
    del = Bodies(1).r(2) - Forces(2).L0;
    if del < 0
        fy = Forces(2).k*del + ...
            Forces(2).dc*Bodies(1).r_d(2);
        fsd = [0; -fy];
        Bodies(1).f = Bodies(1).f + fsd;
        Bodies(1).n = Bodies(1).n + ...
                      s_rot(Points(3).sP)'*fsd;
    end
"""


def test_macpherson_tire_force_and_its_moment():
    """Manual B.4.2 (MP_B): the unilateral tire spring-damper on body 1 and its moment
    s_rot(sP)' f about the mass centre, with the model's Forces(2).k, L0, dc."""
    model = DapbcModel(folder=".", bodies=[Body(m=20, J=2.5), Body()],
                       points=[Point(Bindex=1, sPlocal=np.array([0.0, -0.07])),
                               Point(Bindex=1, sPlocal=np.array([-0.17, 0.25])),
                               Point(Bindex=1, sPlocal=np.array([0.11, -0.02]))],
                       forces=[Force(), Force(type="user", k=100000, L0=0.30, dc=1000), Force(type="weight")])
    force = compile_user_force(AA_MP_USER_FORCE, model).load()
    p = 6.0819
    for y, y_d in ((0.29, -0.4), (0.31, -0.4)):
        f, n, _ = evaluate(force, model, r=[[0.584, y], [0, 0]], p=[p, 0], r_d=[[0, y_d], [0, 0]], p_d=[0, 0])
        delta = y - 0.30
        if delta < 0:
            fy = 100000 * delta + 1000 * y_d
            c, s = math.cos(p), math.sin(p)
            sx = c * 0.11 - s * (-0.02)  # A s'C, x component
            assert f[0] == pytest.approx([0.0, -fy], rel=1e-14)
            assert n[0] == pytest.approx(sx * -fy, rel=1e-13)
        else:
            assert np.all(f == 0) and np.all(n == 0)


CART_USER_FORCE = """function user_force
    include_global
% Motor
    omega_max = 4*pi; T_max = 20;
    omega = abs(Bodies(2).p_d);
    T_motor = T_max*(1 - omega/omega_max);
    if T_motor > T_max
        T_motor = T_max;
    end
    Bodies(2).n = Bodies(2).n - T_motor;
    Bodies(1).n = Bodies(1).n + T_motor;
% Aerodynamic resistive force
    damp_aero = 10;
    x_d = Bodies(1).r_d(1);
    f_aero = damp_aero*x_d^2;
    Bodies(1).f(1) = Bodies(1).f(1) - f_aero;
"""


def test_cart_motor_torque_and_air_drag():
    """Manual B.4.3 (Cart_C, Cart_D): T = T_max (1 - |omega|/omega_max) on the rear wheel
    (reaction on the body), drag 10 x'^2 against x."""
    model = DapbcModel(folder=".", bodies=[Body(), Body(), Body()])
    force = compile_user_force(CART_USER_FORCE, model).load()
    f, n, _ = evaluate(force, model, r=np.zeros((3, 2)), p=np.zeros(3), r_d=[[1.5, 0], [0, 0], [0, 0]],
                       p_d=[0, -2 * math.pi, 0], f=np.ones((3, 2)))
    torque = 20 * (1 - 2 * math.pi / (4 * math.pi))
    assert n == pytest.approx([torque, -torque, 0.0], rel=1e-14)
    assert f[0] == pytest.approx([1 - 10 * 1.5 ** 2, 1.0]) and np.all(f[1:] == 1.0)


def test_rotation_matrix_vectors_time_and_branches():
    """Reads of A, rP, rP_d, a Force 2-vector field and t; products, transposes, elseif/else."""
    model = DapbcModel(folder=".", bodies=[Body()],
                       points=[Point(Bindex=1, sPlocal=np.array([0.5, 0.0]))],
                       forces=[Force(type="user", wgt=np.array([0.6, -0.8]), k=3.0)])
    source = """function user_force
include_global
u = Bodies(1).A*[1; 0];            % body x axis in the world frame
w = Forces(1).wgt';                % a row
M = [Bodies(1).A(1,1) 0; 0 1] * [u, u];
if t > 2
    Bodies(1).f = [u(1); u(2)] * Forces(1).k;
elseif t > 1 && ~(t > 1.5)
    Bodies(1).f = w' + Points(1).rP_d;
    Bodies(1).n = w * Points(1).rP + max(-3, min(2, sign(-4))) + sqrt(4)*exp(0)*cos(0)*sin(pi/2);
else
    Bodies(1).n = M(2,1) + [1 2]*[3; 4];
end
"""
    force = compile_user_force(source, model).load()
    q = 0.3
    c, s = math.cos(q), math.sin(q)
    state = dict(r=[1.0, 2.0], p=[q], r_d=[0.1, 0.2], p_d=[2.0])
    f, n, _ = evaluate(force, model, t=3.0, **state)
    assert f[0] == pytest.approx([3 * c, 3 * s], rel=1e-14)
    f, n, _ = evaluate(force, model, t=1.2, **state)
    rP = np.array([1.0 + 0.5 * c, 2.0 + 0.5 * s])
    rP_d = np.array([0.1 - 2.0 * 0.5 * s, 0.2 + 2.0 * 0.5 * c])
    assert f[0] == pytest.approx(np.array([0.6, -0.8]) + rP_d, rel=1e-14)
    assert n[0] == pytest.approx(0.6 * rP[0] - 0.8 * rP[1] - 1 + 2, rel=1e-14)
    f, n, _ = evaluate(force, model, t=0.5, **state)
    assert n[0] == pytest.approx(s + 11, rel=1e-14)


def test_force_fields_table_columns():
    forces = [Force(k=1, L0=2, theta0=3, dc=4, f_a=5, T_a=6, gravity=7, wgt=np.array([8.0, 9.0]),
                    flocal=np.array([10.0, 11.0]), f=np.array([12.0, 13.0]), T=14)]
    table = force_field_table(forces)
    assert table.shape == (1, FORCE_FIELD_COUNT)
    assert list(table[0]) == [float(x) for x in range(1, 15)]
    assert sorted(c for cols in FORCE_FIELDS.values() for c in cols) == list(range(FORCE_FIELD_COUNT))


PYTHON_FORCE = """import numpy as np

N_STATE = 1


def user_force(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):
    state[0] += 1.0
    f[0, 0] += -fields[0, 0] * r[0, 0]
"""


def test_python_user_force_from_the_folder_wins(tmp_path):
    files = {"inBodies.m": "include_global\nB1 = Body_struct;\nB1.r = [0.5; 0];\nBodies = [B1];\n",
             "inForces.m": "include_global\nF1 = Force_struct;\nF1.type = 'user';\nF1.k = 4;\nForces = [F1];\n",
             "user_force.m": "include_global\nBodies(1).f = [1; 1];\n", "user_force.py": PYTHON_FORCE}
    model = read_dapbc_folder(write_folder(tmp_path, files, base={}))
    code = user_force_code(model)
    assert code.n_state == 1 and code.file.name == "user_force.py"
    state = np.zeros(1)
    f, _, state = evaluate(code.load(), model, r=[0.5, 0], p=[0], r_d=[0, 0], p_d=[0], state=state)
    assert f[0, 0] == -2.0 and state[0] == 1.0
    (model.folder / "user_force.py").unlink()
    model = read_dapbc_folder(model.folder)
    f, _, _ = evaluate(user_force_code(model).load(), model, r=[0.5, 0], p=[0], r_d=[0, 0], p_d=[0])
    assert list(f[0]) == [1.0, 1.0]


def test_signature_is_the_documented_one():
    assert SIGNATURE == ("t", "r", "p", "r_d", "p_d", "A", "rP", "rP_d", "sP", "fields", "state", "f", "n")
