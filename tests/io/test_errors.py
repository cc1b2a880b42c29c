"""Malformed files give a ModelError naming the file and line; nothing else escapes."""

import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mbds.errors import ModelError
from mbds.io.text import read_text
from tests.io.formats import FORMATS

MANUAL = Path(__file__).resolve().parents[1] / "data" / "manual"

CASES = [
    ("wld", "[main]\nminimumTimestep = abc\n", 2, "'abc' is not a number"),
    ("wld", "[main]\nminimumTimestep = 1e-3\nmaximumTimestep = 1e-5\n", 2, "minimumTimestep is larger"),
    ("wld", "[main\nbreakTime = 1\n", 1, "malformed section header"),
    ("wld", "[bodies]\nbody1 = a.bdy\n", 1, "no [main] section"),
    ("wld", "[main]\nbreakTime\n", 2, "expected 'key = value'"),
    ("wld", "[main]\nTryToSolveByGoingBack = maybe\n", 2, "is not a flag"),
    ("job", "[main]\njobs = 005-001\n", 2, "runs backwards"),
    ("job", "[main]\njobs = 1a\n", 2, "not a version number"),
    ("bdy", "[main]\nshapeFile = a.exs\n", 1, "has no name"),
    ("bdy", "[main]\nname = a-b\n", 2, "contains a quote"),
    ("bdy", "[main]\nname = a\nshapeType = sphere\n", 1, "not supported"),
    ("exs", "points = 4\n%%data\n0 1 0\n0 0 1\n%%enddata\n", 2, "2 lines of 4 values"),
    ("exs", "points = 4\n%%data\n0 1 0 0\n0 0 1 0\n", 2, "no %%enddata"),
    ("exs", "points = 4\n", 1, "no %%data block"),
    ("gc", "b'mass1'q[t]\n", 1, "is not a coordinate"),
    ("gc", "b'm'x[t]\nb'm'x[t]\n", 2, "listed twice"),
    ("dc", "b'bird'x[t]\n", 1, "expected %%%new%%%"),
    ("dc", "%%%new%%%\nb'bird'x[t]\n%%definition\n1\n2\n", 2, "needs 1 (position) or 3"),
    ("cns", "gravity = 9.81\n", 1, "is not a constant name"),
    ("cns", "c'g = 9,81\n", 1, "is not a number"),
    ("mmx", "a b c\n", 1, "row has 3 entries, expected 1"),
    ("cop", "[mass1]\nfriction = 0.1\n", 1, "must be [body1-body2] or [body:all]"),
    ("cop", "[a-b]\nresistingPenetration = F:F\n", 2, "resistingPenetration must be one of"),
    ("wtc", "[a]\ncontactWatch = 3-1\n", 2, "runs backwards"),
    ("wtc", "[a]\ncontactWatch = 1,,2\n", 2, "empty item"),
    ("wtc", "[a]\ncontactWatch = [1:2\n", 2, "unbalanced brackets"),
    ("wtc", "[a]\ndirectionInside = 2\n", 1, "directionInside must be"),
    ("wtc", "[reshapeWindow]\ncutHiLowValues = 60\n", 1, "cutHiLowValues is a percentage"),
]


@pytest.mark.parametrize("kind, text, line, message", CASES)
def test_malformed_file_names_file_and_line(tmp_path, kind, text, line, message):
    path = tmp_path / f"bad.{kind}"
    with pytest.raises(ModelError) as info:
        FORMATS[kind][0](text, path)
    assert message in info.value.message
    assert info.value.file == str(path)
    assert info.value.line == line
    prefix = f"{path}:{line}: " if line else f"{path}: "
    assert str(info.value).startswith(prefix)


def test_unknown_key_is_a_warning_with_line(tmp_path):
    with pytest.warns(UserWarning, match=r"bad.wld:3: unknown key 'maximumTimeStepp'"):
        FORMATS["wld"][0]("[main]\nbreakTime = 1\nmaximumTimeStepp = 1\n", tmp_path / "bad.wld")


def test_keys_in_any_letter_case(tmp_path):
    world = FORMATS["wld"][0]("[MAIN]\nMAXIMUMTIMESTEP = 2e-5\nbreaktime = 3\n", tmp_path / "w.wld")
    assert world.settings.maximum_timestep == 2e-5 and world.settings.break_time.text == "3"


def test_decimal_comma(tmp_path):
    world = FORMATS["wld"][0]("[main]\ndecimalSeparator = ,\nmaximumTimestep = 2,5e-5\n", tmp_path / "w.wld")
    assert world.settings.maximum_timestep == 2.5e-5
    shape = FORMATS["exs"][0]("points = 4\n%%data\n0 1,5 0 0\n0 0 1 0\n%%enddata\n", tmp_path / "s.exs", separator=",")
    assert shape.points[1, 0] == 1.5
    again = FORMATS["wld"][0](FORMATS["wld"][1](world), tmp_path / "w.wld")
    assert again == world


SAMPLES = sorted(p for p in MANUAL.iterdir() if p.suffix[1:] in FORMATS)


def _mutate(text: str, data) -> str:
    """Delete, duplicate, replace or insert characters or lines of ``text``."""
    for _ in range(data.draw(st.integers(1, 4))):
        action = data.draw(st.sampled_from(["delete", "insert", "swap_lines", "drop_line", "truncate"]))
        if not text:
            break
        i = data.draw(st.integers(0, len(text) - 1))
        if action == "delete":
            text = text[:i] + text[i + data.draw(st.integers(1, 5)) :]
        elif action == "insert":
            text = text[:i] + data.draw(st.text(alphabet="[]=%-:,.;`'01eE+ \n\tabc\x00\u2018", max_size=4)) + text[i:]
        elif action == "truncate":
            text = text[:i]
        else:
            lines = text.splitlines()
            if len(lines) > 1:
                j = data.draw(st.integers(0, len(lines) - 2))
                if action == "swap_lines":
                    lines[j], lines[j + 1] = lines[j + 1], lines[j]
                else:
                    del lines[j]
                text = "\n".join(lines)
    return text


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_mutated_files_raise_only_model_errors(data):
    path = data.draw(st.sampled_from(SAMPLES))
    text = _mutate(read_text(path), data)
    parser = FORMATS[path.suffix[1:]][0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            parser(text, path)
        except ModelError:
            pass


@settings(max_examples=200, deadline=None)
@given(kind=st.sampled_from(sorted(FORMATS)), text=st.text(max_size=200))
def test_random_text_raises_only_model_errors(kind, text):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            FORMATS[kind][0](text, Path(f"random.{kind}"))
        except ModelError:
            pass
