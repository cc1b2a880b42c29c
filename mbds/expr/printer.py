"""Print sympy expressions as Python source that numba compiles.

Functions come from ``math`` (``numpy`` for floor and ceiling, whose ``math`` versions return
integers in numba), numbers are printed so that they read back as the same float64.
"""

from __future__ import annotations

import math

import sympy
from sympy.printing.pycode import PythonCodePrinter

_EXACT_INTEGER = 2**53


def float_literal(value: float) -> str:
    """Shortest Python text of ``value`` that reads back exactly; inf and nan via ``math``."""
    if math.isnan(value):
        return "math.nan"
    if math.isinf(value):
        return "math.inf" if value > 0 else "(-math.inf)"
    return repr(value)


class NumbaPrinter(PythonCodePrinter):
    """Python code printer for numba; raises on anything it cannot print."""

    def __init__(self):
        super().__init__({"strict": True, "standard": "python3"})

    def _print_Float(self, expr: sympy.Float) -> str:
        return float_literal(float(expr))

    def _print_Integer(self, expr: sympy.Integer) -> str:
        value = int(expr)
        return str(value) if abs(value) < _EXACT_INTEGER else float_literal(float(value))

    def _print_Rational(self, expr: sympy.Rational) -> str:
        return float_literal(expr.p / expr.q)

    def _print_factorial(self, expr: sympy.factorial) -> str:
        return f"math.gamma({self._print(expr.args[0])} + 1)"

    def _print_floor(self, expr: sympy.floor) -> str:
        return f"np.floor({self._print(expr.args[0])})"

    def _print_ceiling(self, expr: sympy.ceiling) -> str:
        return f"np.ceil({self._print(expr.args[0])})"
