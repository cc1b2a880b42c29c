"""The canonical sympy objects of the expression language, and helpers to inspect them.

Names follow Mathematica's contexts with backquotes: a body coordinate is the function
``b`body`coord`` applied to ``t``, a free generalized coordinate is ``g`name`` applied to ``t``,
a constant is the symbol ``c`name`` and a mass property is the symbol ``b`body`prop``.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy
from sympy.core.function import AppliedUndef

T = sympy.Symbol("t", real=True)
"""Time (s)."""
TEMP = sympy.Symbol("temp", real=True)
"""Contact temperature (°C), a variable of contact-property functions."""
VREL = sympy.Symbol("vRel", real=True)
"""Absolute relative tangential velocity at a contact (m/s), a variable of contact-property functions."""

COORDINATES = ("x", "y", "z", "Rx", "Ry", "Rz")
MASS_PROPERTIES = ("m", "Jzz")


def body_coordinate(body: str, coord: str) -> sympy.Expr:
    """Coordinate ``coord`` (one of :data:`COORDINATES`) of body ``body`` as a function of time."""
    if coord not in COORDINATES:
        raise ValueError(f"unknown body coordinate {coord!r}")
    return sympy.Function(f"b`{body}`{coord}", real=True)(T)


def generalized(name: str) -> sympy.Expr:
    """Free generalized coordinate ``g`name`` as a function of time."""
    return sympy.Function(f"g`{name}", real=True)(T)


def constant(name: str) -> sympy.Symbol:
    """Constant ``c`name``."""
    return sympy.Symbol(f"c`{name}", real=True)


def mass_property(body: str, prop: str) -> sympy.Symbol:
    """Mass property ``prop`` (one of :data:`MASS_PROPERTIES`) of body ``body``."""
    if prop not in MASS_PROPERTIES:
        raise ValueError(f"unknown mass property {prop!r}")
    return sympy.Symbol(f"b`{body}`{prop}", real=True)


@dataclass(frozen=True)
class Reference:
    """What a language object refers to.

    ``kind`` is ``"coordinate"`` (body coordinate), ``"generalized"``, ``"constant"``,
    ``"mass_property"`` or ``"variable"`` (t, temp, vRel); ``body`` is set for the body kinds;
    ``name`` is the coordinate, generalized name, constant name, property or variable name.
    """

    kind: str
    name: str
    body: str | None = None


def reference(obj: sympy.Basic) -> Reference | None:
    """Classify a symbol or an applied coordinate function; None for anything else."""
    if obj in (T, TEMP, VREL):
        return Reference("variable", obj.name)
    if isinstance(obj, AppliedUndef) and obj.args == (T,):
        context, *names = obj.func.__name__.split("`")
        if context == "b" and len(names) == 2 and names[1] in COORDINATES:
            return Reference("coordinate", names[1], names[0])
        if context == "g" and len(names) == 1:
            return Reference("generalized", names[0])
    elif isinstance(obj, sympy.Symbol):
        context, *names = obj.name.split("`")
        if context == "b" and len(names) == 2 and names[1] in MASS_PROPERTIES:
            return Reference("mass_property", names[1], names[0])
        if context == "c" and len(names) == 1:
            return Reference("constant", names[0])
    return None


def coordinates_in(expr: sympy.Basic) -> set[sympy.Expr]:
    """Body and generalized coordinates (as functions of t) that ``expr`` uses, derivatives included."""
    return {f for f in expr.atoms(AppliedUndef) if reference(f) is not None}


def constants_in(expr: sympy.Basic) -> set[sympy.Symbol]:
    """Constant symbols in ``expr``."""
    return {s for s in expr.free_symbols if _kind(s) == "constant"}


def mass_properties_in(expr: sympy.Basic) -> set[sympy.Symbol]:
    """Mass-property symbols in ``expr``."""
    return {s for s in expr.free_symbols if _kind(s) == "mass_property"}


def bodies_in(expr: sympy.Basic) -> set[str]:
    """Names of the bodies whose coordinates or mass properties ``expr`` uses."""
    refs = (reference(obj) for obj in expr.free_symbols | expr.atoms(AppliedUndef))
    return {ref.body for ref in refs if ref is not None and ref.body is not None}


def derivative_order(expr: sympy.Basic) -> int:
    """Highest time-derivative order of a coordinate in ``expr`` (0 when none is differentiated)."""
    orders = [d.derivative_count for d in expr.atoms(sympy.Derivative)]
    return max(orders, default=0)


def display(obj: sympy.Basic) -> str:
    """MBDS spelling of a coordinate, a derivative of one, a constant or a mass property.

    Uses apostrophes as context quotes, as MBDS files usually do: ``b'rect'x[t]``,
    ``Derivative[1][b'rect'x][t]``, ``c'gravity``, ``b'rect'm``. Other objects print as sympy does.
    """
    if isinstance(obj, sympy.Derivative) and isinstance(obj.expr, AppliedUndef):
        return f"Derivative[{obj.derivative_count}][{display(obj.expr).removesuffix('[t]')}][t]"
    ref = reference(obj)
    if ref is None or ref.kind == "variable":
        return str(obj)
    if ref.kind == "coordinate":
        return f"b'{ref.body}'{ref.name}[t]"
    if ref.kind == "mass_property":
        return f"b'{ref.body}'{ref.name}"
    if ref.kind == "generalized":
        return f"g'{ref.name}[t]"
    return f"c'{ref.name}"


def _kind(obj: sympy.Basic) -> str | None:
    ref = reference(obj)
    return None if ref is None else ref.kind
