"""A resting stack of three boxes stays at rest.

Source: statics of rigid bodies in unilateral contact (Pfeiffer and Glocker, "Multibody
Dynamics with Unilateral Contacts", Wiley 1996, ch. 5): boxes stacked centred on a floor under
gravity are in equilibrium with normal forces equal to the weight above each contact, so the
exact motion is no motion. The integrator must not drift (1e-9 m), gain energy or log impacts.
"""

import numpy as np
import pytest

from mbds.kernel import layout as K
from tests.physics.models import BoxStack, run_folder

pytestmark = pytest.mark.physics


def test_a_resting_stack_of_three_boxes_stays_at_rest(tmp_path):
    boxes = [(0.3, 0.1, 3.0), (0.2, 0.1, 2.0), (0.1, 0.1, 1.0)]  # (width, height (m), mass (kg)): a pyramid
    result = run_folder(BoxStack(boxes, break_time=1.0).write(tmp_path / "stack"))
    assert np.abs(result.q - result.q[0]).max() < 1e-9
    assert result.energy.max() <= result.energy[0] + 1e-12 * abs(result.energy[0])
    assert result.state.clock[K.IMPACTS] == 0
    assert result.state.clock[K.STEPS] < 2.0 * 1.0 / 1e-4  # steps near maximumTimestep
