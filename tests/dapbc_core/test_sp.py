"""DAP_BC's sliding pendulum (manual Sec. B.1.1, Example B.1) through the four analyses."""

from pathlib import Path

import numpy as np
import pytest

from mbds import dapbc

SP = Path(__file__).resolve().parents[2] / "campaigns" / "dap_bc" / "SP"


def test_function_evaluations_are_the_manuals():
    """Manual Sec. B.1.1: 4 s at ode45's RelTol 1e-6 / AbsTol 1e-9 (DAP_BC's settings) after the
    initial-condition correction take 655 function evaluations; mbds' Dormand-Prince pair with
    ode45's step control, without projection (DAP_BC's algorithm), takes the same number."""
    ds = dapbc.simulate(SP, final_time=4.0, report_step=0.02, projection=False)
    assert ds.attrs["nfev"] == 655


def test_projection_keeps_the_constraints_and_the_evaluation_count():
    """With projection (the default) the reports satisfy the constraints to 1e-12 and the
    evaluation count is still ode45's (the step's last derivative is reused)."""
    ds = dapbc.simulate(SP, final_time=4.0, report_step=0.02)
    slider, pendulum_pin = ds["rP"].values[:, 1], ds["rP"].values[:, 2]
    assert np.abs(slider - pendulum_pin).max() < 1e-12
    assert np.abs(ds["r"].values[:, 0, 1] - 0.2).max() < 1e-12
    assert ds.attrs["nfev"] == 655


def test_static_equilibrium():
    """The spring (k 20, L0 0.6, horizontal along the slider's track) is at rest length and the
    pendulum hangs straight down: slider at x = 0.6, pendulum centre at (0.6, -0.3), phi2 = 0;
    the pin carries the pendulum's weight 2 x 9.81 N (rev row y: M q'' - D^T Lam = h with D = -I
    for the pendulum, so Lam = -19.62 N)."""
    ds = dapbc.simulate(SP, analysis="static", final_time=1.0, report_step=0.5)
    assert np.allclose(ds["r"].values[:, 0], [0.6, 0.2], atol=1e-9)
    assert np.allclose(ds["r"].values[:, 1], [0.6, -0.3], atol=1e-9)
    assert np.allclose(np.sin(ds["p"].values[:, 1]), 0.0, atol=1e-9) and (np.cos(ds["p"].values[:, 1]) > 0).all()
    rev_y = list(ds["constraint_name"].values).index("joint 2 rev y")
    assert np.allclose(ds["Lam"].values[:, rev_y], -2 * 9.81, atol=1e-8)
    assert np.allclose(ds["eng"].values[:, 0], 0.0)


def test_kinematic_analysis_needs_a_driven_system():
    with pytest.raises(dapbc.ModelError, match="zero degrees of freedom: 6 coordinates but 4 constraint"):
        dapbc.simulate(SP, analysis="kinematic", final_time=1.0, report_step=0.5)


def test_unknown_analysis_and_bad_settings():
    with pytest.raises(dapbc.ModelError, match="unknown analysis 'dynamic'"):
        dapbc.simulate(SP, analysis="dynamic", final_time=1.0, report_step=0.5)
    with pytest.raises(dapbc.ModelError, match="report step"):
        dapbc.simulate(SP, final_time=1.0, report_step=2.0)


def test_runs_are_bit_identical():
    first, second = (dapbc.simulate(SP, final_time=1.0, report_step=0.05) for _ in range(2))
    for name in ("r", "p", "rdd", "Lam", "eng"):
        assert np.array_equal(first[name].values, second[name].values)


def test_a_changed_field_reuses_the_compiled_module():
    """What a campaign varies (force.1.k = 40): the element field changes through
    set_field_value, the system is built again with the same compiled module (its source depends
    on the model's structure only) and the new stiffness in its parameters, and the motion changes."""
    from mbds.io.dapbc.fields import set_field_value
    from mbds.io.dapbc.records import SourcePos
    from mbds.model.dapbc import build_system

    system = dapbc.load(SP)
    model = system.model
    set_field_value(model.forces[0], "k", 40.0, SourcePos("campaign.job", 3))
    stiffer = build_system(model)
    assert stiffer.module is system.module
    assert stiffer.data.par[system.parameter_labels.index("force 1 k")] == 40.0
    settings = dapbc.DapbcSettings(1.0, 0.1)
    before, after = (dapbc.analyse(s, "forward", settings)[1] for s in (system, stiffer))
    assert not np.allclose(before["r"].values, after["r"].values)
