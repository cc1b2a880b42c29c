"""Plain numpy references for the 11 DAP_BC example models of campaigns/dap_bc/.

Each model is written here again, by hand, in body coordinates q = (x1, y1, phi1, x2, ...)
with the constraint equations Phi(q, t) = 0 reduced to the acceleration level without any
Baumgarte stabilisation:

    M q'' = h(q, q', t) + D^T lam,    D q'' = gamma,

D = dPhi/dq, gamma the velocity-quadratic right-hand side.  The model numbers are those of the
in-files (sources in campaigns/dap_bc/README.md); nothing here reads the in-files or uses mbds,
so the tests in tests/dapbc_examples/ compare two independent implementations.

``reference_rhs(name) -> (fun, y0, t_span)`` gives scipy's ``solve_ivp`` what it needs: the
right-hand side of y = (q, q'), consistent initial conditions (corrected as DAP_BC does, by
minimum-norm Newton steps on the positions and a minimum-norm projection of the velocities)
and the book's simulation interval.  Units: SI (m, kg, s, N, rad).
"""

from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np
from scipy.integrate import solve_ivp

GRAVITY = 9.81  # m/s^2, DAP_BC's default 'gravity'
#: the simulated interval per model (s): SP's 4 s of the manual (Sec. B.1.1), the benchmark
#: intervals for MP_A, Rod and CB (docs/performance.md), and for the others intervals chosen
#: here that cover the main event of each model (campaigns/dap_bc/README.md)
T_FINAL = {"SP": 4.0, "AA": 2.0, "MP_A": 1.0, "MP_B": 1.0, "MP_C": 1.0, "Cart_A": 2.0,
           "Cart_B": 4.0, "Cart_C": 4.0, "Cart_D": 4.0, "CB": 10.0, "Rod": 0.2}


def _rot90(v: np.ndarray) -> np.ndarray:
    """v rotated by +90 degrees (the book's breve operator); works on (2,) and (2, n)."""
    return np.array([-v[1], v[0]])


def _rot(phi: float) -> np.ndarray:
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s], [s, c]])


class Vec(NamedTuple):
    """A planar vector function of the state: value, Jacobian (2, n) with respect to q, rate
    (d/dt) and ``quad``, the velocity-quadratic part of its second time derivative."""

    val: np.ndarray
    jac: np.ndarray
    rate: np.ndarray
    quad: np.ndarray

    def __sub__(self, other: "Vec") -> "Vec":
        return Vec(*(a - b for a, b in zip(self, other)))

    def perp(self) -> "Vec":
        """The vector turned by +90 degrees (a linear map, so it applies to every part)."""
        return Vec(*(_rot90(a) for a in self))


class Row(NamedTuple):
    """One scalar constraint: Phi, its Jacobian row D, nu (D q' = nu), gamma (D q'' = gamma)."""

    phi: float
    jac: np.ndarray
    nu: float
    gamma: float


def dot(a: Vec, b: Vec, offset: float = 0.0) -> Row:
    """The constraint a . b - offset = 0 (neither factor depends explicitly on time)."""
    quad = a.val @ b.quad + b.val @ a.quad + 2.0 * a.rate @ b.rate
    return Row(a.val @ b.val - offset, a.val @ b.jac + b.val @ a.jac, 0.0, -quad)


class State:
    """Positions, orientations and rates of the moving bodies at one instant."""

    def __init__(self, q: np.ndarray, qd: np.ndarray):
        self.q, self.qd, self.n = q, qd, q.size

    def body(self, b: int) -> tuple[np.ndarray, float, np.ndarray, float]:
        """(r, phi, r', phi') of body b >= 1."""
        k = 3 * (b - 1)
        return self.q[k:k + 2], self.q[k + 2], self.qd[k:k + 2], self.qd[k + 2]

    def constant(self, value) -> Vec:
        z = np.zeros(2)
        return Vec(np.asarray(value, float), np.zeros((2, self.n)), z, z)

    def point(self, b: int, local) -> Vec:
        """Point with body-fixed coordinates ``local`` on body b (b = 0: the ground)."""
        return self._body_fixed(b, local, True)

    def unit(self, b: int, local) -> Vec:
        """Unit vector with body-fixed components ``local`` on body b (b = 0: the ground)."""
        return self._body_fixed(b, local, False)

    def _body_fixed(self, b: int, local, translates: bool) -> Vec:
        """A body-fixed vector A_b local, plus r_b when it is a point (``translates``)."""
        if b == 0:
            return self.constant(local)
        r, phi, _, phid = self.body(b)
        s = _rot(phi) @ np.asarray(local, float)
        jac = np.zeros((2, self.n))
        jac[:, 3 * b - 1] = _rot90(s)
        if translates:
            jac[:, 3 * b - 3:3 * b - 1] = np.eye(2)
        return Vec(r + s if translates else s, jac, jac @ self.qd, -s * phid ** 2)

    def angle(self, b: int) -> Row:
        """phi_b as a constraint row (0 for the ground)."""
        jac = np.zeros(self.n)
        if b == 0:
            return Row(0.0, jac, 0.0, 0.0)
        jac[3 * b - 1] = 1.0
        return Row(self.q[3 * b - 1], jac, 0.0, 0.0)


# ---------------------------------------------------------------- joints (constraint rows)
def rev(s: State, pi, pj) -> list[Row]:
    """Pin joint: the points pi = (body, local) and pj coincide (2 rows)."""
    d = s.point(*pi) - s.point(*pj)
    return [dot(s.constant([1.0, 0.0]), d), dot(s.constant([0.0, 1.0]), d)]


def tran(s: State, pi, pj, ui, uj) -> list[Row]:
    """Sliding joint: d = Pi - Pj and the unit vector uj stay along the unit vector ui."""
    n_i = s.unit(*ui).perp()
    return [dot(n_i, s.point(*pi) - s.point(*pj)), dot(n_i, s.unit(*uj))]


def rev_tran(s: State, pi, pj, ui, length=0.0) -> list[Row]:
    """Revolute-translational link: Pj stays at distance ``length`` from the line (Pi, ui)."""
    return [dot(s.unit(*ui).perp(), s.point(*pi) - s.point(*pj), length)]


def rev_rev(s: State, pi, pj, length) -> list[Row]:
    """Massless link of ``length`` between Pi and Pj: (d.d - L^2)/2 = 0."""
    d = s.point(*pi) - s.point(*pj)
    row = dot(d, d, length ** 2)
    return [Row(row.phi / 2, row.jac / 2, 0.0, row.gamma / 2)]


def disc(s: State, b, radius, x0=0.0, p0=0.0) -> list[Row]:
    """Disc of ``radius`` rolling without slip on the ground y = 0 (book Eq. 7.38)."""
    centre = s.point(b, [0.0, 0.0])
    height = dot(s.constant([0.0, 1.0]), centre, radius)
    ang = s.angle(b)
    roll = dot(s.constant([1.0, 0.0]), centre, x0)
    return [height, Row(roll.phi + radius * (ang.phi - p0), roll.jac + radius * ang.jac, 0.0, 0.0)]


def rel_rot(s: State, bi, bj, funct: Callable, t: float) -> list[Row]:
    """Rotational driver: phi_i - phi_j = f(t)."""
    f, fd, fdd = funct(t)
    a, b = s.angle(bi), s.angle(bj)
    return [Row(a.phi - b.phi - f, a.jac - b.jac, fd, fdd)]


# ---------------------------------------------------------------- driver functions
def funct_a(c1, c2, c3):
    """Type a: f = c1 + c2 t + c3 t^2; returns f(t) -> (f, f', f'')."""
    return lambda t: (c1 + c2 * t + c3 * t * t, c2 + 2 * c3 * t, 2 * c3)


def funct_c(t_start, f_start, t_end, dfdt_end):
    """Type c: f = c1 + c2 tau^4 + c3 tau^5 + c4 tau^6 (tau = t - t_start) with f' = dfdt_end
    and f'' = f''' = 0 at t_end; f' constant after t_end and f = f_start before t_start."""
    T = t_end - t_start
    lhs = np.array([[4 * T ** 3, 5 * T ** 4, 6 * T ** 5],
                    [12 * T ** 2, 20 * T ** 3, 30 * T ** 4],
                    [24 * T, 60 * T ** 2, 120 * T ** 3]])
    c2, c3, c4 = np.linalg.solve(lhs, [dfdt_end, 0.0, 0.0])

    def poly(tau):
        return (f_start + c2 * tau ** 4 + c3 * tau ** 5 + c4 * tau ** 6,
                4 * c2 * tau ** 3 + 5 * c3 * tau ** 4 + 6 * c4 * tau ** 5,
                12 * c2 * tau ** 2 + 20 * c3 * tau ** 3 + 30 * c4 * tau ** 4)

    f_end = poly(T)[0]

    def f(t):
        tau = t - t_start
        if tau <= 0:
            return f_start, 0.0, 0.0
        if tau >= T:
            return f_end + dfdt_end * (tau - T), dfdt_end, 0.0
        return poly(tau)

    return f


# ---------------------------------------------------------------- forces
def apply(s: State, h: np.ndarray, b: int, force, at_local=(0.0, 0.0)) -> None:
    """Add ``force`` (N, x-y frame) acting at the body-fixed point ``at_local`` of body b."""
    if b == 0:
        return
    k = 3 * (b - 1)
    arm = _rot(s.q[k + 2]) @ np.asarray(at_local, float)
    h[k:k + 2] += force
    h[k + 2] += arm[0] * force[1] - arm[1] * force[0]


def ptp(s: State, h: np.ndarray, pi, pj, k, L0, dc=0.0, f_a=0.0) -> float:
    """Point-to-point spring-damper-actuator; tension f = k (L - L0) + dc L' + f_a pulls Pi
    toward Pj.  Returns the spring's potential energy k (L - L0)^2 / 2 (J)."""
    d = s.point(*pi) - s.point(*pj)
    length = np.linalg.norm(d.val)
    u = d.val / length
    f = k * (length - L0) + dc * (u @ d.rate) + f_a
    apply(s, h, pi[0], -f * u, pi[1])
    apply(s, h, pj[0], f * u, pj[1])
    return 0.5 * k * (length - L0) ** 2


class Model(NamedTuple):
    """A reference model: masses (kg) and moments of inertia (kg m^2) per body, initial
    coordinates and velocities, constraint rows of (state, t), and the applied forces: a
    function of (state, t, h, memory) that adds the standard elements' forces to h and returns
    their potential energy, and the user force."""

    mass: np.ndarray
    inertia: np.ndarray
    q0: np.ndarray
    qd0: np.ndarray
    constraints: Callable
    forces: Callable
    user: Callable | None = None  # what the model's user_force.m adds, of (state, t, h, memory)

    @property
    def diag_mass(self) -> np.ndarray:
        return np.ravel(np.column_stack([self.mass, self.mass, self.inertia]))


def weight(s: State, h: np.ndarray, mass: np.ndarray) -> float:
    """Gravity along -y on every body; returns its potential energy (J)."""
    h[1::3] -= mass * GRAVITY
    return float(mass @ s.q[1::3] * GRAVITY)


# ---------------------------------------------------------------- the models
def _sp() -> Model:
    mass, inertia = np.array([5.0, 2.0]), np.array([4.0, 0.2])

    def cons(s, t):
        return (tran(s, (1, [0, 0]), (0, [0, 0.2]), (1, [1, 0]), (0, [1, 0]))
                + rev(s, (1, [0, 0]), (2, [0, 0.5])))

    def forces(s, t, h, memory):
        return ptp(s, h, (1, [0, 0]), (0, [0, 0.2]), 20.0, 0.6) + weight(s, h, mass)

    return Model(mass, inertia, np.array([1.0, 0.2, 0.0, 1.25, -0.233, np.pi / 6]), np.zeros(6),
                 cons, forces)


def _aa() -> Model:
    mass, inertia = np.array([2.0, 30.0, 1.0]), np.array([0.5, 2.5, 0.5])

    def cons(s, t):
        return (rev(s, (1, [-0.24, 0]), (0, [0.20, 0.26])) + rev(s, (1, [0.18, 0]), (2, [-0.07, -0.10]))
                + rev(s, (2, [-0.10, 0.12]), (3, [0.13, 0])) + rev(s, (3, [-0.13, 0]), (0, [0.32, 0.40])))

    def forces(s, t, h, memory):
        return ptp(s, h, (1, [0, 0]), (0, [0.38, 0.43]), 90000.0, 0.23, 1100.0) + weight(s, h, mass)

    def user(s, t, h, memory):
        r, _, rd, _ = s.body(2)
        tire(h, 2, r[1], rd[1], 50000.0, 0.35, 1000.0)

    q0 = np.array([0.4398, 0.2512, -0.0367, 0.6817, 0.3498, 0.0783, 0.4463, 0.4308, 6.5222])
    return Model(mass, inertia, q0, np.zeros(9), cons, forces, user)


def tire(h, b, y, yd, k, L0, dc, s=None, contact_local=None) -> None:
    """The examples' unilateral tire: when the body height y is below L0 a vertical force
    -(k (y - L0) + dc y') acts on body b, at its mass centre or at ``contact_local``."""
    if y - L0 < 0:
        force = np.array([0.0, -(k * (y - L0) + dc * yd)])
        if s is None:
            h[3 * b - 3:3 * b - 1] += force
        else:
            apply(s, h, b, force, contact_local)


_MP_WHEEL = dict(A=[0.0, -0.07], B=[-0.17, 0.25], C=[0.11, -0.02])
_MP_GROUND = dict(O=[0.41, 0.83], Q=[0.12, 0.29])


def _mp(variant: str) -> Model:
    nb = {"A": 3, "B": 2, "C": 1}[variant]
    mass, inertia = np.array([20.0, 2.0, 0.5])[:nb], np.array([2.5, 0.5, 0.2])[:nb]
    w, g = _MP_WHEEL, _MP_GROUND

    def cons(s, t):
        if variant == "A":
            return (rev(s, (1, w["A"]), (2, [0.225, 0])) + rev(s, (0, g["Q"]), (2, [-0.225, 0]))
                    + rev(s, (0, g["O"]), (3, [-0.15, 0]))
                    + tran(s, (1, w["B"]), (3, [-0.15, 0]), (1, [0.47, -0.88]), (3, [1, 0])))
        if variant == "B":
            return (rev(s, (1, w["A"]), (2, [0.225, 0])) + rev_tran(s, (1, w["B"]), (0, g["O"]), (1, [0.47, -0.88]))
                    + rev(s, (0, g["Q"]), (2, [-0.225, 0])))
        return rev_rev(s, (1, w["A"]), (0, g["Q"]), 0.45) + rev_tran(s, (1, w["B"]), (0, g["O"]), (1, [0.47, -0.88]))

    def forces(s, t, h, memory):
        return ptp(s, h, (1, w["B"]), (0, g["O"]), 20000.0, 0.34, 1100.0) + weight(s, h, mass)

    def user(s, t, h, memory):
        r, _, rd, _ = s.body(1)
        tire(h, 1, r[1], rd[1], 100000.0, 0.30, 1000.0, s, w["C"])

    q0 = np.array([0.5840, 0.3586, 6.0819, 0.3450, 0.2900, 0.0, 0.4528, 0.6862, 5.0019])[:3 * nb]
    return Model(mass, inertia, q0, np.zeros(3 * nb), cons, forces, user)


def _cart(variant: str) -> Model:
    mass, inertia = np.array([20.0, 2.0, 2.0]), np.array([5.0, 0.5, 0.5])
    driver = {"A": funct_a(0.0, -2 * np.pi, 0.0), "B": funct_c(0.0, 0.0, 2.0, -2 * np.pi)}.get(variant)

    def cons(s, t):
        rows = (rev(s, (1, [-0.3, -0.1]), (2, [0, 0])) + rev(s, (1, [0.3, -0.1]), (3, [0, 0]))
                + disc(s, 2, 0.1, 0.2) + disc(s, 3, 0.1, 0.8))
        return rows + (rel_rot(s, 2, 1, driver, t) if driver else [])

    def forces(s, t, h, memory):
        return weight(s, h, mass)

    def user(s, t, h, memory):
        """Cart_C, Cart_D: motor torque T = T_max (1 - |w|/w_max), capped at T_max, on the rear
        wheel (-T) and the cart (+T); Cart_D: aerodynamic drag 10 x'^2 on the cart."""
        torque = min(20.0 * (1.0 - abs(s.qd[5]) / (4 * np.pi)), 20.0)
        h[5] -= torque
        h[2] += torque
        if variant == "D":
            h[0] -= 10.0 * s.qd[0] ** 2

    q0 = np.array([0.5, 0.2, 0.0, 0.2, 0.1, 0.0, 0.8, 0.1, 0.0])
    return Model(mass, inertia, q0, np.zeros(9), cons, forces, None if driver else user)


def friction_anderson(mu_s, mu_d, v_s, p, k_t, v) -> float:
    """Anderson et al. friction coefficient without viscous term (book Sec. 11.4)."""
    return (mu_d + (mu_s - mu_d) * np.exp(-((abs(v) / v_s) ** p))) * np.tanh(k_t * v)


def _cb() -> Model:
    mass, inertia = np.array([1.0]), np.array([1.0])

    def cons(s, t):
        return tran(s, (1, [0, 0]), (0, [0, 0.2]), (1, [1, 0]), (0, [1, 0]))

    def forces(s, t, h, memory):
        return ptp(s, h, (1, [0, 0]), (0, [0, 0.2]), 10.0, 0.8) + weight(s, h, mass)

    def user(s, t, h, memory):
        slip = 0.1 - s.qd[0]  # belt speed 0.1 m/s
        h[0] += 9.81 * friction_anderson(0.2, 0.15, 0.001, 2.0, 10000.0, slip)

    return Model(mass, inertia, np.array([1.0, 0.2, 0.0]), np.zeros(3), cons, forces, user)


def contact_lankarani_nikravesh(depth, rate, rate0, k, e) -> float:
    """Book Eq. 11.42: k d^1.5 (1 + 3 (1 - e^2)/4 d'/d'0) (N); no damping when d'0 = 0."""
    ratio = rate / rate0 if rate0 != 0.0 else 0.0
    return k * depth ** 1.5 * (1.0 + 0.75 * (1.0 - e * e) * ratio)


ROD_ENDS = ([0.0, -1.0], [0.0, 1.0])  # body-fixed points of the rod's ends (m)


def _rod() -> Model:
    mass, inertia = np.array([1.0]), np.array([0.01])

    def forces(s, t, h, memory):
        return weight(s, h, mass)

    def user(s, t, h, memory):
        """Both rod ends against the ground y = 0.  As DAP_BC's Contact does, the penetration
        rate at the first evaluation in contact is kept (in ``memory``) until the end leaves;
        with ``memory["located"]`` set, the rates come from located impacts (Reference.solve)."""
        for end, local in enumerate(ROD_ENDS):
            p = s.point(1, local)
            depth, rate = -p.val[1], -p.rate[1]
            if depth > 0:
                rate0 = memory.get(end, rate) if memory.get("located") else memory.setdefault(end, rate)
                apply(s, h, 1, [0.0, contact_lankarani_nikravesh(depth, rate, rate0, 1e11, 0.95)], local)
            elif not memory.get("located"):
                memory.pop(end, None)

    return Model(mass, inertia, np.array([0.0, 1.0, np.pi / 4]), np.array([0.0, -6.0, 0.0]),
                 lambda s, t: [], forces, user)


MODELS: dict[str, Callable[[], Model]] = {
    "SP": _sp, "AA": _aa, "MP_A": lambda: _mp("A"), "MP_B": lambda: _mp("B"), "MP_C": lambda: _mp("C"),
    "Cart_A": lambda: _cart("A"), "Cart_B": lambda: _cart("B"), "Cart_C": lambda: _cart("C"),
    "Cart_D": lambda: _cart("D"), "CB": _cb, "Rod": _rod,
}


# ---------------------------------------------------------------- equations of motion
class Reference:
    """One model's equations of motion in plain numpy."""

    def __init__(self, name: str):
        self.name = name
        self.model = MODELS[name]()
        self.m = self.model.diag_mass
        self.memory: dict = {}  # contact states (Rod)
        self.impacts: list = []  # (end, time in s, d'0 in m/s) of the impacts located by solve

    def rows(self, q, qd, t):
        """(Phi, D, nu, gamma) of all constraints at (q, q', t)."""
        rows = self.model.constraints(State(q, qd), t)
        n = q.size
        if not rows:
            return np.zeros(0), np.zeros((0, n)), np.zeros(0), np.zeros(0)
        return (np.array([r.phi for r in rows]), np.array([r.jac for r in rows]),
                np.array([r.nu for r in rows]), np.array([r.gamma for r in rows]))

    def applied(self, q, qd, t):
        """(h, potential energy) at (q, q', t)."""
        h = np.zeros(q.size)
        state = State(q, qd)
        potential = self.model.forces(state, t, h, self.memory)
        if self.model.user is not None:
            self.model.user(state, t, h, self.memory)
        return h, potential

    def accelerations(self, t, y):
        """(q'', lam) with M q'' = h + D^T lam and D q'' = gamma."""
        n = y.size // 2
        q, qd = y[:n], y[n:]
        _, D, _, gamma = self.rows(q, qd, t)
        h, _ = self.applied(q, qd, t)
        m = D.shape[0]
        lhs = np.zeros((n + m, n + m))
        lhs[:n, :n] = np.diag(self.m)
        lhs[:n, n:] = -D.T
        lhs[n:, :n] = D
        sol = np.linalg.solve(lhs, np.concatenate([h, gamma]))
        return sol[:n], sol[n:]

    def rhs(self, t, y):
        """dy/dt for y = (q, q')."""
        return np.concatenate([y[y.size // 2:], self.accelerations(t, y)[0]])

    def energy(self, y):
        """(kinetic, potential, total) energy in J; potential of gravity and ptp springs."""
        n = y.size // 2
        kinetic = 0.5 * self.m @ y[n:] ** 2
        potential = self.applied(y[:n], y[n:], 0.0)[1]
        return np.array([kinetic, potential, kinetic + potential])

    def solve(self, y0, t_eval, rtol=1e-12, atol=1e-12):
        """DOP853 from y0 with output at t_eval; (len(t_eval), 2n) states.  For Rod, each end's
        impact is located as an event and the penetration rate at that instant is the d'0 of
        Eq. 11.42 for the whole contact (the exact value of what DAP_BC's Contact samples)."""
        t_eval = np.asarray(t_eval, float)
        if self.name != "Rod":
            sol = solve_ivp(self.rhs, (t_eval[0], t_eval[-1]), y0, method="DOP853", rtol=rtol,
                            atol=atol, t_eval=t_eval)
            return sol.y.T
        self.memory, self.impacts = {"located": True}, []
        out, t0, y = [], t_eval[0], np.asarray(y0, float)
        while True:
            events = [self._end_height(k) for k in range(len(ROD_ENDS))]
            for k, event in enumerate(events):  # the next impact, or the end leaving the ground
                event.terminal, event.direction = True, (1.0 if k in self.memory else -1.0)
            pending = t_eval[(t_eval > t0) if out else (t_eval >= t0)]
            sol = solve_ivp(self.rhs, (t0, t_eval[-1]), y, method="DOP853", rtol=rtol, atol=atol,
                            t_eval=pending, events=events)
            out.append(np.asarray(sol.y).reshape(y.size, -1).T)
            if sol.status != 1:
                return np.vstack(out)
            end = next(k for k, te in enumerate(sol.t_events) if te.size)
            t0, y = sol.t_events[end][0], sol.y_events[end][0]
            if end in self.memory:
                del self.memory[end]
            else:
                self.memory[end] = -State(y[:3], y[3:]).point(1, ROD_ENDS[end]).rate[1]
                self.impacts.append((end, t0, self.memory[end]))

    def _end_height(self, end: int):
        return lambda t, y: State(y[:3], y[3:]).point(1, ROD_ENDS[end]).val[1]

    def corrected(self, q, qd, t=0.0, tol=1e-13):
        """Initial conditions made consistent: minimum-norm Newton steps on Phi(q) = 0, then the
        minimum-norm change of q' that gives D q' = nu."""
        q, qd = np.array(q, float), np.array(qd, float)
        for _ in range(50):
            phi, D, _, _ = self.rows(q, qd, t)
            if phi.size == 0 or np.max(np.abs(phi)) < tol:
                break
            q -= D.T @ np.linalg.solve(D @ D.T, phi)
        _, D, nu, _ = self.rows(q, qd, t)
        if nu.size:
            qd -= D.T @ np.linalg.solve(D @ D.T, D @ qd - nu)
        return q, qd


def reference_rhs(name: str):
    """(fun, y0, t_span) of a model for scipy's solve_ivp; y = (q, q') in body coordinates."""
    ref = Reference(name)
    q, qd = ref.corrected(ref.model.q0, ref.model.qd0)
    return ref.rhs, np.concatenate([q, qd]), (0.0, T_FINAL[name])
