"""Time DAP_BC models in mbds against DAP_BC's own code and against scipy's solve_ivp.

Run from the repository root: ``.venv/bin/python benchmarks/dapbc.py [--repeat N]``.

For SP (4 s), MP_A (1 s), Rod (0.2 s) and CB (10 s) of campaigns/dap_bc, forward dynamics at
DAP_BC's ode45 settings RelTol 1e-6, AbsTol 1e-9, initial conditions corrected:

- ``mbds``: the forward analysis (integration and DAP_BC's post at every report) on a system
  already compiled and loaded (warm), best of ``--repeat`` runs, with mbds.kernel.dopri5 (the
  Dormand-Prince pair as ode45 applies it) and, for CB and Rod, also the ``stiff`` option;
- ``scipy``: ``solve_ivp(method="RK45")`` (the same Dormand-Prince pair) at the same tolerances
  and report times on the plain numpy right-hand side of benchmarks/dapbc_reference.py, from
  the same corrected initial state: the choice a Python user would make today; the last column
  is the largest difference of the coordinates q (m, rad) between the two at the reports (Rod's
  depends on where each integrator's trial stages first touch the ground, since DAP_BC's Contact
  keeps the penetration rate of that first evaluation);
- ``DAP_BC``: the wall times and evaluation counts of DAP_BC's own code under GNU Octave 7.3
  (ode45, same tolerances) quoted in issue 11; they were not measured here.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.dapbc_reference import Reference  # noqa: E402
from mbds.analysis import analysis  # noqa: E402
from mbds.analysis.dapbc import DapbcSettings  # noqa: E402
from mbds.dapbc import load  # noqa: E402

RTOL, ATOL = 1e-6, 1e-9
#: model -> (final time, report step) in s
CASES = {"SP": (4.0, 0.02), "MP_A": (1.0, 0.01), "Rod": (0.2, 0.001), "CB": (10.0, 0.01)}
#: DAP_BC under GNU Octave 7.3 (issue 11): wall time (s), function evaluations
DAPBC_OCTAVE = {"SP": (1.81, 615), "MP_A": (7.2, 1202), "Rod": (13.0, 8037), "CB": (150.0, 55635)}


def best_of(repeat: int, run) -> tuple[float, object]:
    """The shortest wall time (s) of ``repeat`` calls, and the last result."""
    best, result = np.inf, None
    for _ in range(repeat):
        start = time.perf_counter()
        result = run()
        best = min(best, time.perf_counter() - start)
    return best, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per timing (best is kept)")
    args = parser.parse_args()
    forward = analysis("forward")
    header = (f"{'model':6} {'T (s)':>6} {'DAP_BC (s)':>10} {'nfev':>6} {'mbds (s)':>9} {'nfev':>6} "
              f"{'speed-up':>9} {'goal (s)':>8} {'stiff (s)':>9} {'nfev':>6} {'scipy (s)':>9} {'nfev':>6} "
              f"{'max|q mbds-scipy|':>17}")
    print(header)
    for name, (final_time, step) in CASES.items():
        system = load(ROOT / "campaigns" / "dap_bc" / name)
        settings = DapbcSettings(final_time, step, True, "dopri5", RTOL, ATOL)
        forward(system, settings)  # compile or load from the cache
        mbds_time, result = best_of(args.repeat, lambda: forward(system, settings))
        stiff_text = f"{'':>9} {'':>6}"
        if name in ("CB", "Rod"):
            stiff = DapbcSettings(final_time, step, True, "stiff", RTOL, ATOL)
            forward(system, stiff)
            stiff_time, stiff_result = best_of(args.repeat, lambda: forward(system, stiff))
            stiff_text = f"{stiff_time:9.4f} {stiff_result.nfev:6d}"
        ref = Reference(name)
        y0 = result.y[0]

        def scipy_run():
            ref.memory = {}
            return solve_ivp(ref.rhs, (0.0, final_time), y0, method="RK45", rtol=RTOL, atol=ATOL,
                             t_eval=result.times)
        scipy_time, sol = best_of(max(1, args.repeat // 5), scipy_run)
        n = result.y.shape[1] // 2
        difference = np.abs(sol.y.T[:, :n] - result.y[:, :n]).max() if sol.success else np.nan
        octave_time, octave_nfev = DAPBC_OCTAVE[name]
        print(f"{name:6} {final_time:6.1f} {octave_time:10.2f} {octave_nfev:6d} {mbds_time:9.4f} {result.nfev:6d} "
              f"{octave_time / mbds_time:8.0f}x {octave_time / 100:8.3f} {stiff_text} {scipy_time:9.3f} "
              f"{sol.nfev:6d} {difference:17.2e}", flush=True)


if __name__ == "__main__":
    main()
