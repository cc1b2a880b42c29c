"""A compiled function as numba's first-class function value, called through its address.

The address is that of the function's C wrapper, as numba itself takes it where a dispatcher is
passed for a first-class function (``numba.experimental.function_type._get_wrapper_address``;
pyproject.toml pins the numba versions this is tested with).
"""

from __future__ import annotations

from numba.core.types import WrapperAddressProtocol
from numba.experimental.function_type import _get_wrapper_address


class FunctionAddress(WrapperAddressProtocol):
    """A generated function (a numba dispatcher compiled for one signature) as numba's
    first-class function value: compiled code that receives it calls the function through its
    address. The kernel's stepper is therefore compiled once for all models (and cached with
    the kernel), not once per model."""

    def __init__(self, dispatcher):
        self.dispatcher = dispatcher  # (keeps the machine code alive)
        self._signature = dispatcher.nopython_signatures[0]
        self._address = _get_wrapper_address(dispatcher, self._signature)

    def __wrapper_address__(self) -> int:
        return self._address

    def signature(self):
        return self._signature
