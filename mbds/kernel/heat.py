"""Contact temperatures (an mbds extension): the points of contact pairs with a heat model warm
by their share of the energy lost at their contacts (booked with the losses, see
:func:`mbds.kernel.rollback.record`) and relax towards their ambient temperature. Temperatures
are in deg C, in the TEMP column of the per-point values; ``point_heat`` holds each point's
HEATING (deg C per J), COOLING rate (1/s) and AMBIENT (deg C) temperature."""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit
from mbds.kernel.layout import AMBIENT, COOLING, HEATING, TEMP


@jit(refcount=False)
def cool(point_heat, point_interval, dt):
    """Let every point with a heat model relax towards its ambient temperature over dt (s):
    T = T_a + (T - T_a) exp(-dt * COOLING), exact for a step with no heating."""
    for k in range(point_heat.shape[0]):
        rate = point_heat[k, COOLING]
        if point_heat[k, HEATING] > 0.0 and rate > 0.0:
            ambient = point_heat[k, AMBIENT]
            point_interval[k, TEMP] = ambient + (point_interval[k, TEMP] - ambient) * np.exp(-dt * rate)


@jit(inline="always")
def contact_temperature(model, pair, vertex, edge, edge_end, xi, point_interval):
    """The temperature (deg C) a contact law sees: the mean of the vertex point's and of the
    edge's temperature at the contact (interpolated between its points); the pair's
    initialTemperature when the pair has no heat model."""
    if not model.pair_heated[pair]:
        return model.pair_temperature[pair]
    xi = min(max(xi, 0.0), 1.0)  # a vertex beyond an end of its edge (mbds.kernel.detection.band) meets that end
    edge_temperature = (1.0 - xi) * point_interval[edge, TEMP] + xi * point_interval[edge_end, TEMP]
    return 0.5 * (point_interval[vertex, TEMP] + edge_temperature)
