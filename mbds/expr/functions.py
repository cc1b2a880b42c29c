"""The functions of the expression language, by lower-case name (names are case-insensitive)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import sympy

_MAX_EXPONENT10 = 308  # numeric results must stay within float64 range
_MAX_FACTORIAL = 171  # 171! overflows float64


@dataclass(frozen=True)
class Function:
    """A language function: how many arguments it takes and the sympy expression it builds."""

    build: Callable[..., sympy.Expr]
    arities: tuple[int, ...] = (1,)
    variadic: bool = False  # any number of arguments, at least one

    def accepts(self, count: int) -> bool:
        return count >= 1 if self.variadic else count in self.arities

    def arity_text(self) -> str:
        if self.variadic:
            return "one or more arguments"
        counts = " or ".join(str(a) for a in self.arities)
        return f"{counts} argument{'s' if self.arities != (1,) else ''}"


def power(base: sympy.Expr, exponent: sympy.Expr) -> sympy.Expr:
    """``base ** exponent``; ValueError if both are numbers and the result is beyond float64 range."""
    base, exponent = sympy.sympify(base), sympy.sympify(exponent)
    if base.is_Number and exponent.is_Number and base != 0:
        try:
            magnitude = float(exponent) * math.log10(abs(float(base)))
        except OverflowError:
            magnitude = math.inf
        if abs(magnitude) > _MAX_EXPONENT10:
            raise ValueError("number out of range")
    return sympy.Pow(base, exponent)


def factorial(x: sympy.Expr) -> sympy.Expr:
    """``x!``; ValueError if x is a number whose factorial is beyond float64 range."""
    if x.is_Number and not x < _MAX_FACTORIAL:
        raise ValueError("number out of range")
    return sympy.factorial(x)


def _arctan(*args: sympy.Expr) -> sympy.Expr:
    """ArcTan[x] = atan(x); Mathematica's ArcTan[x, y] is the angle of the point (x, y): atan2(y, x)."""
    if len(args) == 1:
        return sympy.atan(args[0])
    x, y = args
    return sympy.atan2(y, x)


def _log(*args: sympy.Expr) -> sympy.Expr:
    """Log[x] is natural; Log[b, x] is to base b (Mathematica's order)."""
    if len(args) == 1:
        return sympy.log(args[0])
    base, x = args
    return sympy.log(x, base)


FUNCTIONS: dict[str, Function] = {
    "sin": Function(sympy.sin),
    "cos": Function(sympy.cos),
    "tan": Function(sympy.tan),
    "cot": Function(sympy.cot),
    "cotan": Function(sympy.cot),
    "sec": Function(sympy.sec),
    "csc": Function(sympy.csc),
    "arcsin": Function(sympy.asin),
    "arccos": Function(sympy.acos),
    "arctan": Function(_arctan, (1, 2)),
    "arctan2": Function(sympy.atan2, (2,)),  # Pascal's ArcTan2(y, x)
    "sinh": Function(sympy.sinh),
    "cosh": Function(sympy.cosh),
    "tanh": Function(sympy.tanh),
    "arcsinh": Function(sympy.asinh),
    "arccosh": Function(sympy.acosh),
    "arctanh": Function(sympy.atanh),
    "exp": Function(sympy.exp),
    "ln": Function(sympy.log),
    "log": Function(_log, (1, 2)),
    "log10": Function(lambda x: sympy.log(x, 10)),
    "log2": Function(lambda x: sympy.log(x, 2)),
    "logn": Function(lambda base, x: sympy.log(x, base), (2,)),
    "sqr": Function(lambda x: power(x, 2)),
    "sqrt": Function(sympy.sqrt),
    "power": Function(power, (2,)),
    "abs": Function(sympy.Abs),
    "sign": Function(sympy.sign),
    "min": Function(sympy.Min, variadic=True),
    "max": Function(sympy.Max, variadic=True),
    "floor": Function(sympy.floor),
    "ceil": Function(sympy.ceiling),
    "ceiling": Function(sympy.ceiling),
}
