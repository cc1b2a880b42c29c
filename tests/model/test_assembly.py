"""Assembling the example models: bodies, bindings, parameters, contacts, watches, and
compiled functions that agree with sympy's own evaluation of the model files' expressions."""

from pathlib import Path

import numpy as np
import pytest
import sympy

from mbds.errors import ModelError
from mbds.expr import symbols as S
from mbds.model.arrays import flatten
from mbds.model.bodies import DEPENDENT, FIXED, GENERALIZED
from mbds.model.load import load_model
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGNS = ROOT / "campaigns"


@pytest.fixture(scope="module")
def models():
    return {name: load_model(CAMPAIGNS / name) for name in ("2mass", "wearballs", "woodpecker")}


def test_2mass_bodies_and_parameters(models):
    model = models["2mass"]
    mass1, mass2 = model.bodies
    assert mass1.mass == pytest.approx(0.735, rel=1e-12)
    assert mass1.inertia == pytest.approx(1.8503e-3, rel=1e-4)
    assert mass1.binding == (GENERALIZED,) * 3 and mass1.binding_index == (0, 1, 2)
    assert mass2.binding == (FIXED,) * 3
    assert model.q0 == pytest.approx([-0.005, 0.15, 3.1459])
    assert model.qd0 == pytest.approx([0, -1, 0])
    assert model.break_time == 0.5
    names = [str(s) for s in model.parameters.symbols]
    assert names[:3] == ["c`gravity", "b`mass1`m", "b`mass1`Jzz"]
    assert model.parameters.values[:3] == pytest.approx([9.81, 0.735, mass1.inertia])
    assert [(p.first, p.second) for p in model.pairs] == [(0, 1)]
    assert [w.label for w in model.watches] == ["mass1#0", "mass1#1", "mass1#2"]


def test_woodpecker_virtual_and_dependent_bodies(models):
    model = models["woodpecker"]
    by_name = {b.name: b for b in model.bodies}
    ring, bird = by_name["ring"], by_name["bird"]
    assert bird.binding == (DEPENDENT, DEPENDENT, GENERALIZED)
    assert ring.binding[1:] == (GENERALIZED, GENERALIZED)
    virtual = by_name["ringSideR"]
    assert virtual.virtual and model.bodies[virtual.carrier] is ring
    assert virtual.mass == 0.0
    # the offset reproduces the start pose from the carrier's start pose
    c, s = np.cos(ring.start_position[2]), np.sin(ring.start_position[2])
    dx, dy = virtual.offset[:2]
    rebuilt = ring.start_position[:2] + np.array([c * dx - s * dy, s * dx + c * dy])
    assert rebuilt == pytest.approx(virtual.start_position[:2], abs=1e-15)
    pairs = {(model.bodies[p.first].name, model.bodies[p.second].name) for p in model.pairs}
    assert ("ring", "ringSideR") not in pairs and ("stick", "ringSideR") in pairs


def _numeric(expr, model, q, qd, t):
    """sympy's own value of ``expr`` at (q, qd, t), dependent coordinates replaced by their
    position and velocity expressions, in 30-digit arithmetic."""
    expressions = model.expressions
    for d in expressions.dependent:
        expr = expr.subs(sympy.Derivative(d.coordinate, S.T), d.velocity).subs(d.coordinate, d.position)
    for coordinate, value in expressions.fixed.items():
        expr = expr.subs(sympy.Derivative(coordinate, S.T), 0).subs(coordinate, value)
    values = {}
    for k, c in enumerate(expressions.coordinates):
        values[sympy.Derivative(c, S.T)] = sympy.Float(qd[k], 30)
    expr = expr.subs(values)
    expr = expr.subs({c: sympy.Float(q[k], 30) for k, c in enumerate(expressions.coordinates)})
    expr = expr.subs({s: sympy.Float(v, 30) for s, v in zip(model.parameters.symbols, model.parameters.values)})
    return float(expr.subs(S.T, sympy.Float(t, 30)).evalf(30))


@pytest.mark.parametrize("name", ["2mass", "wearballs", "woodpecker"])
def test_compiled_functions_equal_sympy(models, name):
    model = models[name]
    compiled = model.compiled
    n, m = len(model.coordinates), len(model.dependent)
    rng = np.random.default_rng(7)
    p = model.parameters.values
    for _ in range(3):
        q = model.q0 + rng.normal(0, 0.1, n)
        qd = rng.normal(0, 1, n)
        t = rng.uniform(0, 1)
        M, h = np.empty((n, n)), np.empty(n)
        compiled.mass_matrix(q, t, p, M)
        compiled.h_vector(q, qd, t, p, h)
        expected_M = [[_numeric(e, model, q, qd, t) for e in row] for row in model.expressions.mass_matrix]
        expected_h = [_numeric(e, model, q, qd, t) for e in model.expressions.h_vector]
        assert M == pytest.approx(np.array(expected_M), rel=1e-12, abs=1e-14 * np.abs(expected_M).max())
        assert h == pytest.approx(np.array(expected_h), rel=1e-12, abs=1e-14 * max(np.abs(expected_h).max(), 1e-300))
        energy = compiled.mechanical_energy(q, qd, t, p)
        assert energy == pytest.approx(_numeric(model.expressions.mechanical_energy, model, q, qd, t), rel=1e-12)
        if m:
            pos, vel, acc = np.empty(m), np.empty(m), np.empty(m)
            compiled.dependent_state(q, qd, np.zeros(n), t, p, pos, vel, acc)
            J, j = np.empty((m, n)), np.empty(m)
            compiled.dependent_jacobian(q, qd, t, p, J, j)
            def positions_at(tau):
                out = np.empty(m)
                compiled.dependent_state(q, qd, np.zeros(n), tau, p, out, np.empty(m), np.empty(m))
                return out

            explicit = (positions_at(t + 1e-6) - positions_at(t - 1e-6)) / 2e-6  # d pos / dt at fixed q
            for i, d in enumerate(model.expressions.dependent):
                assert pos[i] == pytest.approx(_numeric(d.position, model, q, qd, t), rel=1e-12, abs=1e-15)
                assert vel[i] == pytest.approx(_numeric(d.velocity, model, q, qd, t), rel=1e-12, abs=1e-15)
                assert vel[i] == pytest.approx(J[i] @ qd + explicit[i], rel=1e-7, abs=1e-9)  # c' = J q' + dc/dt
                assert J[i] == pytest.approx([_numeric(e, model, q, qd, t) for e in d.jacobian], rel=1e-12, abs=1e-15)


def test_woodpecker_jacobian_matches_finite_differences(models):
    """The .dc file's J and j are the derivatives of its positions: c'' = J q'' + j."""
    model = models["woodpecker"]
    compiled, p = model.compiled, model.parameters.values
    n, m = 3, len(model.dependent)
    q, qd, qdd = np.array([0.01, -0.1, -0.25]), np.array([-0.3, 2.0, -7.0]), np.array([1.0, -50.0, 300.0])

    def positions(tau):
        qq = q + qd * tau + 0.5 * qdd * tau**2
        pos = np.empty(m)
        compiled.dependent_state(qq, qd + qdd * tau, qdd, tau, p, pos, np.empty(m), np.empty(m))
        return pos

    def second_difference(h):
        return (positions(h) - 2 * positions(0.0) + positions(-h)) / h**2

    acc_fd = (4 * second_difference(5e-4) - second_difference(1e-3)) / 3  # Richardson: O(h^4)
    J, j = np.empty((m, n)), np.empty(m)
    compiled.dependent_jacobian(q, qd, 0.0, p, J, j)
    assert J @ qdd + j == pytest.approx(acc_fd, rel=1e-8)


def test_flattened_arrays(models):
    model = models["woodpecker"]
    arrays = flatten(model)
    nb = len(model.bodies)
    assert arrays.binding.shape == (nb, 3) and arrays.points.shape[1] == 2
    assert arrays.point_start[-1] == len(arrays.points)
    assert (arrays.carrier >= 0).sum() == 1
    assert arrays.pair_bodies.shape == (len(model.pairs), 2)
    assert arrays.watch_start[-1] == len(arrays.watch_points)
    assert arrays.parameters == pytest.approx(model.parameters.values)
    for name, value in arrays.as_dict().items():
        assert value.flags.c_contiguous, name


def test_variant_constants_reuse_the_compiled_module(tmp_path, models):
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    (folder / "2mass.cns").write_text("c'gravity = 1.62\n")
    variant = load_model(folder)
    assert variant.compiled.source_hash == models["2mass"].compiled.source_hash
    assert variant.parameters.values[0] == 1.62
    h = np.empty(3)
    variant.compiled.h_vector(variant.q0, variant.qd0, 0.0, variant.parameters.values, h)
    assert h[1] == pytest.approx(-1.62 * 0.735)


@pytest.fixture
def copy_2mass(tmp_path):
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    return folder


BROKEN = [
    ("2mass.wtc", "[mass1]\ncontactWatch = 0-9\n", r"2mass.wtc:1: contactWatch point 9 of body 'mass1' does not exist"),
    ("2mass.cop", "[mass1-mass3]\nfriction = 0\n", r"2mass.cop:1: \[mass1-mass3\] names no body 'mass3'"),
    ("2mass.hv", "0\n-(c'gravity*b'mass1'm) + temp\n0\n", r"2mass.hv:2: 'temp' can only be used in contact-property functions"),
    ("2mass.mmx", "b'mass1'm*b'mass1'x'[t]\t0\t0\n0\tb'mass1'm\t0\n0\t0\tb'mass1'Jzz\n", r"2mass.mmx:1: a velocity is not allowed here"),
    ("2mass.gc", "b'mass1'x[t]\nb'mass1'y[t]\n", r"2mass.gc:2: the .gc file lists 2 coordinates but numberOfGeneralizedCoordinates is 3"),
    ("2mass.hv", "0\n-(c'g*b'mass1'm)\n0\n", r"2mass.hv:2: unknown constant c'g"),
    ("2mass.hv", "0\n-(c'gravity*b'mass3'm)\n0\n", r"2mass.hv:2: b'mass3'm names no body"),
    ("2mass.wld", "[main]\nnumberOfGeneralizedCoordinates = 3\nbreakTime = c'gravity - 10\n[bodies]\nbody1 = mass1.bdy\nbody2 = mass2.bdy\n", r"2mass.wld:3: breakTime must be a positive time"),
]


@pytest.mark.parametrize("name, text, message", BROKEN)
def test_broken_model_is_reported_with_file_and_line(copy_2mass, name, text, message):
    (copy_2mass / name).write_text(text)
    with pytest.raises(ModelError, match=message):
        load_model(copy_2mass, compile=False)


def test_inconsistent_jacobian_is_warned_about(tmp_path):
    folder = tmp_path / "woodpecker"
    copy_example("woodpecker", folder)
    dc = folder / "woodpecker.dc"
    text = dc.read_text()
    lines = text.splitlines()
    index = lines.index("%%J")
    lines[index + 2] = "c'lM*Sin[b'ring'Rz[t]]"  # sign error in dx/d(ring Rz)
    dc.write_text("\n".join(lines) + "\n")
    with pytest.warns(UserWarning, match=r"J\[1\] of b'bird'x\[t\] differs from the one derived"):
        load_model(folder, compile=False)


def test_dependent_coordinate_from_position_only(tmp_path):
    """A .dc block with only a position gets velocity, acceleration, J and j by differentiation."""
    folder = tmp_path / "woodpecker"
    copy_example("woodpecker", folder)
    full = load_model(CAMPAIGNS / "woodpecker", compile=False)
    lines = (folder / "woodpecker.dc").read_text().splitlines()
    short = []
    for block in "\n".join(lines).split("%%%new%%%")[1:]:
        body = [line for line in block.strip().splitlines()]
        short += ["%%%new%%%", body[0], "%%definition", body[2]]
    (folder / "woodpecker.dc").write_text("\n".join(short) + "\n")
    derived = load_model(folder)
    reference = load_model(CAMPAIGNS / "woodpecker")
    q, qd, p = np.array([0.0, -0.1, -0.27]), np.array([-0.3, 1.0, -7.0]), full.parameters.values
    out = {}
    m = len(full.dependent)
    for name, model in (("derived", derived), ("reference", reference)):
        J, j = np.empty((m, 3)), np.empty(m)
        model.compiled.dependent_jacobian(q, qd, 0.0, p, J, j)
        out[name] = (J, j)
    assert out["derived"][0] == pytest.approx(out["reference"][0], rel=1e-12, abs=1e-15)
    assert out["derived"][1] == pytest.approx(out["reference"][1], rel=1e-12, abs=1e-15)


def test_unsupported_parameter_ni_is_warned_about(copy_2mass):
    cop = copy_2mass / "2mass.cop"
    cop.write_text(cop.read_text().replace("parameterNi=0", "parameterNi=0.2"))
    with pytest.warns(UserWarning, match=r"2mass.cop:5: parameterNi is not supported"):
        load_model(copy_2mass, compile=False)


def test_pairs_that_can_never_touch_are_skipped(tmp_path):
    """[ringSideR:all] names every body, but not the carrier ring, a second virtual body of the
    same carrier, or two fixed bodies."""
    folder = tmp_path / "woodpecker"
    copy_example("woodpecker", folder)
    (folder / "ringSideX.bdy").write_text((folder / "ringSideR.bdy").read_text().replace("name = ringSideR", "name = ringSideX"))
    (folder / "post.bdy").write_text((folder / "stick.bdy").read_text().replace("name = stick", "name = post"))
    world = folder / "woodpecker.wld"
    world.write_text(world.read_text() + "body5 = ringSideX.bdy\nbody6 = post.bdy\n")
    cop = folder / "woodpecker.cop"
    cop.write_text(cop.read_text() + "[ringSideR:all]\nfriction = 0.1\n[post:all]\nfriction = 0.1\n")
    model = load_model(folder, compile=False)
    pairs = {frozenset((model.bodies[p.first].name, model.bodies[p.second].name)) for p in model.pairs}
    assert frozenset(("ringSideR", "bird")) in pairs and frozenset(("post", "bird")) in pairs
    for never in (("ringSideR", "ring"), ("ringSideR", "ringSideX"), ("post", "stick")):
        assert frozenset(never) not in pairs


def test_contact_law_numbers_are_parameters(tmp_path):
    """Variants that differ only in contact-law numbers share one generated module."""
    from mbds.expr.codegen import generate_source

    sources, values = [], []
    for friction, law in (("0.1", "0.3 - 0.001*temp"), ("0.4", "0.2 - 0.005*temp")):
        folder = copy_example("2mass", tmp_path / friction)
        cop = folder / "2mass.cop"
        text = cop.read_text().replace("friction=0.1", f"friction={friction}")
        cop.write_text(text.replace("restitutionTangent=0.2", f"restitutionTangent={law}"))
        model = load_model(folder, compile=False)
        sources.append(generate_source(model.expressions))
        values.append(dict(zip(map(str, model.parameters.symbols), model.parameters.values)))
    assert sources[0] == sources[1]
    assert values[0]["law`1`0`0"] == 0.1 and values[1]["law`1`0`0"] == 0.4
    assert (values[1]["law`1`2`0"], values[1]["law`1`2`1"]) == (0.2, -0.005)
