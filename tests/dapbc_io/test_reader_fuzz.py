"""Mutated in-files: the reader either reads them or stops with a ModelError that names the
file (and the line, except for a file that never sets its array); never another exception."""

from __future__ import annotations

import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mbds.errors import ModelError
from mbds.io.dapbc import read_dapbc_folder
from tests.dapbc_io.folders import SP, write_folder

PIECES = ["[", "]", "(", ")", ";", ",", "'", "...", "%", "=", "==", ".", "end", "if", "else",
          "function", "global", "include_global", "Bodies", "Points(2)", "B1", ".r", ".type",
          "Body_struct", "Point_struct", "0", "-1", "1e300", "2.5", "pi", "sin(", "'rev'", "~",
          "^", "*", "/", "\n", " ", "B1.m = ", ":", "{", "@", "\"", "1/0", "[1 2; 3]", "\t"]


@st.composite
def mutated_model(draw):
    name = draw(st.sampled_from(sorted(SP)))
    text = SP[name]
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(["insert", "delete", "replace", "swap"]))
        i = draw(st.integers(0, len(text)))
        if kind == "insert":
            text = text[:i] + draw(st.sampled_from(PIECES) | st.text(max_size=3)) + text[i:]
        elif kind == "delete":
            text = text[:i] + text[i + draw(st.integers(1, 8)):]
        elif kind == "replace":
            text = text[:i] + draw(st.sampled_from(PIECES)) + text[i + draw(st.integers(1, 4)):]
        else:
            lines = text.split("\n")
            a, b = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
            lines[a], lines[b] = lines[b], lines[a]
            text = "\n".join(lines)
    return name, text


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated_model())
def test_mutated_in_files_give_located_errors(mutation):
    name, text = mutation
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_folder(Path(tmp), {name: text})
        try:
            read_dapbc_folder(folder)
        except ModelError as error:
            assert error.file is not None and Path(error.file).parent == folder, str(error)
            assert error.line is not None or "never sets" in error.message or "UTF-8" in error.message, str(error)
            assert error.line is None or error.line >= 1
