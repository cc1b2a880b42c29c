"""A model's generated functions, called from kernels compiled once for all models.

The functions of a model (mbds.expr.codegen, mbds.expr.dapbc_codegen) are compiled per model;
the stepper and the DAP_BC analyses that call them are compiled once and cached with the kernel.
The caller passes a table, int64 (k, 2): per function the address of its C wrapper and of its
native entry, in a fixed order. Inside compiled code, an accessor made by :func:`function_at`
turns row i of the table into numba's first-class function value of the row's signature; a call
of it goes to the native entry. The table is a plain array: passing it costs nothing, where
numba's own first-class function objects cost several microseconds each to pass from Python on
every call.

The table must match the signatures the kernel expects (:func:`address_table` checks it), and
the functions must stay alive while compiled code may call them.
"""

from __future__ import annotations

import numpy as np
from numba import types
from numba.core import cgutils
from numba.core.sigutils import normalize_signature
from numba.experimental.function_type import _get_jit_address, _get_wrapper_address
from numba.extending import intrinsic


def signature_of(text: str) -> types.Signature:
    """numba's signature of a signature string such as ``"float64(float64[::1], int64)"``."""
    args, return_type = normalize_signature(text)
    return return_type(*args)


def function_at(signature: str):
    """An accessor ``at(table, i)``, callable from compiled code: row i of a function table as a
    function of ``signature`` (a signature string)."""
    function_type = types.FunctionType(signature_of(signature))

    @intrinsic
    def at(typingctx, table, row):
        def codegen(context, builder, sig, args):
            array = context.make_array(sig.args[0])(context, builder, args[0])

            def entry(column):
                index = [args[1], context.get_constant(types.intp, column)]
                address = builder.load(cgutils.get_item_pointer(context, builder, sig.args[0], array, index))
                return builder.inttoptr(address, context.get_value_type(types.voidptr))

            value = cgutils.create_struct_proxy(function_type)(context, builder)
            value.c_addr = entry(0)
            value.jit_addr = entry(1)
            value.py_addr = cgutils.get_null_value(context.get_value_type(types.voidptr))
            return value._getvalue()

        return function_type(table, row), codegen

    return at


def address_table(functions, signatures: dict[str, str]) -> np.ndarray:
    """The table (int64, (k, 2)) of the numba dispatchers named by ``signatures`` (name:
    signature string, in the table's order), attributes of ``functions`` (a module, say), each
    compiled for its signature; raises TypeError for a dispatcher without it."""
    table = np.zeros((len(signatures), 2), np.int64)
    for row, (name, text) in enumerate(signatures.items()):
        dispatcher = getattr(functions, name)
        signature = signature_of(text)
        if signature not in dispatcher.nopython_signatures:
            raise TypeError(f"{dispatcher.__name__} is not compiled for {signature}")
        table[row] = _get_wrapper_address(dispatcher, signature), _get_jit_address(dispatcher, signature)
    return table
