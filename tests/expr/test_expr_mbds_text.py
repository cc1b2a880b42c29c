"""The MBDS text printer: what it prints reads back as the same expression."""

import pytest
import sympy

from mbds.expr import symbols as S
from mbds.expr.parse import parse_expression
from mbds.expr.printer import mbds_text

TEXTS = [
    "-(c'lM*Cos[b'ring'Rz[t]]*Derivative[1][b'ring'Rz][t]^2)-c'lG*Sin[b'bird'Rz[t]]*Derivative[2][b'bird'Rz][t]",
    "c'a^(1/2) + ArcTan[c'a, c'b] + Exp[-c'a] + Log[c'a] + Abs[c'a] + Pi*c'a^-2 - c'a/2 + (c'a+c'b)^3",
    "1.5e-7*c'a/(c'b+2) + 1e-300 + 123456789.125 + Max[c'a, c'b] + g'phi[t]*Derivative[1][g'phi][t]",
    "c'amplitude*c'omega^2*Sin[c'omega*t] + Sqrt[b'ball1'm] + b'ball1'Jzz",
]


@pytest.mark.parametrize("text", TEXTS)
def test_printed_text_reads_back_as_the_same_expression(text):
    expr = parse_expression(text)
    assert parse_expression(mbds_text(expr)) == expr


def test_names_are_spelled_as_in_model_files():
    expr = S.constant("g") * S.mass_property("b1", "m") * sympy.Derivative(S.body_coordinate("b1", "y"), S.T)
    assert mbds_text(expr) == "b'b1'm*c'g*Derivative[1][b'b1'y][t]"


def test_a_name_outside_the_language_is_refused():
    with pytest.raises(ValueError, match="not a name"):
        mbds_text(sympy.Symbol("k") * S.constant("g"))
    with pytest.raises(ValueError, match="not a coordinate"):
        mbds_text(sympy.Function("f")(S.T))
