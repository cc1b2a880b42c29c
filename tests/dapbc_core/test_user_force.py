"""A user force given as a Python function (user_force.py in the model folder) runs in the
compiled model: the sliding pendulum pushed by 1.5 N along x on the slider through
user_force.py moves exactly as with the manual's constant-force element ``f``."""

import shutil
from pathlib import Path

import numpy as np

from mbds import dapbc

SP = Path(__file__).resolve().parents[2] / "campaigns" / "dap_bc" / "SP"
PUSH = '''
def user_force(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):
    f[0, 0] += 1.5
'''


def with_force(folder: Path, element: str) -> Path:
    shutil.copytree(SP, folder)
    forces = folder / "inForces.m"
    text = forces.read_text().replace("Forces = [F1; F2];", f"F3 = Force_struct;\n{element}\nForces = [F1; F2; F3];")
    forces.write_text(text)
    return folder


def test_python_user_force_equals_the_constant_force_element(tmp_path):
    python = with_force(tmp_path / "python", "F3.type = 'user';")
    (python / "user_force.py").write_text(PUSH)
    element = with_force(tmp_path / "element", "F3.type = 'f';\nF3.iBindex = 1;\nF3.f = [1.5; 0];")
    a = dapbc.simulate(python, final_time=1.0, report_step=0.1)
    b = dapbc.simulate(element, final_time=1.0, report_step=0.1)
    assert np.array_equal(a["r"].values, b["r"].values) and np.array_equal(a["Lam"].values, b["Lam"].values)
    assert not np.allclose(a["r"].values, dapbc.simulate(SP, final_time=1.0, report_step=0.1)["r"].values)
