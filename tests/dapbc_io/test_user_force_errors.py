"""user_force code outside the subset: ModelError at file:line, never a traceback."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mbds.errors import ModelError
from mbds.io.dapbc.records import Body, DapbcModel, Force, Point
from mbds.io.dapbc.user_force import compile_user_force, from_function, python_user_force
from tests.dapbc_io.mutations import mutate
from tests.dapbc_io.test_user_force import AA_MP_USER_FORCE, CART_USER_FORCE, CB_USER_FORCE, ROD_USER_FORCE

MODEL = DapbcModel(folder=".", bodies=[Body(), Body()],
                   points=[Point(Bindex=1, sPlocal=np.array([0.0, -1.0])), Point(Bindex=2), Point(Bindex=1)],
                   forces=[Force(type="user"), Force(type="user", k=1.0, L0=0.3, dc=2.0)])

CASES = [
    ("x = Points(3).sp;", "Points(i).sp is not available in user_force; did you mean 'sP'"),
    ("x = Bodies(1).m;", "Bodies(i).m is not available"),
    ("x = Bodies(3).r;", "the index of Bodies = 3 is out of range (1..2)"),
    ("x = Forces(1).stiffness;", "Forces(i).stiffness is not available"),
    ("x = Uvectors(1).u;", "Uvectors is not available in user_force"),
    ("Bodies(1).r = [0; 0];", "may change only Bodies(i).f and Bodies(i).n, not Bodies(1).r"),
    ("Forces(2).k = 3;", "may change only Bodies(i).f and Bodies(i).n"),
    ("Bodies(1).n = [1; 2];", "expected a number, got a 2x1 vector"),
    ("Bodies(1).f = [1 2; 3 4];", "must be a 2x1 vector, not a 2x2 matrix"),
    ("Bodies(1).f(3) = 1;", "an index must be a constant whole number 1..2"),
    ("x = 1;\nx = [1; 2];", "'x' is a number (line 3); it cannot become a 2x1 vector"),
    ("y = z + 1;", "'z' is used before it is set"),
    ("Contact(1, 2, 1, 1e9, 0.9, 1)", "Contact: point 2 is on body 2, not on body 1"),
    ("Contact(1, 4, 1, 1e9, 0.9, 1)", "point index Pi = 4 is out of range (1..3)"),
    ("Contact(1, 1, 1, 1e9, 0.9, 3)", "model index Mi = 3 is out of range (1..2)"),
    ("Contact(0, 1, 1, 1e9, 0.9, 1)", "contact index Ci must be a constant whole number >= 1"),
    ("Contact(1, 1, 1, 1e9, 0.9)", "Contact takes 6 arguments"),
    ("x = Contact(1, 1, 1, 1e9, 0.9, 1);", "Contact(...) is a statement of its own"),
    ("x = Friction_A(1, 2, 3);", "Friction_A takes 6 or 7 arguments, got 3"),
    ("x = functs(1, 0.5);", "'functs' is not a function of the user_force subset"),
    ("for i = 1:2\nend", "for loops are outside the subset"),
    ("global g\ng = 1;", "global 'g': global variables other than the model's arrays"),
    ("x = [1; 2] * [3; 4];", "inner sizes differ"),
    ("x = [1; 2] + [3 4];", "sizes do not match"),
    ("x = [1 2 3];", "only 2x1, 1x2 and 2x2 matrices"),
    ("x = 'text';", "text is outside the user_force subset"),
    ("x = [1; 2] / [1; 2];", "'/' by a vector or matrix"),
    ("x = [1; 2]^2;", "'^' of vectors is outside the subset"),
    ("x = 3; x(1) = 2;", "'x' is not a vector set earlier"),
    ("x = s_rot(1);", "s_rot takes one 2x1 vector"),
    ("Bodies(1).r_d;", "a statement without effect"),
    ("x = Bodies(1);", "Bodies(i) needs a field"),
    ("x = Bodies(i).r;", "the index of Bodies must be a constant whole number"),
    ("Bodies = 1;", "'Bodies' cannot be replaced in user_force"),
    ("x = 1 +\n2;", "expected a value, found the end of the line (continue a statement on the next line with '...')"),
]


@pytest.mark.parametrize("line, message", CASES, ids=[c[1][:40] for c in CASES])
def test_user_force_errors_name_file_and_line(line, message):
    source = "function user_force\n    include_global\n" + line + "\n"
    with pytest.raises(ModelError) as info:
        compile_user_force(source, MODEL, "model/user_force.m")
    assert message in info.value.message
    assert info.value.file == "model/user_force.m"
    assert info.value.line == 3 + (line.count("\n") if "(line 3)" in message or "global" in message else 0)


PYTHON_CASES = [
    ("import numpy\n\ndef user_force(t, r, p):\n    pass\n", r"user_force.py:3: user_force must take \(t, r, p, r_d"),
    ("def user_force(:\n", r"user_force.py:1: Python syntax error"),
    ("N_STATE = -1\n", r"user_force.py:1: N_STATE must be a whole number"),
    ("x = 1\n", r"user_force.py: user_force.py must define"),
]


@pytest.mark.parametrize("text, message", PYTHON_CASES)
def test_bad_python_user_force(tmp_path, text, message):
    path = tmp_path / "user_force.py"
    path.write_text(text)
    with pytest.raises(ModelError, match=message):
        python_user_force(path)


def bad_signature(t, r, p):
    """Not a user force."""


@pytest.mark.parametrize("name", ["spring_to_origin", "compiled_spring_to_origin"])
def test_user_force_given_as_a_function(name):
    from tests.dapbc_io import python_force
    code = from_function(getattr(python_force, name), n_state=0)
    force = code.load()
    f, n = np.zeros((1, 2)), np.zeros(1)
    force(0.0, np.array([[2.0, -1.0]]), np.zeros(1), np.zeros((1, 2)), np.zeros(1), np.eye(2)[None],
          np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 2)), np.array([[3.0]]), np.zeros(0), f, n)
    assert list(f[0]) == [-6.0, 3.0]
    with pytest.raises(ModelError, match="a user force function must take"):
        from_function(bad_signature)


PIECES = ["if", "end", "else", "elseif", "(", ")", "[", "]", ";", "'", "Bodies(1)", "Bodies(9)",
          ".f", ".n", ".r", ".A", "Points(1).sP", "Forces(2).k", "Contact(1, 1, 1, k, e, 1)", "=",
          "==", "<", "&&", "~", "*", "/", "^", "+", "-", "s_rot(", "abs(", "min(", "1", "0", "2.5", "1e400", "Inf",
          "\n", " ", "...", "%", "x", "fsd", "Friction_A(", "global ", "t", "'a'", ",", ":"]


@st.composite
def mutated_user_force(draw):
    text = draw(st.sampled_from([CB_USER_FORCE, AA_MP_USER_FORCE, CART_USER_FORCE,
                                 ROD_USER_FORCE.replace("MODEL", "2")]))
    return mutate(draw, text, PIECES)


FUZZ_MODEL = DapbcModel(folder=".", bodies=[Body(), Body()],
                        points=[Point(Bindex=1), Point(Bindex=1), Point(Bindex=1)],
                        forces=[Force(), Force(type="user")])


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated_user_force())
def test_mutated_user_force_compiles_or_gives_a_located_error(text):
    """Either a ModelError with file:line, or Python source that compiles."""
    with tempfile.TemporaryDirectory() as tmp:
        file = Path(tmp) / "user_force.m"
        try:
            code = compile_user_force(text, FUZZ_MODEL, file)
        except ModelError as error:
            assert error.file == str(file) and error.line is not None and error.line >= 1, str(error)
            return
        compile(code.module_source, "generated", "exec")


@pytest.mark.parametrize("index", ["1e400", "2.5", "-1", "1/0"])
def test_user_force_indices_that_are_not_whole_numbers(index):
    with pytest.raises(ModelError, match=r"user_force.m:1: the index of Bodies must be a constant whole number"):
        compile_user_force(f"x = Bodies({index}).p;\n", MODEL, "user_force.m")
