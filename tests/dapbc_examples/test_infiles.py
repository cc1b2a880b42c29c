"""The in-files of campaigns/dap_bc/ read by mbds' DAP_BC reader carry the same model data as
the independent references of benchmarks/dapbc_reference.py, which were typed in separately
from the manual's listings: a typo in either shows here."""

from pathlib import Path

import numpy as np
import pytest

from benchmarks.dapbc_reference import MODELS, Reference, State
from mbds.io.dapbc import read_dapbc_folder
from mbds.io.dapbc.user_force import user_force_code
from tests.dapbc_io.user_force_eval import evaluate

FOLDERS = Path(__file__).resolve().parents[2] / "campaigns" / "dap_bc"
#: (joints, forces, functions) per model as listed in the manual, Sec. B.1 and B.4
ELEMENTS = {
    "SP": (["tran", "rev"], ["ptp", "weight"], []),
    "AA": (["rev"] * 4, ["ptp", "user", "weight"], []),
    "MP_A": (["rev", "rev", "rev", "tran"], ["ptp", "user", "weight"], []),
    "MP_B": (["rev", "rev-tran", "rev"], ["ptp", "user", "weight"], []),
    "MP_C": (["rev-rev", "rev-tran"], ["ptp", "user", "weight"], []),
    "Cart_A": (["rev", "rev", "disc", "disc", "rel-rot"], ["weight"], ["a"]),
    "Cart_B": (["rev", "rev", "disc", "disc", "rel-rot"], ["weight"], ["c"]),
    "Cart_C": (["rev", "rev", "disc", "disc"], ["weight", "user"], []),
    "Cart_D": (["rev", "rev", "disc", "disc"], ["weight", "user"], []),
    "CB": (["tran"], ["ptp", "weight", "user"], []),
    "Rod": ([], ["weight", "user"], []),
}


def test_every_example_is_listed():
    assert sorted(p.name for p in FOLDERS.iterdir() if p.is_dir()) == sorted(MODELS) == sorted(ELEMENTS)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_bodies_match_the_reference(name):
    model = read_dapbc_folder(FOLDERS / name)
    ref = Reference(name).model
    assert np.array_equal([b.m for b in model.bodies], ref.mass)
    assert np.array_equal([b.J for b in model.bodies], ref.inertia)
    q0 = np.ravel([[*b.r, b.p] for b in model.bodies])
    qd0 = np.ravel([[*b.r_d, b.p_d] for b in model.bodies])
    assert np.array_equal(q0, ref.q0) and np.array_equal(qd0, ref.qd0)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_elements_are_the_manuals(name):
    model = read_dapbc_folder(FOLDERS / name)
    joints, forces, functs = ELEMENTS[name]
    assert [j.type for j in model.joints] == joints
    assert [f.type for f in model.forces] == forces
    assert [f.type for f in model.functs] == functs
    assert (model.user_force_file is not None) == ("user" in forces)


@pytest.mark.parametrize("name", sorted(n for n, e in ELEMENTS.items() if "user" in e[1]))
def test_user_forces_match_the_reference(name):
    """Each user_force.m, compiled by mbds, adds the same forces and torques as the reference's
    hand-written user force, at states drawn around the initial one (tires and the rod's lower
    end both in and out of contact, the belt both slipping and near sticking)."""
    model = read_dapbc_folder(FOLDERS / name)
    force = user_force_code(model).load()
    ref = Reference(name)
    rng = np.random.default_rng(7)
    nb = len(model.bodies)
    engaged = 0
    for _ in range(20):
        q = ref.model.q0 + rng.normal(scale=0.05, size=3 * nb)
        if name.startswith("MP"):  # the wheel centre around the tire's free height 0.30 m
            q[1] -= 0.0586
        if name == "Rod":  # lower end within +-0.1 mm of the ground
            q[1] = np.cos(q[2]) + rng.normal(scale=1e-4)
        qd = rng.normal(scale=0.5 if name != "CB" else 0.08, size=3 * nb)
        x, xd = q.reshape(nb, 3), qd.reshape(nb, 3)
        ref.memory = {}
        h = np.zeros(3 * nb)
        ref.model.user(State(q, qd), 0.0, h, ref.memory)
        f, n, _ = evaluate(force, model, x[:, :2], x[:, 2], xd[:, :2], xd[:, 2])
        assert np.allclose(np.column_stack([f, n]).ravel(), h, rtol=1e-12, atol=1e-9)
        engaged += np.any(h)
    assert engaged >= 5  # the forces were not all zero
