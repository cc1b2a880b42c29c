"""Generated numba functions against sympy's own evaluation of the same expressions."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import expr_models
import numba
import numpy as np
import pytest
import sympy

from mbds.errors import ModelError
from mbds.expr.codegen import (
    DependentCoordinate,
    ModelExpressions,
    compile_model,
    generate_source,
)
from mbds.expr.parse import parse_expression
from mbds.kernel.layout import MODEL_FUNCTIONS
from mbds.expr.symbols import TEMP, VREL, T, body_coordinate, constant

DIGITS = 30
NEEDS_JIT = pytest.mark.skipif(numba.config.DISABLE_JIT, reason="compiled semantics (IEEE division, signatures)")


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    expressions = expr_models.expressions()
    return expressions, compile_model(expressions, cache_dir=tmp_path_factory.mktemp("models"))


class Reference:
    """Evaluates a model's expressions by substitution in sympy at high precision."""

    def __init__(self, x: ModelExpressions, q, qd, qdd, t, p):
        exact = lambda v: sympy.Float(float(v), DIGITS)  # noqa: E731
        self.values = {T: exact(t)}
        for k, coordinate in enumerate(x.coordinates):
            self.values[sympy.Derivative(coordinate, (T, 2))] = exact(qdd[k])
            self.values[sympy.Derivative(coordinate, T)] = exact(qd[k])
            self.values[coordinate] = exact(q[k])
        self.values.update({parameter: exact(v) for parameter, v in zip(x.parameters, p, strict=True)})
        for coordinate, value in x.fixed.items():
            self.values[coordinate] = value.xreplace(self.values)
            self.values[sympy.Derivative(coordinate, T)] = 0
        # Dependent coordinates by their own expressions (repeated: they may use each other).
        self.dependent = {}
        for d in x.dependent:
            self.dependent[d.coordinate] = d.position
            self.dependent[sympy.Derivative(d.coordinate, T)] = d.velocity
            self.dependent[sympy.Derivative(d.coordinate, (T, 2))] = d.acceleration

    def __call__(self, expr, **variables) -> float:
        expr = sympy.sympify(expr)
        for _ in range(len(self.dependent) + 1):
            expr = expr.xreplace(self.dependent)
        expr = expr.xreplace(self.values).xreplace({TEMP: variables.get("temp", 0), VREL: variables.get("vrel", 0)})
        return float(expr.evalf(DIGITS))


def random_state(rng, x: ModelExpressions):
    n = len(x.coordinates)
    return (
        rng.uniform(-2, 2, n),
        rng.uniform(-3, 3, n),
        rng.uniform(-5, 5, n),
        float(rng.uniform(0, 10)),
        rng.uniform(0.1, 2.0, len(x.parameters)),
    )


def assert_close(actual, expected):
    expected = np.asarray(expected, dtype=float)
    scale = max(1.0, float(np.max(np.abs(expected)))) if expected.size else 1.0
    np.testing.assert_allclose(actual, expected, rtol=1e-12, atol=1e-13 * scale)


def evaluate(compiled, q, qd, qdd, t, p):
    n, m = compiled.n, compiled.m
    mass, h = np.empty((n, n)), np.empty(n)
    pos, vel, acc, jac, scalar = np.empty(m), np.empty(m), np.empty(m), np.empty((m, n)), np.empty(m)
    compiled.mass_matrix(q, t, p, mass)
    compiled.h_vector(q, qd, t, p, h)
    compiled.dependent_state(q, qd, qdd, t, p, pos, vel, acc)
    compiled.dependent_jacobian(q, qd, t, p, jac, scalar)
    energy = compiled.mechanical_energy(q, qd, t, p)
    return mass, h, pos, vel, acc, jac, scalar, energy


@pytest.mark.parametrize("seed", range(8))
def test_functions_match_sympy(model, seed):
    x, compiled = model
    q, qd, qdd, t, p = random_state(np.random.default_rng(seed), x)
    ref = Reference(x, q, qd, qdd, t, p)
    mass, h, pos, vel, acc, jac, scalar, energy = evaluate(compiled, q, qd, qdd, t, p)
    assert_close(mass, [[ref(e) for e in row] for row in x.mass_matrix])
    assert_close(h, [ref(e) for e in x.h_vector])
    assert_close(pos, [ref(d.position) for d in x.dependent])
    assert_close(vel, [ref(d.velocity) for d in x.dependent])
    assert_close(acc, [ref(d.acceleration) for d in x.dependent])
    assert_close(jac, [[ref(e) for e in d.jacobian] for d in x.dependent])
    assert_close(scalar, [ref(d.jacobian_scalar) for d in x.dependent])
    assert_close(energy, ref(x.mechanical_energy))
    # The test model is consistent: acceleration = J qdd + j.
    assert_close(acc, jac @ qdd + scalar)


@pytest.mark.parametrize("seed", range(4))
def test_contact_laws_match_sympy(model, seed):
    x, compiled = model
    rng = np.random.default_rng(100 + seed)
    *_, p = random_state(rng, x)
    ref = Reference(x, *random_state(rng, x)[:4], p)
    out = np.empty(4)
    for k, law in enumerate(x.contact_laws):
        vrel, temp = rng.uniform(0.01, 5), rng.uniform(0.5, 300)
        compiled.contact_law(k, vrel, temp, p, out)
        assert_close(out, [ref(e, vrel=vrel, temp=temp) for e in law])


@NEEDS_JIT
def test_contact_law_non_finite_values_are_visible(model):
    _, compiled = model
    p = np.ones(compiled.n_parameters)
    out = np.zeros(4)
    compiled.contact_law(0, 0.0, 0.0, p, out)  # 0.5 - 1/vRel at vRel = 0
    assert not np.isfinite(out[0]) and not np.isfinite(out[1])
    assert out[2:].tolist() == [0.5, 0.0]
    compiled.contact_law(compiled.n_contact_laws, 1.0, 1.0, p, out)
    assert np.isnan(out).all()


def test_sizes(model):
    x, compiled = model
    assert (compiled.n, compiled.m, compiled.n_contact_laws, compiled.n_parameters) == (3, 2, 2, len(x.parameters))
    assert compiled.source_path.name == f"mbds_model_{compiled.source_hash}.py"


def test_new_parameters_reuse_the_compiled_code(model, tmp_path):
    x, compiled = model
    again = compile_model(expr_models.expressions(), cache_dir=compiled.source_path.parent)
    assert again.source_hash == compiled.source_hash
    assert again.mass_matrix is compiled.mass_matrix
    rng = np.random.default_rng(7)
    q, qd, qdd, t, p = random_state(rng, x)
    first = compiled.mechanical_energy(q, qd, t, p)
    p2 = p * 1.5
    second = again.mechanical_energy(q, qd, t, p2)
    assert second != first
    assert_close(second, Reference(x, q, qd, qdd, t, p2)(x.mechanical_energy))


@NEEDS_JIT
def test_each_function_has_its_one_signature(model):
    _, compiled = model
    for name, dispatcher in compiled.dispatchers().items():
        assert [str(sig) for sig in dispatcher.signatures] == [_canonical(MODEL_FUNCTIONS[name])]


def _canonical(signature: str) -> str:
    """numba's spelling of an argument tuple: '(array(float64, 1d, C), float64, ...)'."""
    return str(numba.core.sigutils.normalize_signature(signature)[0])


def test_source_ignores_parameter_values_and_hash_seed(tmp_path):
    """The text depends only on structure: identical across processes with different hash seeds."""
    code = (
        "import expr_models, sys; from mbds.expr.codegen import generate_source; "
        "sys.stdout.write(generate_source(expr_models.expressions()))"
    )
    outputs = []
    for seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": seed, "PYTHONPATH": _python_path()}
        done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
        outputs.append(done.stdout)
    assert outputs[0] == outputs[1] == generate_source(expr_models.expressions())
    assert outputs[0].startswith("# Generated by mbds")


def _python_path() -> str:
    return os.pathsep.join([str(Path(__file__).parent), *sys.path])


# -- a model where dependent coordinates use each other -------------------------------------


def chain_model(**overrides) -> ModelExpressions:
    """q = (a x); b x = 2 a x + c t; c x = b x^2 (declared first)."""
    parse = parse_expression
    ax, bx, cx = (body_coordinate(b, "x") for b in "abc")
    dc = DependentCoordinate(
        coordinate=cx,
        position=parse("b'b'x[t]^2"),
        velocity=parse("2 b'b'x[t] b'b'x'[t]"),
        acceleration=parse("2 b'b'x'[t]^2 + 2 b'b'x[t] b'b'x''[t]"),
        jacobian=[parse("4 b'b'x[t]")],
        jacobian_scalar=parse("2 b'b'x'[t]^2"),
    )
    db = DependentCoordinate(
        coordinate=bx,
        position=parse("2 b'a'x[t] + c'c t"),
        velocity=parse("2 b'a'x'[t] + c'c"),
        acceleration=parse("2 b'a'x''[t]"),
        jacobian=[sympy.Integer(2)],
        jacobian_scalar=sympy.Integer(0),
    )
    fields = dict(
        coordinates=[ax],
        parameters=[constant("c"), constant("m")],
        fixed={body_coordinate("a", "y"): constant("c") * 3},
        dependent=[dc, db],
        mass_matrix=[[parse("c'm (1 + b'c'x[t]^2) + b'a'y[t]")]],
        h_vector=[parse("-c'm b'c'x'[t] b'b'x[t] + Derivative[1][b'a'y][t]")],
        mechanical_energy=parse("c'm b'c'x'[t]^2/2 + t"),
        contact_laws=[],
    )
    fields.update(overrides)
    return ModelExpressions(**fields)


def test_dependent_coordinates_using_each_other(tmp_path):
    x = chain_model()
    compiled = compile_model(x, cache_dir=tmp_path)
    q, qd, qdd, t, p = np.array([0.7]), np.array([-1.3]), np.array([0.4]), 2.5, np.array([0.3, 1.7])
    ref = Reference(x, q, qd, qdd, t, p)
    mass, h, pos, vel, acc, jac, scalar, energy = evaluate(compiled, q, qd, qdd, t, p)
    b = 2 * 0.7 + 0.3 * 2.5
    assert_close(pos, [b**2, b])
    assert_close(mass, [[ref(x.mass_matrix[0][0])]])
    assert_close(h, [ref(x.h_vector[0])])
    assert_close(energy, ref(x.mechanical_energy))
    assert_close(acc, [ref(d.acceleration) for d in x.dependent])
    assert_close(acc, jac @ qdd + scalar)
    out = np.zeros(4)
    compiled.contact_law(0, 1.0, 1.0, p, out)
    assert np.isnan(out).all()
    assert math.isfinite(energy)


def test_model_without_energy_gives_zero(tmp_path):
    compiled = compile_model(chain_model(mechanical_energy=None), cache_dir=tmp_path)
    assert compiled.mechanical_energy(np.ones(1), np.ones(1), 0.0, np.ones(2)) == 0.0


# Every function of the language, compiled: contact laws in vRel and temp.
FUNCTION_LAWS = [
    ("Sin[vRel] + Cos[temp] + Tan[vRel]", "Cot[vRel] + Sec[temp] + Csc[vRel]", "ArcSin[vRel/2]", "ArcCos[vRel/3]"),
    ("ArcTan[vRel, -temp]", "arctan2(-vRel, temp)", "Sinh[vRel] + Cosh[temp] + Tanh[vRel]", "ArcCosh[temp + 1]"),
    ("ArcTanh[vRel/2] + Exp[vRel]", "Ln[temp] + Log[vRel] + Log[3, temp]", "Log10[temp] + logN(5, vRel)", "Log2[vRel]"),
    ("Power[temp, 1.5] + temp^-2 + 2^vRel", "Abs[-vRel] + Sign[vRel - 1]", "Min[vRel, temp, 1]", "ArcTan[vRel]"),
    ("Max[vRel, 0]", "Sign[0 vRel]", "0", "0"),
    ("temp! + 3!", "Pi E + 1.5*^-7 vRel", "0.1 + 1e-3 temp + Floor[temp] + Ceil[vRel]", "c'm temp vRel/c'c"),
    ("ArcSinh[vRel]", "Sqrt[temp] + Sqr[vRel]", "0", "1"),
]


def test_every_function_compiles_and_matches_sympy(tmp_path):
    laws = [tuple(parse_expression(e) for e in law) for law in FUNCTION_LAWS]
    compiled = compile_model(chain_model(contact_laws=laws), cache_dir=tmp_path)
    p = np.array([0.3, 1.7])
    out = np.empty(4)
    for vrel, temp in [(0.7, 1.3), (1.9, 4.6)]:
        ref = Reference(chain_model(), [0], [0], [0], 0, p)
        for k, law in enumerate(laws):
            compiled.contact_law(k, vrel, temp, p, out)
            assert_close(out, [ref(e, vrel=vrel, temp=temp) for e in law])


# -- errors ---------------------------------------------------------------------------------

ERRORS = {
    "unknown constant": (dict(h_vector=[parse_expression("c'nope")]), "h vector entry 1 uses unknown c'nope"),
    "unknown coordinate": (
        dict(mechanical_energy=parse_expression("b'ghost'Rz'[t]^2")),
        "mechanical energy uses unknown Derivative[1][b'ghost'Rz][t]",
    ),
    "velocity in mass matrix": (
        dict(mass_matrix=[[parse_expression("b'a'x'[t]")]]),
        "mass matrix entry (1, 1) may not use Derivative[1][b'a'x][t]",
    ),
    "dependent velocity in mass matrix": (
        dict(mass_matrix=[[parse_expression("b'b'x'[t]")]]),
        "mass matrix entry (1, 1) may not use Derivative[1][b'b'x][t]",
    ),
    "second derivative in h": (
        dict(h_vector=[parse_expression("b'a'x''[t]")]),
        "h vector entry 1 may not use Derivative[2][b'a'x][t]",
    ),
    "temperature in h": (dict(h_vector=[parse_expression("temp")]), "h vector entry 1 may not depend on temp"),
    "coordinate in contact law": (
        dict(contact_laws=[(parse_expression("b'a'x[t]"), 0, 0, 0)]),
        "friction of contact properties 1 may not depend on b'a'x[t]",
    ),
    "time in contact law": (
        dict(contact_laws=[(0, 0, 0, T)]),
        "parameterNi of contact properties 1 may not depend on t",
    ),
    "short contact law": (dict(contact_laws=[(0, 0, 0)]), "a contact law has 4 expressions"),
    "mass matrix shape": (dict(mass_matrix=[[1, 0]]), "the mass matrix must be 1 x 1"),
    "h vector length": (dict(h_vector=[]), "the h vector must have 1 entries"),
    "twice declared": (dict(parameters=[constant("c"), constant("m"), constant("c")]), "c'c is declared twice"),
    "fixed using a coordinate": (
        dict(fixed={body_coordinate("a", "y"): body_coordinate("a", "x")}),
        "fixed value of b'a'y[t] may not depend on b'a'x[t]",
    ),
}


@pytest.mark.parametrize("case", ERRORS)
def test_errors(case):
    overrides, message = ERRORS[case]
    with pytest.raises(ModelError) as caught:
        generate_source(chain_model(**overrides))
    assert message in str(caught.value)


def test_cycle_of_dependent_coordinates():
    x = chain_model()
    x.dependent[1].position = parse_expression("b'c'x[t]")
    with pytest.raises(ModelError, match=r"cycle: b'(c|b)'x\[t\] -> b'(b|c)'x\[t\] -> b'\1'x\[t\]"):
        generate_source(x)


def test_wrong_jacobian_length():
    x = chain_model()
    x.dependent[0].jacobian = []
    with pytest.raises(ModelError, match=r"Jacobian vector of b'c'x\[t\] must have 1 entries"):
        generate_source(x)
