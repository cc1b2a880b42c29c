"""Bad in-files: every error names file:line and what is wrong, never a traceback."""

from __future__ import annotations

import pytest

from mbds.errors import ModelError
from mbds.io.dapbc import read_dapbc_folder
from tests.dapbc_io.folders import SP, write_folder


def replaced(name: str, old: str, new: str) -> dict[str, str]:
    """SP's file ``name`` with ``old`` replaced by ``new`` (which must occur)."""
    assert old in SP[name]
    return {name: SP[name].replace(old, new, 1)}


CASES = [
    # syntax outside the subset
    ("inBodies.m", "B1.m = 5.0;", "for i = 1:2\nend", 5, "for loops are outside the subset"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 5.0 +;", 5, "expected a value, found ';'"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = (5.0;", 5, "expected ')'"),
    ("inBodies.m", "B1.r = [1.0; 0.2];", "B1.r = [1.0; 0.2;", 7, "never closed by ']'"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = \"5\";", 5, "double-quoted strings"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 'abc;", 5, "not closed on this line"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 5.0 $", 5, "unexpected character '$'"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 1:3;", 5, "ranges 'a:b'"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = {5};", 5, "cell arrays"),
    ("inBodies.m", "B1.m = 5.0;", "[a, b] = size(1);", 5, "several outputs"),
    ("inBodies.m", "B1.m = 5.0;", "hold on", 5, "command syntax"),
    ("inBodies.m", "B1.m = 5.0;", "if 1\n B1.m = 2;", 5, "never closed by 'end'"),
    ("inBodies.m", "B1.m = 5.0;", "end", 5, "closes the function but statements follow"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 5e;", 5, "malformed number"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = @sin;", 5, "function handles"),
    # evaluation
    ("inBodies.m", "B1.m = 5.0;", "B1.mass = 5.0;", 5, "Body has no field 'mass'"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = [5.0; 1];", 5, "must be a number, not a 2x1 matrix"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 'heavy';", 5, "must be a number, not text"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = 1/0;", 5, "not a finite number"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = qq;", 5, "'qq' is not defined"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = frob(2);", 5, "neither a variable nor a known function"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = sin(1, 2);", 5, "sin takes 1 argument"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = [1 2] * [3 4];", 5, "inner sizes differ"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = [1 2] + [1 2 3];", 5, "sizes do not match"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = [1; 2] / [1; 2];", 5, "'/' by a 2x1 matrix"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = [1 2; 3];", 5, "rows in brackets have different lengths"),
    ("inBodies.m", "B1.m = 5.0;", "C.m = 5.0;", 5, "'C' is not defined; create it first"),
    ("inBodies.m", "B1.r = [1.0; 0.2];", "B1.r = [1.0; 0.2; 3];", 7, "must be a 2-vector"),
    ("inBodies.m", "B1.r = [1.0; 0.2];", "B1.r(3) = 1;", 7, "has no component 3"),
    ("inBodies.m", "B1.m = 5.0;", "B1.m = Body_struct(2);", 5, "Body_struct takes no arguments"),
    ("inBodies.m", "Bodies = [B1; B2];", "Bodies = [B1; 3];", 15, "cannot hold a number"),
    ("inBodies.m", "Bodies = [B1; B2];", "Bodies = [B1; Point_struct];", 15, "mixes Body and Point"),
    ("inBodies.m", "Bodies = [B1; B2];", "Bodies = 3;", 15, "must be an array of Body structs"),
    ("inBodies.m", "Bodies = [B1; B2];", "Bodies = [];", 15, "the model has no bodies"),
    ("inBodies.m", "Bodies = [B1; B2];", "", None, "never sets 'Bodies'"),
    ("inBodies.m", "    include_global\n", "", 1, "include_global is missing"),
    ("inBodies.m", "function inBodies", "function Bodies = inBodies(x)", 1, "take no arguments"),
    ("inPoints.m", "Points = [P1; P2; P3];", "Points = [P1; P2; B1];", 16, "'B1' is not defined"),
    ("inPoints.m", "Points = [P1; P2; P3];", "Points = [P1; P2; Body_struct];", 16, "mixes Body and Point"),
    ("inPoints.m", "P1.Bindex = 0;", "P1.Bindex = 1.5;", 5, "must be a whole number >= 0"),
    ("inPoints.m", "P1.Bindex = 0;", "P1.Bindex = -1;", 5, "must be a whole number >= 0"),
    ("inForces.m", "F1.type = 'ptp';", "F1.type = 'spring';", 5, "unknown 'spring'"),
    ("inForces.m", "F1.type = 'ptp';", "F1.typ2 = 'ptp';", 5, "did you mean 'type'"),
    ("inJoints.m", "J2.type = 'rev';", "J2.type = 'pin';", 12, "unknown 'pin'"),
    ("inAnimate.m", "Bodies(2).shape = 'line';", "Bodies(3).shape = 'line';", 7, "Bodies(3) does not exist"),
    ("inAnimate.m", "Bodies(2).shape = 'line';", "Bodies(2).shape = 'star';", 7, "unknown 'star'"),
    ("inAnimate.m", "Bodies(2).shape = 'line';", "Bodies(0).shape = 'line';", 7, "index must be a whole number >= 1"),
    ("inAnimate.m", "xmin = -0.5;", "xmin = [1 2];", 9, "'xmin' must be a finite number"),
    # references
    ("inPoints.m", "P3.Bindex = 2;", "P3.Bindex = 3;", 13, "Point 3: Bindex = 3 names no body; the model has 2 bodies"),
    ("inUvectors.m", "U2.Bindex = 1;", "U2.Bindex = 5;", 9, "Unit vector 2: Bindex = 5 names no body"),
    ("inJoints.m", "J2.jPindex = 3;", "J2.jPindex = 4;", 14, "Joint 2: jPindex = 4 names no point; the model has 3 points"),
    ("inJoints.m", "J1.jUindex = 1;", "J1.jUindex = 3;", 9, "Joint 1: jUindex = 3 names no unit vector"),
    ("inJoints.m", "J1.jUindex = 1;", "", 5, "Joint 1 (tran) needs jUindex"),
    ("inJoints.m", "J1.iUindex = 2;", "J1.iUindex = 1;", 8, "unit vector 1 is on body 0 but point 2 is on body 1"),
    ("inJoints.m", "J2.jPindex = 3;", "J2.jPindex = 2;", 14, "are on the same body"),
    ("inJoints.m", "J2.jPindex = 3;", "J2.jPindex = 3; J2.iFunct = 1;", 14, "iFunct = 1 names no function; the model has no functs"),
    ("inForces.m", "F1.iPindex = 2;", "F1.iPindex = 7;", 6, "Force 1: iPindex = 7 names no point"),
    ("inForces.m", "F1.jPindex = 1;", "F1.jPindex = 2;", 7, "points 2 and 2 are on the same body"),
    ("inForces.m", "F2.type = 'weight';", "F2.type = 'user';", 12, "has no user_force.m"),
    ("inForces.m", "F2.type = 'weight';", "F2.type = 'T'; F2.iBindex = 3;", 12, "iBindex = 3 names no body"),
    ("inForces.m", "F2.type = 'weight';", "F2.type = 'rot-sda';", 12, "two different bodies"),
]


@pytest.mark.parametrize("name, old, new, line, message", CASES, ids=[c[4][:40] for c in CASES])
def test_bad_in_file_is_reported_at_its_line(tmp_path, name, old, new, message, line):
    with pytest.raises(ModelError) as info:
        read_dapbc_folder(write_folder(tmp_path, replaced(name, old, new)))
    error = info.value
    assert message in error.message
    assert error.file.endswith(name)
    assert error.line == line
    assert str(error).startswith(f"{error.file}:{line}: " if line else f"{error.file}: ")


def test_function_errors_point_at_the_field(tmp_path):
    functs = """function inFuncts
    include_global
F1 = Funct_struct;
F1.type = 'b';
F1.t_start = 2;
F1.t_end = 1;
F2 = Funct_struct;
F2.coeff = [1 2];
Functs = [F1; F2];
"""
    with pytest.raises(ModelError, match=r"inFuncts.m:6: Function 1 \(type 'b'\) needs t_end > t_start"):
        read_dapbc_folder(write_folder(tmp_path, {"inFuncs.m": None, "inFuncts.m": functs}))
    fixed = functs.replace("F1.t_end = 1;", "F1.t_end = 3;")
    with pytest.raises(ModelError, match=r"inFuncts.m:8: Function 2 \(type 'a'\) needs coeff"):
        read_dapbc_folder(write_folder(tmp_path, {"inFuncs.m": None, "inFuncts.m": fixed}))


def test_both_function_file_names_is_an_error(tmp_path):
    with pytest.raises(ModelError, match="both inFuncts.m and inFuncs.m exist"):
        read_dapbc_folder(write_folder(tmp_path, {"inFuncts.m": SP["inFuncs.m"]}))


def test_not_utf8_is_an_error(tmp_path):
    folder = write_folder(tmp_path, {})
    (folder / "inPoints.m").write_bytes(b"function inPoints\n\xff\xfe")
    with pytest.raises(ModelError, match="inPoints.m: not UTF-8 text"):
        read_dapbc_folder(folder)


@pytest.mark.parametrize("index", ["NaN", "Inf", "1e400", "2.5", "'a'", "[1 2]"])
def test_indices_that_are_not_whole_numbers(tmp_path, index):
    animate = SP["inAnimate.m"].replace("Bodies(2).shape = 'line';", f"Bodies({index}).shape = 'line';")
    with pytest.raises(ModelError, match=r"inAnimate.m:7: an index must be a whole number >= 1"):
        read_dapbc_folder(write_folder(tmp_path, {"inAnimate.m": animate}))
