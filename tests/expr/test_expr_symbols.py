"""Canonical symbols and the helpers that inspect expressions."""

from __future__ import annotations

import pytest
import sympy

from mbds.expr import symbols as s
from mbds.expr.parse import parse_expression


def test_canonical_objects_are_shared():
    assert s.body_coordinate("rect", "x") == sympy.Function("b`rect`x", real=True)(s.T)
    assert s.generalized("phi") == sympy.Function("g`phi", real=True)(s.T)
    assert s.constant("g") == sympy.Symbol("c`g", real=True)
    assert s.mass_property("rect", "Jzz") == sympy.Symbol("b`rect`Jzz", real=True)
    assert parse_expression("b'rect'x[t] + c'g") == s.body_coordinate("rect", "x") + s.constant("g")


@pytest.mark.parametrize("call", [lambda: s.body_coordinate("rect", "m"), lambda: s.mass_property("rect", "x")])
def test_misnamed_objects_are_refused(call):
    with pytest.raises(ValueError):
        call()


def test_reference():
    assert s.reference(s.body_coordinate("ring", "Rz")) == s.Reference("coordinate", "Rz", "ring")
    assert s.reference(s.generalized("phi")) == s.Reference("generalized", "phi")
    assert s.reference(s.constant("lM")) == s.Reference("constant", "lM")
    assert s.reference(s.mass_property("ring", "m")) == s.Reference("mass_property", "m", "ring")
    assert s.reference(s.VREL) == s.Reference("variable", "vRel")
    assert s.reference(sympy.Symbol("x")) is None
    assert s.reference(sympy.Function("f")(s.T)) is None


def test_inspection_helpers():
    expr = parse_expression(
        "c'a b'ring'm Sin[b'ring'Rz[t]] + Derivative[1][g'phi][t]^2 b'bird'Jzz + b'stick'y'[t] temp"
    )
    assert s.coordinates_in(expr) == {
        s.body_coordinate("ring", "Rz"),
        s.generalized("phi"),
        s.body_coordinate("stick", "y"),
    }
    assert s.constants_in(expr) == {s.constant("a")}
    assert s.mass_properties_in(expr) == {s.mass_property("ring", "m"), s.mass_property("bird", "Jzz")}
    assert s.bodies_in(expr) == {"ring", "bird", "stick"}
    assert s.derivative_order(expr) == 1
    assert s.derivative_order(parse_expression("b'a'x''[t] + 1")) == 2
    assert s.derivative_order(parse_expression("c'a")) == 0


@pytest.mark.parametrize(
    "text",
    ["b'ring'Rz[t]", "Derivative[1][b'ring'Rz][t]", "Derivative[2][g'phi][t]", "g'phi[t]", "c'lM", "b'ring'Jzz"],
)
def test_display_reads_back(text):
    expr = parse_expression(text)
    assert s.display(expr) == text
    assert parse_expression(s.display(expr)) == expr
