"""The functions DAP_BC offers to user forces, as small numba functions that compiled
user_force code calls (see mbds/io/dapbc/user_force.py).  SI units: m, s, N, N m, rad.

- ``friction_anderson``: Friction_A, the friction coefficient of Anderson, Soederberg and
  Bjoerklund (Tribology International 40 (2007) 580-587) without its viscous term,
  mu(v) = (mu_d + (mu_s - mu_d) exp(-(|v|/v_s)^p)) tanh(k_t v).
- ``friction_brown_mcphee``: Friction_B, the friction force of Brown and McPhee (J. Comput.
  Nonlinear Dynam. 11 (2016) 054502), F = f_n (mu_d tanh(4 v/v_t) + (mu_s - mu_d)(v/v_t) /
  ((v/v_t)^2/4 + 3/4)^2) + mu_v v tanh(4 f_n/f_nt).
- ``contact_lankarani_nikravesh`` (Eq. 11.42 of the book, Lankarani and Nikravesh, J. Mech.
  Des. 112 (1990) 369-376): f = k d^1.5 (1 + 3(1 - e^2)/4 * d'/d'0).
- ``contact_flores`` (Eq. 11.43, Flores, Machado, Silva and Martins, Multibody Syst. Dyn. 25
  (2011) 357-375): f = k d^1.5 (1 + 8(1 - e)/(5 e) * d'/d'0).
- ``contact_ground``: DAP_BC's Contact, a body point against the ground y = 0, keeping per
  contact the penetration velocity at first contact d'0 in a state array.

d is the penetration (m), d' its rate (m/s), d'0 the rate at first contact, e the coefficient
of restitution, k the contact stiffness (N/m^1.5).
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit

#: state slots per contact: [in contact (1.0) or not (0.0), penetration rate at first contact (m/s)]
CONTACT_STATE_SLOTS = 2
LANKARANI_NIKRAVESH = 1  # DAP_BC's model index Mi of Eq. 11.42
FLORES = 2  # model index of Eq. 11.43


@jit
def friction_anderson(mu_s, mu_d, v_s, p, k_t, v):
    """Friction_A: the coefficient of Anderson et al. (viscous term left out); v in m/s."""
    return (mu_d + (mu_s - mu_d) * np.exp(-((abs(v) / v_s) ** p))) * np.tanh(k_t * v)


@jit
def friction_brown_mcphee(mu_s, mu_d, mu_v, v_t, f_nt, v, f_n):
    """Friction_B: the friction force (N) of Brown and McPhee for normal force f_n (N)."""
    ratio = v / v_t
    stribeck = (mu_s - mu_d) * ratio / (0.25 * ratio * ratio + 0.75) ** 2
    return f_n * (mu_d * np.tanh(4.0 * ratio) + stribeck) + mu_v * v * np.tanh(4.0 * f_n / f_nt)


@jit
def _damping_ratio(rate, rate0):
    # d'/d'0, with no damping when the contact began at rest (d'0 = 0)
    return rate / rate0 if rate0 != 0.0 else 0.0


@jit
def contact_lankarani_nikravesh(depth, rate, rate0, k, e):
    """Eq. 11.42: contact force (N) of penetration depth (m) and rate (m/s)."""
    return k * depth ** 1.5 * (1.0 + 3.0 * (1.0 - e * e) / 4.0 * _damping_ratio(rate, rate0))


@jit
def contact_flores(depth, rate, rate0, k, e):
    """Eq. 11.43: contact force (N) of penetration depth (m) and rate (m/s)."""
    return k * depth ** 1.5 * (1.0 + 8.0 * (1.0 - e) / (5.0 * e) * _damping_ratio(rate, rate0))


@jit
def contact_ground(state, slot, point, body, k, e, law, rP, rP_d, sP, f, n):
    """DAP_BC's Contact(Ci, Pi, Bi, k, e, Mi) with 0-based ``point`` and ``body``: when the
    point is below y = 0, add the vertical contact force of ``law`` (1: Eq. 11.42, 2: Eq. 11.43)
    to f[body] and its moment about the body's mass centre to n[body].  ``state[slot]`` and
    ``state[slot + 1]`` hold the contact flag and d'0, set at the first evaluation in contact
    and cleared when the point leaves the ground."""
    depth = -rP[point, 1]
    if depth > 0.0:
        rate = -rP_d[point, 1]
        if state[slot] == 0.0:
            state[slot + 1] = rate
            state[slot] = 1.0
        if law == LANKARANI_NIKRAVESH:
            fy = contact_lankarani_nikravesh(depth, rate, state[slot + 1], k, e)
        else:
            fy = contact_flores(depth, rate, state[slot + 1], k, e)
        f[body, 1] += fy
        n[body] += sP[point, 0] * fy  # s_rot(sP)' * [0; fy]
    else:
        state[slot] = 0.0
