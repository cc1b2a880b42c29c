"""DAP_BC's four analyses of a body-coordinate system (manual Sec. B.1; the book's Ch. 12-14):
``forward`` (forward dynamics, after the optional initial-condition correction), ``kinematic``
(a driven system with zero degrees of freedom), ``inverse`` (the multipliers, driver forces
included, along the kinematic motion) and ``static`` (static equilibrium at each report time).
Each returns a DapbcResult with DAP_BC's post arrays at the report times 0, DT, ..., T."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mbds.analysis.registry import register_analysis
from mbds.errors import ModelError
from mbds.kernel.dapbc_layout import ACCEPTED, NFEV, REJECTED, DapbcPost, integrator_state, post_arrays
from mbds.model.dapbc.system import DapbcSystem

#: max |Phi| (m, rad) the Newton iterations of the correction and of the kinematic and static
#: analyses stop at, and max |F| (N) of the static residual
POSITION_TOLERANCE = 1e-12
FORCE_TOLERANCE = 1e-9
METHODS = ("dopri5", "stiff")
#: the reports per progress update of a forward run
PROGRESS_UPDATES = 50


@dataclass(frozen=True)
class DapbcSettings:
    """Run settings: final time T and report step DT (s), whether to correct the initial
    conditions, the integrator (``dopri5`` or ``stiff``), its RelTol and AbsTol (DAP_BC's
    ode45 settings by default), and whether forward dynamics projects every step and report
    onto the constraints (off: DAP_BC's algorithm and evaluation count exactly)."""

    final_time: float
    report_step: float
    correct_ic: bool = True
    method: str = "dopri5"
    rtol: float = 1e-6
    atol: float = 1e-9
    projection: bool = True

    def __post_init__(self):
        if not (self.final_time > 0 and np.isfinite(self.final_time)):
            raise ModelError(f"the final time must be a positive number of seconds, not {self.final_time}")
        if not (0 < self.report_step <= self.final_time):
            raise ModelError(f"the report step must be positive and at most the final time, not {self.report_step}")
        if self.method not in METHODS:
            raise ModelError(f"unknown method '{self.method}' (known: {', '.join(METHODS)})")
        if not (self.rtol > 0 and self.atol > 0):
            raise ModelError("rtol and atol must be positive")

    @property
    def times(self) -> np.ndarray:
        """0, DT, ..., T (T included; a last shorter step when DT does not divide T)."""
        count = int(np.floor(self.final_time / self.report_step * (1 + 1e-12)))
        times = np.arange(count + 1) * self.report_step
        return times if np.isclose(times[-1], self.final_time, rtol=1e-12, atol=0) else np.append(times, self.final_time)


@dataclass
class Correction:
    """What the initial-condition correction changed: coordinates and velocities before and after."""

    q_before: np.ndarray
    qd_before: np.ndarray
    q_after: np.ndarray
    qd_after: np.ndarray
    iterations: int


@dataclass
class DapbcResult:
    """States y = (q, qd) (nt, 2n) at ``times``, DAP_BC's post arrays, and counters."""

    analysis: str
    times: np.ndarray
    y: np.ndarray
    post: DapbcPost
    nfev: int = 0
    steps: int = 0
    rejected: int = 0
    correction: Correction | None = None


def initial_state(system: DapbcSystem, correct: bool) -> tuple[np.ndarray, np.ndarray, Correction | None]:
    """(q0, qd0) of the bodies, corrected as DAP_BC does when ``correct``."""
    q, qd = system.q0.copy(), system.qd0.copy()
    if not correct or system.nc == 0:
        return q, qd, None
    iterations = system.module.correct(q, qd, 0.0, system.data.par, system.data.functs, POSITION_TOLERANCE)
    if iterations < 0:
        raise ModelError("the initial-condition correction did not converge in 50 Newton iterations "
                         "(constraints not satisfiable near the given coordinates)", system.source.path)
    return q, qd, Correction(system.q0.copy(), system.qd0.copy(), q.copy(), qd.copy(), iterations)


def _post(system: DapbcSystem, times, Y, states) -> DapbcPost:
    out = post_arrays(len(times), system.n, system.nc, system.n_points)
    system.module.post(times, Y, states, system.data, out)
    return out


@register_analysis("forward")
def forward(system: DapbcSystem, settings: DapbcSettings, progress: Callable | None = None) -> DapbcResult:
    """Forward dynamics: integrate M q'' - D^T lam = h, D q'' = gamma from the (corrected)
    initial state with ``settings.method``; progress(t, T, nfev) after each stretch of reports."""
    q, qd, correction = initial_state(system, settings.correct_ic)
    times = settings.times
    integ = integrator_state(np.concatenate([q, qd]))
    Y = np.zeros((len(times), 2 * system.n))
    states = np.zeros((len(times), system.n_state))
    state = np.zeros(system.n_state)
    step = system.module.forward_dopri5 if settings.method == "dopri5" else system.module.forward_stiff
    # (the integration resumes exactly where a stretch ended; without progress, one stretch)
    stride = max(1, len(times) // PROGRESS_UPDATES) if progress is not None else len(times)
    stop = 0
    while stop < len(times) - 1:
        stop = min(stop + stride, len(times) - 1)
        status = step(int(settings.projection), system.data, state, times, settings.rtol, settings.atol, integ, Y, states, stop)
        if status:
            t = integ.clock[0]
            reason = "the step size fell below its minimum" if status == 1 else "the state is not finite"
            raise ModelError(f"forward dynamics stopped at t = {t:.9g} s: {reason}", system.source.path)
        if progress is not None:
            progress(float(times[stop]), float(times[-1]), int(integ.counts[NFEV]))
    return DapbcResult("forward", times, Y, _post(system, times, Y, states), int(integ.counts[NFEV]),
                       int(integ.counts[ACCEPTED]), int(integ.counts[REJECTED]), correction)


def _kinematic_motion(system: DapbcSystem, settings: DapbcSettings, name: str):
    n, nc = system.n, system.nc
    if nc != n:
        raise ModelError(f"the {name} analysis needs a driven system with zero degrees of freedom: "
                         f"{n} coordinates but {nc} constraint equations", system.source.path)
    times = settings.times
    q, qd = system.q0.copy(), system.qd0.copy()
    Y, qdd = np.zeros((len(times), 2 * n)), np.zeros((len(times), n))
    acc = np.zeros(n)
    for k, t in enumerate(times):
        if system.module.kinematic_state(q, qd, acc, t, system.data.par, system.data.functs, POSITION_TOLERANCE) < 0:
            raise ModelError(f"kinematic analysis: the constraints have no solution near t = {t:.9g} s "
                             f"(Newton did not converge)", system.source.path)
        Y[k, :n], Y[k, n:], qdd[k] = q, qd, acc
        q = q + qd * settings.report_step + 0.5 * acc * settings.report_step ** 2  # next Newton start
    return times, Y, qdd


@register_analysis("kinematic")
def kinematic(system: DapbcSystem, settings: DapbcSettings, progress: Callable | None = None) -> DapbcResult:
    """Kinematics of a fully driven system: q, qd, qdd from the constraints alone (Lam: NaN)."""
    times, Y, qdd = _kinematic_motion(system, settings, "kinematic")
    post = _post(system, times, Y, np.zeros((len(times), system.n_state)))
    post.qdd[:] = qdd
    post.lam[:] = np.nan
    return DapbcResult("kinematic", times, Y, post)


@register_analysis("inverse")
def inverse(system: DapbcSystem, settings: DapbcSettings, progress: Callable | None = None) -> DapbcResult:
    """Inverse dynamics along the kinematic motion: Lam from D^T Lam = M qdd - h (the
    multipliers of the drivers are the driver forces and torques)."""
    times, Y, qdd = _kinematic_motion(system, settings, "inverse")
    states = np.zeros((len(times), system.n_state))
    post = _post(system, times, Y, states)
    post.qdd[:] = qdd
    n = system.n
    for k, t in enumerate(times):
        system.module.inverse_multipliers(t, Y[k, :n].copy(), Y[k, n:].copy(), qdd[k].copy(), system.data,
                                          states[k].copy(), post.lam[k], post.jac[k])
    return DapbcResult("inverse", times, Y, post)


@register_analysis("static")
def static(system: DapbcSystem, settings: DapbcSettings, progress: Callable | None = None) -> DapbcResult:
    """Static equilibrium h(q) + D^T lam = 0, Phi(q, t) = 0 at every report time (the drivers
    at their values there), by Newton's method from the (corrected) initial coordinates."""
    q, _, correction = initial_state(system, settings.correct_ic)
    times = settings.times
    n = system.n
    x = np.concatenate([q, np.zeros(system.nc)])
    Y = np.zeros((len(times), 2 * n))
    lam = np.zeros((len(times), system.nc))
    for k, t in enumerate(times):
        state = np.zeros(system.n_state)
        if system.module.static_equilibrium(t, x, system.data, state, FORCE_TOLERANCE) < 0:
            raise ModelError(f"static analysis: no equilibrium found near the initial coordinates at "
                             f"t = {t:.9g} s (Newton did not converge)", system.source.path)
        Y[k, :n], lam[k] = x[:n], x[n:]
    post = _post(system, times, Y, np.zeros((len(times), system.n_state)))
    post.qdd[:] = 0.0
    post.lam[:] = lam
    return DapbcResult("static", times, Y, post, correction=correction)
