"""Parsing MBDS expressions to sympy."""

from __future__ import annotations

import re

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from mbds.errors import ModelError
from mbds.expr.parse import parse_expression
from mbds.expr.symbols import (
    TEMP,
    VREL,
    T,
    body_coordinate,
    constant,
    generalized,
    mass_property,
)


def D(f: sympy.Expr, order: int = 1) -> sympy.Expr:
    return sympy.Derivative(f, (T, order))


c = constant
rz = {body: body_coordinate(body, "Rz") for body in ("rect", "ring", "bird", "mass1")}
rod_x = body_coordinate("rod", "x")
m1 = mass_property("mass1", "m")

# Expressions of the manual (chapters 2 and 3), written with apostrophes as context quotes.
MANUAL = [
    ("-(c'gravity*b'mass1'm)", -c("gravity") * m1),
    (
        "(b'mass1'm*(Derivative[1][b'mass1'x][t]^2+Derivative[1][b'mass1'y][t]^2))/2",
        m1 * (D(body_coordinate("mass1", "x")) ** 2 + D(body_coordinate("mass1", "y")) ** 2) / 2,
    ),
    ("c'force1y + c'gravityz b'rect'm", c("force1y") + c("gravityz") * mass_property("rect", "m")),
    (
        "c'force1x (c'j1y Cos[b'rect'Rz[t]] - c'j1x Sin[Derivative[1][b'rod'x][t]])",
        c("force1x") * (c("j1y") * sympy.cos(rz["rect"]) - c("j1x") * sympy.sin(D(rod_x))),
    ),
    ("0.5-1/vRel", sympy.Float(0.5) - 1 / VREL),
    ("0.5 - 1/temp", sympy.Float(0.5) - 1 / TEMP),
    ("-(c'lM* Sin[b'ring'Rz[t]])", -c("lM") * sympy.sin(rz["ring"])),
    (
        "-(c'lG*Cos[b'bird'Rz[t]]*Derivative[1][b'bird'Rz][t]^2)",
        -c("lG") * sympy.cos(rz["bird"]) * D(rz["bird"]) ** 2,
    ),
    (
        "c'lG*Cos[b'bird'Rz[t]]+c'lM*Cos[b'ring'Rz[t]]",
        c("lG") * sympy.cos(rz["bird"]) + c("lM") * sympy.cos(rz["ring"]),
    ),
    ("c'lG + c'lM", c("lG") + c("lM")),
    ("b'mass1'x[t]", body_coordinate("mass1", "x")),
    ("b'mass1'Rz[t]", rz["mass1"]),
    ("b'rect'Jzz", mass_property("rect", "Jzz")),
    ("g'relative1[t]", generalized("relative1")),
    ("b'rod'x'[t]", D(rod_x)),
    ("b'rect'x", body_coordinate("rect", "x")),
    ("Sin[1*t]", sympy.sin(T)),
    ("sin(b'rect'x)", sympy.sin(body_coordinate("rect", "x"))),
    ("9.81", sympy.Float(9.81)),
    ("1e-10", sympy.Float(1e-10)),
]

# Quote styles: as written, backquotes only, typographic quotes, and a mix within one name.
QUOTE_STYLES = {
    "apostrophe": str.maketrans({}),
    "backquote": str.maketrans({"'": "`"}),
    "typographic": str.maketrans({"'": "’"}),
}


@pytest.mark.parametrize("style", QUOTE_STYLES)
@pytest.mark.parametrize(("text", "expected"), MANUAL, ids=[text for text, _ in MANUAL])
def test_manual_examples(text, expected, style):
    assert parse_expression(text.translate(QUOTE_STYLES[style])) == expected


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("b'mass1`Rz[t]", rz["mass1"]),
        ("b‘bird’Rz[t]", rz["bird"]),
        ("b`rod`x'[t]", D(rod_x)),
        ("b'rod'x''[t]", D(rod_x, 2)),
        ('b\'rod\'x"[t]', D(rod_x, 2)),
        ("b'rod'x'", D(rod_x)),
        ("b'rod'x [t]", rod_x),
        ("Derivative[2][b'rod'x][t]", D(rod_x, 2)),
        ("Derivative[1][b'rod'x]", D(rod_x)),
        ("Derivative[0][b'rod'x][t]", rod_x),
        ("Derivative[1][b'rod'x'][t]", D(rod_x, 2)),
        ("g'phi'[t]", D(generalized("phi"))),
        ("Derivative[1][g`phi][t]", D(generalized("phi"))),
        ("g'phi''[t]", D(generalized("phi"), 2)),
        ("b'wheel_2'Ry[t]", body_coordinate("wheel_2", "Ry")),
        ("c'a1_b", constant("a1_b")),
        ("c'a", constant("a")),
    ],
)
def test_references_and_derivatives(text, expected):
    assert parse_expression(text) == expected


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("arcsinh(1)", sympy.asinh(1)),
        ("log10(1000)", 3),
        ("ln(E^2)", 2),
        ("logN(2, 8)", 3),
        ("Log[2, 8]", 3),
        ("Log[E]", 1),
        ("log2(32)", 5),
        ("sqr(3)", 9),
        ("abs(-2)", 2),
        ("exp(1)", sympy.E),
        ("Sqrt[16]", 4),
        ("Power[2, 10]", 1024),
        ("3!", 6),
        ("2^3^2", 512),
        ("-2^2", -4),
        ("2^-1", sympy.Rational(1, 2)),
        ("2^-1*3", sympy.Rational(3, 2)),
        ("2^3!", 64),
        ("-3!", -6),
        ("2 3", 6),
        ("2(1+2)", 6),
        ("(1+2)(3+4)", 21),
        ("2 -3", -1),
        ("6/2 3", 9),
        ("6/2/3", 1),
        ("1 - 2 - 3", -4),
        ("--2", 2),
        ("2*-3", -6),
        ("ArcTan[1, 1]", sympy.pi / 4),
        ("ArcTan[-1, 0]", sympy.pi),
        ("arctan2(1, -1)", 3 * sympy.pi / 4),
        ("ARCTAN(1)", sympy.pi / 4),
        ("Min[3, 1, 2]", 1),
        ("max(3, 1, 2)", 3),
        ("Sign[-2.5]", -1),
        ("Floor[2.5] + Ceil[2.5]", 5),
        ("Cot[Pi/4] + Sec[0] + Csc[Pi/2]", 3),
        ("Sinh[0] + Cosh[0] + Tanh[0] + ArcCosh[1] + ArcTanh[0]", 1),
        ("ArcSin[1] + ArcCos[1]", sympy.pi / 2),
        ("Cos[Pi] + Sin[pi] + Tan[0]", -1),
        ("1.5*^-7", sympy.Float(1.5e-7)),
        ("1.5E+3", 1500),
        (".5", sympy.Float(0.5)),
        ("1.", 1),
        ("2e3", 2000),
        ("2E", 2 * sympy.E),
    ],
)
def test_numeric_values(text, value):
    result = parse_expression(text)
    assert result.is_number
    assert abs(complex(result.evalf(30) - sympy.sympify(value).evalf(30))) < 1e-14


def test_precedence_and_implicit_multiplication():
    a, b, x = c("a"), c("b"), body_coordinate("r", "x")
    assert parse_expression("c'a (1 + c'b)") == a * (1 + b)
    assert parse_expression("c'a c'b^2") == a * b**2
    assert parse_expression("-c'a^2") == -(a**2)
    assert parse_expression("c'a/c'b c'a") == a**2 / b
    assert parse_expression("c'a!^2") == sympy.factorial(a) ** 2
    assert parse_expression("2 c'a Sin[b'r'x[t]]") == 2 * a * sympy.sin(x)
    assert parse_expression("c'a-c'b") == a - b
    assert parse_expression("t temp vRel Pi E") == T * TEMP * VREL * sympy.pi * sympy.E


def test_decimal_comma():
    assert parse_expression("0,5", decimal_separator=",") == sympy.Float(0.5)
    assert parse_expression("Max[0,5; 1,5; c'a]", decimal_separator=",") == sympy.Max(sympy.Float(1.5), c("a"))
    assert parse_expression("logN(2; 8)", decimal_separator=",") == 3


def test_floats_keep_full_precision():
    assert float(parse_expression("0.1")) == 0.1
    assert float(parse_expression("3.141592653589793")) == 3.141592653589793


ERRORS = [
    ("", "empty expression", None),
    ("   ", "empty expression", None),
    ("(1 + 2", "expected ')' to close '(' at column 1, found end of expression", 7),
    ("1 + 2)", "unexpected ')'", 6),
    ("Sin[1)", "expected ']' to close '['", 6),
    ("foo + 1", "unknown identifier 'foo'", 1),
    ("2 Foo[1]", "unknown function 'Foo'", 3),
    ("1 +", "unexpected end of expression", 4),
    ("Sin 2", "function 'Sin' needs its arguments", 1),
    ("Sin[1, 2]", "Sin takes 1 argument, not 2", 1),
    ("Sin[]", "unexpected ']'", 5),
    ("b'rect'q[t]", "unknown body coordinate or property 'q'", 1),
    ("b'rect[t]", "expected a quote and a coordinate or property after b'rect", 7),
    ("c'", "missing constant name", 3),
    ("c'a'", "unexpected quote after c'a", 4),
    ("x'", "unexpected quote after 'x'", 2),
    ("'a", "unexpected quote", 1),
    ("b'r'x[s]", "expected t in '[t]'", 7),
    ("b'r'x'''[t]", "derivatives above the second are not supported", 1),
    ("Derivative[1][c'a][t]", "expected a coordinate", 15),
    ("Derivative[x][b'r'x][t]", "expected a whole number", 12),
    ("1 # 2", "unexpected character '#'", 3),
    ("1.5.2", "malformed number", 1),
    ("0,5", "unexpected ','", 2),
    ("3!!", "double factorial", 2),
    ("1/0", "no finite value", None),
    ("Log[0]", "no finite value", None),
    ("(-1)^0.5", "complex value", None),
    ("10^400", "number out of range", 1),
    ("1e400", "out of range", 1),
    ("200!", "number out of range", 1),
    ("(" * 150 + "1" + ")" * 150, "nested too deeply", None),
]


@pytest.mark.parametrize(("text", "message", "column"), ERRORS, ids=[text[:20] for text, _, _ in ERRORS])
def test_errors_are_located(text, message, column):
    with pytest.raises(ModelError) as caught:
        parse_expression(text, file="model.hv", line=7)
    error = caught.value
    assert str(error).startswith("model.hv:7: ")
    assert message in error.message
    if column is not None:
        assert re.search(rf"at column {column}\b", error.message)


def test_comma_decimal_rejects_point():
    with pytest.raises(ModelError, match="unexpected character '.'.*decimal separator is ','"):
        parse_expression("1.5", decimal_separator=",")


def test_bad_decimal_separator():
    with pytest.raises(ModelError, match="decimal separator"):
        parse_expression("1", decimal_separator=";")


# -- robustness: random and mutated text gives a result or a ModelError, nothing else ----------

VALID = [text for text, _ in MANUAL] + [
    "ArcTan[b'r'x[t], g'a[t]] + logN(2, c'a)^-2 3!",
    "Power[Sqrt[c'a], 1.5*^-7] / (Max[1, 2, temp] - Sign[vRel])",
    "Derivative[2][b'r'Rz][t] Floor[c'b] + sqr(b'r'y''[t])",
]
ALPHABET = [*"bcgt'`‘\"[]()+-*/^!,;. 0123456789eExyzRJmD_$", "Sin", "Derivative", "Log", "Pi", "vRel", "^^", "*^"]


def _check(text: str) -> None:
    try:
        result = parse_expression(text, file="f.hv", line=2)
    except ModelError as error:
        assert str(error).startswith("f.hv:2: ")
    else:
        assert isinstance(result, sympy.Expr)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(ALPHABET), max_size=40).map("".join))
def test_random_tokens(text):
    _check(text)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=60))
def test_random_text(text):
    _check(text)


@settings(max_examples=400, deadline=None)
@given(
    st.sampled_from(VALID),
    st.lists(
        st.tuples(st.integers(0, 200), st.sampled_from(["delete", "insert", "replace"]), st.sampled_from(ALPHABET)),
        min_size=1,
        max_size=4,
    ),
)
def test_mutated_expressions(text, mutations):
    for position, kind, piece in mutations:
        i = position % (len(text) + 1)
        if kind == "delete":
            text = text[:i] + text[i + 1 :]
        elif kind == "insert":
            text = text[:i] + piece + text[i:]
        else:
            text = text[:i] + piece + text[i + len(piece) :]
    _check(text)
