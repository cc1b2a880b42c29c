"""Time mbds' Lemke solver side by side with Siconos' Lemke on the same problems.

Run from the repository root: ``.venv/bin/python benchmarks/lcp.py``.

Problems: random symmetric positive definite M for n = 10, 20, 50, 100, 200 with
q = -M z*, z* in [0.5, 1.5]^n (every constraint active: n + 1 pivots), and the peer fc2d
set (``../shared/testdata/lcp/siconos_fc2d``, skipped if absent).

Timing: the CPU time of the timing thread (``time.thread_time``, immune to other processes
on a shared machine), best of 5 repetitions of a batch of solves, divided by the batch size.
mbds is timed in a numba loop over the batch (no Python call per solve). Siconos is Debian's
``python3-siconos``, which lives in the system Python: a subprocess of ``/usr/bin/python3``
loads the problems from .npy files and times a Python loop of
``siconos.numerics.lcp_lexicolemke`` calls (solver SICONOS_LCP_LEMKE, default options), so
its figures include about a microsecond of Python-to-C call per solve. Install it with
``apt-get install -y python3-siconos``.

Flops: a pivot updates the k stored columns of the basis inverse (2 n k flops) and forms the
next entering column from them (2 n k); on the all-active path k grows from 0 to n, so a
pivot costs 2 n^2 flops on average (a full n x (2n + 2) tableau pivot: 4 n^2). The
``axpy GF/s`` column is the rate of the same row update alone on the same data size: the
attainable speed of this memory-bound kernel on this machine.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from mbds.io.lcpfile import read_lcp
from mbds.kernel.jit import jit
from mbds.kernel.lcp import lcp_workspace, lemke
from mbds.lcp import LEXICO_ZERO_TOLERANCE, PIVOT_TOLERANCE_MAX, PIVOT_TOLERANCE_MIN

ROOT = Path(__file__).resolve().parents[1]
FC2D = ROOT.parent / "shared" / "testdata" / "lcp" / "siconos_fc2d"
SIZES = (10, 20, 50, 100, 200)
SYSTEM_PYTHON = "/usr/bin/python3"
INSTALL = "apt-get install -y python3-siconos"

SICONOS_DRIVER = """
import json, sys, time
import numpy as np
import siconos.numerics as sn
out = []
for name, reps in json.loads(sys.argv[1]):
    M = np.load(name + "_M.npy"); q = np.load(name + "_q.npy")
    n = q.size
    problem = sn.LCP(M, q)
    z, w = np.zeros(n), np.zeros(n)
    options = sn.SolverOptions(sn.SICONOS_LCP_LEMKE)
    info = sn.lcp_lexicolemke(problem, z, w, options)
    best = float("inf")
    for _ in range(5):
        start = time.thread_time()
        for _ in range(reps):
            sn.lcp_lexicolemke(problem, z, w, options)
        best = min(best, (time.thread_time() - start) / reps)
    out.append({"seconds": best, "info": int(info), "pivots": int(options.iparam[1])})
print(json.dumps(out))
"""


@jit
def _solve_batch(M, q, reps, z, w, fwork, iwork):
    """Solve LCP(M, q) reps times; return (status, pivots) of the last solve."""
    status, pivots = 0, 0
    for _ in range(reps):
        status, pivots = lemke(
            M, q, z, w, PIVOT_TOLERANCE_MIN, PIVOT_TOLERANCE_MAX, LEXICO_ZERO_TOLERANCE, 100000, fwork, iwork
        )
    return status, pivots


@jit
def _axpy_batch(G, d, k, reps):
    """The pivot's row update G[s] -= f d on k rows of length n, reps times."""
    for rep in range(reps):
        for s in range(k):
            f = 1e-9 * (rep + s)
            for i in range(d.shape[0]):
                G[s, i] -= f * d[i]


def best_time(run, reps: int) -> float:
    """Best thread CPU time of 5 batches of reps calls, per call (seconds)."""
    best = float("inf")
    for _ in range(5):
        start = time.thread_time()
        run(reps)
        best = min(best, (time.thread_time() - start) / reps)
    return best


def problems() -> list[tuple[str, np.ndarray, np.ndarray]]:
    """The benchmark problems as (name, M, q)."""
    rng = np.random.default_rng(2024)
    out = []
    for n in SIZES:
        A = rng.standard_normal((n, n))
        M = A @ A.T + n * np.eye(n)
        out.append((f"spd{n}", M, -M @ rng.uniform(0.5, 1.5, n)))
    if FC2D.is_dir():
        for path in sorted(FC2D.glob("*.dat")):
            M, q = read_lcp(path)
            out.append((path.stem.replace("lcp_from_", ""), M, q))
    else:
        print(f"fc2d set not found at {FC2D}: skipped")
    return out


def repetitions(n: int) -> int:
    """Solves per timed batch for size n (about 10 ms of mbds work)."""
    return max(3, int(3e6 / n**2.5))


def time_mbds(name: str, M: np.ndarray, q: np.ndarray) -> dict:
    """Status, pivots and seconds per solve of mbds; flop model and axpy rate for spd rows."""
    n = q.size
    z, w = np.empty(n), np.empty(n)
    fwork, iwork = lcp_workspace(n)
    status, pivots = _solve_batch(M, q, 1, z, w, fwork, iwork)
    seconds = best_time(lambda reps: _solve_batch(M, q, reps, z, w, fwork, iwork), repetitions(n))
    row = {"status": int(status), "pivots": int(pivots), "seconds": seconds}
    if name.startswith("spd"):
        k = max(n // 2, 1)
        G, d = np.random.default_rng(0).random((k, n)), np.ones(n)
        _axpy_batch(G, d, k, 1)
        reps = max(10, int(1e8 / (n * k)))
        row["flops_per_pivot"] = 2.0 * n * n
        row["axpy_gflops"] = 2.0 * n * k / best_time(lambda r: _axpy_batch(G, d, k, r), reps) / 1e9
    return row


def time_siconos(cases: list[tuple[str, np.ndarray, np.ndarray]]) -> list[dict] | None:
    """Seconds per solve, info and pivots of Siconos per case, or None if it is unavailable."""
    check = subprocess.run([SYSTEM_PYTHON, "-c", "import siconos.numerics"], capture_output=True)
    if check.returncode != 0:
        print(f"Siconos is missing ({SYSTEM_PYTHON} cannot import siconos.numerics): run `{INSTALL}`")
        return None
    with tempfile.TemporaryDirectory() as tmp:
        jobs = []
        for name, M, q in cases:
            np.save(Path(tmp) / f"{name}_M.npy", M)
            np.save(Path(tmp) / f"{name}_q.npy", q)
            jobs.append((name, repetitions(q.size) // 4 + 3))
        done = subprocess.run(
            [SYSTEM_PYTHON, "-c", SICONOS_DRIVER, json.dumps(jobs)], cwd=tmp, capture_output=True, text=True
        )
    if done.returncode != 0:
        print(f"Siconos run failed:\n{done.stderr}")
        return None
    return json.loads(done.stdout)


def table(cases, ours, theirs) -> str:
    """The comparison as a Markdown table."""
    header = (
        "| problem | n | pivots mbds / Siconos | mbds µs/solve | Siconos µs/solve | ratio | flop/pivot "
        "| mbds GF/s | axpy GF/s |"
    )
    lines = [header, "|---" * 9 + "|"]
    for (name, M, q), row, sic in zip(cases, ours, theirs or [None] * len(cases)):
        n = q.size
        status = "" if row["status"] == 0 else f" (status {row['status']})"
        sic_info = "" if not sic or sic["info"] == 0 else f" (info {sic['info']})"
        sic_pivots = f"{sic['pivots']}{sic_info}" if sic else "-"
        sic_time = f"{sic['seconds'] * 1e6:.1f}" if sic else "-"
        ratio = f"{row['seconds'] / sic['seconds']:.2f}" if sic else "-"
        if "flops_per_pivot" in row:
            flops = f"{row['flops_per_pivot']:.0f}"
            rate = f"{row['flops_per_pivot'] * row['pivots'] / row['seconds'] / 1e9:.1f}"
            axpy = f"{row['axpy_gflops']:.1f}"
        else:
            flops = rate = axpy = "-"
        lines.append(
            f"| {name} | {n} | {row['pivots']}{status} / {sic_pivots} | {row['seconds'] * 1e6:.1f} | {sic_time} "
            f"| {ratio} | {flops} | {rate} | {axpy} |"
        )
    return "\n".join(lines)


def main() -> None:
    cases = problems()
    ours = [time_mbds(name, M, q) for name, M, q in cases]
    theirs = time_siconos(cases)
    print(table(cases, ours, theirs))


if __name__ == "__main__":
    sys.exit(main())
