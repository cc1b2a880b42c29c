"""A small deterministic random number generator whose whole state is one uint64 array.

SplitMix64: the state advances by a fixed odd increment and each output is a mixed copy of it.
Keeping the state in an array (not numba's global generator) makes a run reproducible bit for
bit, resumable from a saved state, and independent of anything else that draws numbers.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit

_INCREMENT = np.uint64(0x9E3779B97F4A7C15)
_MIX1 = np.uint64(0xBF58476D1CE4E5B9)
_MIX2 = np.uint64(0x94D049BB133111EB)


@jit(refcount=False)
def next_uint64(state):
    """The next 64-bit output; advances ``state`` (uint64 array of length 1)."""
    state[0] += _INCREMENT
    z = state[0]
    z = (z ^ (z >> np.uint64(30))) * _MIX1
    z = (z ^ (z >> np.uint64(27))) * _MIX2
    return z ^ (z >> np.uint64(31))


@jit(refcount=False)
def uniform(state, low, high):
    """A float64 uniformly distributed in [low, high) (53 random bits)."""
    bits = next_uint64(state) >> np.uint64(11)
    return low + (high - low) * (float(bits) * (1.0 / 9007199254740992.0))


def seeded_state(seed: int) -> np.ndarray:
    """The generator state for a non-negative integer seed."""
    return np.array([seed % 2**64], dtype=np.uint64)
