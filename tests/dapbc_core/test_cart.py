"""Inverse dynamics of the driven carts (manual Sec. B.4.3) against analytic results."""

from pathlib import Path

import numpy as np
import pytest

from mbds import dapbc
from mbds.io.dapbc.records import Funct
from mbds.kernel.dapbc_functions import funct_value
from mbds.model.dapbc.functs import funct_table

FOLDERS = Path(__file__).resolve().parents[2] / "campaigns" / "dap_bc"
#: the inertia the rear-wheel driver sees: every body moves at v = -R phi2' (rolling, R = 0.1 m:
#: (20 + 2 + 2) kg R^2) and both wheels spin at phi2' (2 x 0.5 kg m^2)
EFFECTIVE_INERTIA = 24.0 * 0.1 ** 2 + 2 * 0.5


@pytest.fixture(scope="module")
def cart_b():
    return dapbc.simulate(FOLDERS / "Cart_B", analysis="inverse", final_time=3.0, report_step=0.25)


def test_constraint_order_is_the_manuals(cart_b):
    """The manual plots Lam(:,9) (driver), Lam(:,6) and Lam(:,8) (no-slip of the rear and front
    wheels) for the carts: rows 6, 8 and 9 here are those constraints."""
    names = list(cart_b["constraint_name"].values)
    assert names[5] == "joint 3 disc rolling" and names[7] == "joint 4 disc rolling"
    assert names[8] == "joint 5 rel-rot driver"


def test_driver_torque_accelerates_the_cart(cart_b):
    """Cart_B: no force does work but the driver (gravity is normal to the motion), so its power
    Lam f' equals dT/dt with T = I f'^2 / 2: Lam = I f''; the cart moves at x' = -R f'."""
    ds = cart_b
    table = funct_table([Funct(type="c", t_end=2.0, dfdt_end=-2 * np.pi)])
    rate, second = np.array([funct_value(table[0], t)[1:] for t in ds["time"].values]).T
    assert np.allclose(ds["Lam"].values[:, 8], EFFECTIVE_INERTIA * second, rtol=0, atol=1e-9)
    assert np.allclose(ds["rd"].values[:, 0, 0], -0.1 * rate, rtol=0, atol=1e-12)
