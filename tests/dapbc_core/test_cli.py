"""``mbds run FOLDER`` on a DAP_BC model folder: what it prints, what it writes, bad input."""

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from mbds.cli.main import app

SP = Path(__file__).resolve().parents[2] / "campaigns" / "dap_bc" / "SP"


@pytest.fixture()
def sp(tmp_path):
    return Path(shutil.copytree(SP, tmp_path / "SP"))


def test_run_prints_the_corrected_initial_conditions_and_writes_the_history(sp):
    result = CliRunner().invoke(app, ["run", str(sp), "--final-time", "0.4", "--report-step", "0.1", "--correct-ic"])
    assert result.exit_code == 0, result.output
    # manual Sec. B.1.1, as dap prints them
    assert "Corrected coordinates\nx y phi\n1 0.2 0\n1.25 -0.23301 0.5236\n" in result.output
    assert "Corrected velocities\nx-dot y-dot phi-dot\n0 0 0\n0 0 0\n" in result.output
    assert "Number of function evaluations = " in result.output
    with xr.open_dataset(sp / "000" / "history.nc") as ds:
        assert ds.attrs["kind"] == "dap_bc" and ds.attrs["analysis"] == "forward"
        assert ds.attrs["Conventions"] == "CF-1.10" and "input_inBodies.m" in ds.attrs
        assert np.allclose(ds["time"].values, [0.0, 0.1, 0.2, 0.3, 0.4])
        assert ds["r"].dims == ("time", "body", "axis") and ds["r"].attrs["units"] == "m"
        assert ds["pdd"].attrs["units"] == "rad s-2" and ds["eng"].attrs["units"] == "J"
        assert ds["Jac"].shape == (5, 4, 6) and ds["Lam"].shape == (5, 4) and ds["rP"].shape == (5, 3, 2)
    assert not list(sp.glob("000/*.tmp"))


def test_a_missing_flag_outside_a_terminal_is_bad_input(sp):
    result = CliRunner().invoke(app, ["run", str(sp), "--report-step", "0.1", "--no-correct-ic"])
    assert result.exit_code == 2
    assert "--final-time is missing" in result.output
    assert not (sp / "000").exists()


def test_an_unknown_analysis_is_bad_input(sp):
    result = CliRunner().invoke(app, ["run", str(sp), "--final-time", "1", "--report-step", "0.1",
                                      "--correct-ic", "--analysis", "dynamic"])
    assert result.exit_code == 2 and "unknown analysis 'dynamic'" in result.output


def test_an_in_file_error_names_file_and_line(sp):
    (sp / "inJoints.m").write_text((sp / "inJoints.m").read_text().replace("J2.jPindex = 3;", "J2.jPindex = 9;"))
    result = CliRunner().invoke(app, ["run", str(sp), "--final-time", "1", "--report-step", "0.1", "--correct-ic"])
    assert result.exit_code == 2
    assert "inJoints.m:" in result.output and "Traceback" not in result.output


def test_on_a_terminal_a_missing_flag_is_asked_for_as_dap_asks(monkeypatch):
    """dap's questions (manual Sec. B.1.1); an answer that is not understood is asked again."""
    from rich.console import Console

    from mbds.cli.dapbc_run import _yes_no, ask

    console = Console(force_terminal=True, record=True)
    answers = iter(["maybe", "y"])
    asked = []
    monkeypatch.setattr(console, "input", lambda prompt: asked.append(prompt) or next(answers))
    question = "Do you want to correct the initial conditions? [(y)es/(n)o]"
    assert ask(console, None, question, _yes_no, "--correct-ic") is True
    assert asked == [question + "\t"] * 2
    assert ask(console, 4.0, "Final time = ?", float, "--final-time") == 4.0
