"""Print sympy expressions: as Python source that numba compiles, and as MBDS model-file text.

:class:`NumbaPrinter`: functions come from ``math`` (``numpy`` for floor and ceiling, whose
``math`` versions return integers in numba). :func:`mbds_text`: the manual's Mathematica-like
syntax (``Sin[b'ring'Rz[t]]``, ``Derivative[1][b'ring'Rz][t]^2``) that
:func:`mbds.expr.parse.parse_expression` reads back. Numbers are printed so that they read back
as the same float64.
"""

from __future__ import annotations

import math

import sympy
from sympy.core.function import AppliedUndef
from sympy.printing.mathematica import MCodePrinter
from sympy.printing.pycode import PythonCodePrinter

from mbds.expr.symbols import display, reference

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


class MbdsPrinter(MCodePrinter):
    """Mathematica-syntax printer with MBDS names: coordinates, their time derivatives,
    constants and mass properties are spelled as in the model files (:func:`display`)."""

    def __init__(self):
        super().__init__({"strict": True})

    def _print_Symbol(self, expr: sympy.Symbol) -> str:
        ref = reference(expr)
        if ref is None:
            raise ValueError(f"{expr} is not a name of the MBDS expression language")
        return display(expr)

    def _print_Function(self, expr: sympy.Expr) -> str:
        if isinstance(expr, AppliedUndef):
            if reference(expr) is None:
                raise ValueError(f"{expr} is not a coordinate of the MBDS expression language")
            return display(expr)
        return super()._print_Function(expr)

    def _print_Derivative(self, expr: sympy.Derivative) -> str:
        if not isinstance(expr.expr, AppliedUndef) or reference(expr.expr) is None:
            raise ValueError(f"only coordinates can be differentiated in MBDS files, not {expr.expr}")
        return display(expr)

    def _print_Float(self, expr: sympy.Float) -> str:
        return repr(float(expr))


def mbds_text(expr: sympy.Expr) -> str:
    """``expr`` in the syntax of MBDS model files; ValueError for a name the language lacks."""
    return MbdsPrinter().doprint(sympy.sympify(expr))
