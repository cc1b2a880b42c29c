"""The series figures of a DAP_BC history (kind = dap_bc, arrays of DAP_BC's Table B.10 with time
first, as docs/results.md states the convention)."""

import numpy as np
import pytest
import xarray as xr

from mbds import plot
from mbds.errors import ModelError


@pytest.fixture(scope="module")
def dap_bc():
    """A pendulum of one body swinging as phi = sin t (a history written by hand to the convention)."""
    t = np.linspace(0.0, 1.0, 11)
    phi = np.sin(t)
    r = np.stack([0.5 * np.sin(phi), -0.5 * np.cos(phi)], -1)[:, None, :]
    kinetic, potential = 0.5 * np.cos(t) ** 2, 1 - np.cos(phi)
    return xr.Dataset(
        {"r": (("time", "body", "xy"), r, {"units": "m"}), "p": (("time", "body"), phi[:, None], {"units": "rad"}),
         "Lam": (("time", "constraint"), np.column_stack([t, -t]), {"long_name": "Lagrange multiplier", "units": "N"}),
         "eng": (("time", "energy"), np.column_stack([kinetic, potential, kinetic + potential]), {"units": "J"})},
        coords={"time": ("time", t, {"long_name": "time", "units": "s"})},
        attrs={"kind": "dap_bc", "model": "pendulum"})


def test_coordinates_multipliers_and_energy_of_a_dap_bc_run(dap_bc):
    metres, radians = plot.coordinates(dap_bc).axes
    assert [line.get_label() for line in metres.lines] == ["x1", "y1"]
    np.testing.assert_array_equal(radians.lines[0].get_ydata(), dap_bc["p"].values[:, 0])
    ax = plot.multipliers(dap_bc)
    assert len(ax.lines) == 2 and ax.get_ylabel() == "Lagrange multiplier (N)"
    np.testing.assert_array_equal(ax.lines[1].get_ydata(), -dap_bc["time"].values)
    ax = plot.energy(dap_bc)
    assert [line.get_label() for line in ax.lines] == ["kinetic energy", "potential energy", "total energy"]
    np.testing.assert_array_equal(ax.lines[2].get_ydata(), dap_bc["eng"].values[:, 2])
    assert "model pendulum" in ax.get_title()


def test_an_unknown_kind_of_run_is_named(dap_bc):
    with pytest.raises(ModelError, match="unknown kind of run 'adams'"):
        plot.energy(dap_bc.assign_attrs(kind="adams"))
