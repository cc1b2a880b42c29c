"""The driver functions of DAP_BC's inFuncts (manual Table B.6, the book's Eqs. 8.1-8.3) as
rows of the kernel's function table (see mbds.kernel.dapbc_functions), with the coefficients
of types b and c computed as the manual states: type b has zero first and second derivatives
at t_start and t_end; type c has zero first, second and third derivatives at t_start and zero
second and third derivatives at t_end, where its first derivative is dfdt_end."""

from __future__ import annotations

import numpy as np

from mbds.errors import ModelError
from mbds.io.dapbc.records import Funct
from mbds.kernel.dapbc_functions import FUNCT_COLUMNS, FUNCT_TYPES


def coefficients(funct: Funct, index: int) -> np.ndarray:
    """(c1, c2, c3, c4) of the function: type a f = c1 + c2 t + c3 t^2; type b
    f = f_start + c1 tau^3 + c2 tau^4 + c3 tau^5; type c f = c1 + c2 tau^4 + c3 tau^5 + c4 tau^6
    (tau = t - t_start)."""
    out = np.zeros(4)
    if funct.type == "a":
        given = np.asarray(funct.coeff, float).ravel()
        if given.size > 3:
            raise ModelError(f"function {index} of type 'a' takes 3 coefficients, not {given.size}",
                             *_where(funct, "coeff"))
        out[:given.size] = given
        return out
    span = funct.t_end - funct.t_start
    if not span > 0:
        raise ModelError(f"function {index}: t_end must be later than t_start", *_where(funct, "t_end"))
    if funct.type == "b":
        rise = funct.f_end - funct.f_start
        out[:3] = 10 * rise / span ** 3, -15 * rise / span ** 4, 6 * rise / span ** 5
        return out
    lhs = np.array([[4 * span ** 3, 5 * span ** 4, 6 * span ** 5],
                    [12 * span ** 2, 20 * span ** 3, 30 * span ** 4],
                    [24 * span, 60 * span ** 2, 120 * span ** 3]])
    out[0] = funct.f_start
    out[1:] = np.linalg.solve(lhs, [funct.dfdt_end, 0.0, 0.0])
    return out


def _where(funct: Funct, name: str) -> tuple:
    pos = funct.where(name)
    return (pos.file, pos.line) if pos is not None else ()


def funct_table(functs: list[Funct]) -> np.ndarray:
    """(nFunct, FUNCT_COLUMNS): type code, t_start, f_start, t_end, f_end, c1..c4."""
    table = np.zeros((len(functs), FUNCT_COLUMNS))
    for row, funct in enumerate(functs):
        table[row, :5] = FUNCT_TYPES[funct.type], funct.t_start, funct.f_start, funct.t_end, funct.f_end
        table[row, 5:] = coefficients(funct, row + 1)
    return table
