"""The stiff option (ode23s's Rosenbrock 2(3) pair) converges to the independent reference
integration (benchmarks/dapbc_reference.py, scipy's DOP853 at rtol = atol = 1e-12) of the two
models it is meant for: CB (friction with tanh(1e4 v)) and Rod (contact stiffness 1e11)."""

from pathlib import Path

import numpy as np
import pytest

from benchmarks.dapbc_reference import Reference
from mbds import dapbc

FOLDERS = Path(__file__).resolve().parents[2] / "campaigns" / "dap_bc"


@pytest.mark.parametrize("name, final_time, step", [("CB", 2.0, 0.1), ("Rod", 0.1, 0.01)])
def test_stiff_option_agrees_with_the_reference(name, final_time, step):
    ds = dapbc.simulate(FOLDERS / name, final_time=final_time, report_step=step, method="stiff",
                        rtol=1e-8, atol=1e-11)
    nt, nb = ds["p"].shape
    q = np.concatenate([ds["r"].values, ds["p"].values[:, :, None]], axis=2).reshape(nt, 3 * nb)
    qd = np.concatenate([ds["rd"].values, ds["pd"].values[:, :, None]], axis=2).reshape(nt, 3 * nb)
    reference = Reference(name).solve(np.concatenate([q[0], qd[0]]), ds["time"].values)
    assert np.abs(reference[:, :3 * nb] - q).max() < 2e-6
