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
from tests.dapbc_io.mutations import mutate

PIECES = ["[", "]", "(", ")", ";", ",", "'", "...", "%", "=", "==", ".", "end", "if", "else",
          "function", "global", "include_global", "Bodies", "Points(2)", "B1", ".r", ".type",
          "Body_struct", "Point_struct", "0", "-1", "1e300", "1e400", "NaN", "Inf", "2.5", "pi", "sin(", "'rev'", "~",
          "^", "*", "/", "\n", " ", "B1.m = ", ":", "{", "@", "\"", "1/0", "[1 2; 3]", "\t"]


@st.composite
def mutated_model(draw):
    name = draw(st.sampled_from(sorted(SP)))
    return name, mutate(draw, SP[name], PIECES, swap_lines=True)


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
