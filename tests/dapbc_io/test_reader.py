"""The DAP_BC in-file reader: one test per construct of the subset, on in-files written here."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mbds.io.dapbc import is_dapbc_folder, read_dapbc_folder
from mbds.io.dapbc.records import Body, Force, Funct, Joint, Point, Uvector
from tests.dapbc_io.folders import SP, write_folder


def test_sliding_pendulum_reads_as_the_manual_lists_it(tmp_path):
    """Example B.1 of the manual: values set in the files, the rest the defaults of Tables B.1-B.7."""
    model = read_dapbc_folder(write_folder(tmp_path, {}))
    b1, b2 = model.bodies
    assert (b1.m, b1.J, b1.p) == (5.0, 4.0, 0.0)
    np.testing.assert_array_equal(b1.r, [1.0, 0.2])
    np.testing.assert_array_equal(b1.r_d, [0.0, 0.0])  # Table B.1 default
    assert b2.p == pytest.approx(math.pi / 6) and b2.p_d == 0.0
    assert [p.Bindex for p in model.points] == [0, 1, 2]
    np.testing.assert_array_equal(model.points[2].sPlocal, [0.0, 0.5])
    assert [u.Bindex for u in model.uvectors] == [0, 1]
    f1, f2 = model.forces
    assert (f1.type, f1.iPindex, f1.jPindex, f1.k, f1.L0, f1.dc) == ("ptp", 2, 1, 20.0, 0.6, 0.0)
    assert (f2.type, f2.gravity) == ("weight", 9.81)  # Table B.4 default
    np.testing.assert_array_equal(f2.wgt, [0.0, -1.0])
    assert [j.type for j in model.joints] == ["tran", "rev"]
    assert model.functs == [] and model.points_anim == []
    assert (b1.shape, b1.W, b1.H, b2.shape, b2.H, b2.color) == ("rect", 0.4, 0.2, "line", 1.0, "k")
    assert (model.window.xmin, model.window.ymax) == (-0.5, 0.5)
    assert is_dapbc_folder(model.folder)


def test_defaults_are_the_manuals_tables():
    """Tables B.1-B.7 of the manual."""
    b = Body()
    assert (b.m, b.J, b.p, b.p_d, b.shape, b.R, b.W, b.H, b.color) == (1, 1, 0, 0, " ", 1, 0, 0, "k")
    assert Point().Bindex == 0 and list(Point().sPlocal) == [0, 0]
    assert list(Uvector().ulocal) == [1, 0]
    f = Force()
    assert (f.type, f.k, f.L0, f.theta0, f.dc, f.f_a, f.T_a, f.gravity, f.T, f.iFunct) == \
        ("ptp", 0, 0, 0, 0, 0, 0, 9.81, 0, 0)
    assert list(f.wgt) == [0, -1] and list(f.flocal) == [0, 0] and list(f.f) == [0, 0]
    j = Joint()
    assert (j.type, j.L, j.R, j.x0, j.p0, j.iFunct) == ("rev", 0, 1, 0, 0, 0)
    fn = Funct()
    assert (fn.type, fn.t_start, fn.f_start, fn.t_end, fn.f_end, fn.dfdt_end, fn.ncoeff, fn.coeff.size) == \
        ("a", 0, 0, 1, 1, 1, 3, 0)


def test_source_positions_of_elements_and_fields(tmp_path):
    model = read_dapbc_folder(write_folder(tmp_path, {}))
    assert model.where("bodies", 2).line == 9  # B2 = Body_struct;
    assert model.where("bodies", 2, "p").line == 13
    assert model.where("bodies", 1, "shape").file.endswith("inAnimate.m")
    assert model.where("joints", 1, "iUindex").line == 8
    assert model.where("bodies", 1, "p_d").line == 4  # never set: where the body was made


def read_bodies(tmp_path, body_lines: str):
    text = "function inBodies\n    include_global\n" + body_lines
    return read_dapbc_folder(write_folder(tmp_path, {"inBodies.m": text}, base={})).bodies


def test_continuation_comments_and_missing_semicolons(tmp_path):
    bodies = read_bodies(tmp_path, """
%{
B1.m = 99;
%}
B1 = Body_struct  % no semicolon
B1.r = [1.0; ...  comment after the continuation
        0.2]
B2 = Body_struct; B2.m = 2, B2.p = pi/6
Bodies = [B1; ...
          B2];
""")
    np.testing.assert_array_equal(bodies[0].r, [1.0, 0.2])
    assert bodies[0].m == 1.0 and bodies[1].m == 2.0


def test_row_vectors_transposes_and_arithmetic(tmp_path):
    bodies = read_bodies(tmp_path, """
a = 0.2; L = 1.0;
B1 = Body_struct;
B1.r = [1.0 a]';
B1.r_d = [2*a, -L/4].';
B1.p = -2^2 + 3*(1 - a)^2 - 10^-1;
B2 = Body_struct;
B2.r = B1.r + [0.25; -0.433];
B2.p = 350*pi/180;
B2.r(2) = B2.r(2) * 2;
Bodies = [B1, B2];
""")
    np.testing.assert_allclose(bodies[0].r, [1.0, 0.2])
    np.testing.assert_allclose(bodies[0].r_d, [0.4, -0.25])
    assert bodies[0].p == pytest.approx(-4 + 3 * 0.64 - 0.1)
    np.testing.assert_allclose(bodies[1].r, [1.25, 2 * (0.2 - 0.433)])
    assert bodies[1].p == pytest.approx(350 * math.pi / 180)


def test_functions_of_the_subset(tmp_path):
    bodies = read_bodies(tmp_path, """
B1 = Body_struct;
B1.m = sqrt(16) + abs(-1) + exp(0) + max(2, 3) + min([4 5 1]);
B1.J = sin(pi/2) + cos(0) + tan(0) + atan2(1, 1)*4/pi + deg2rad(180)/pi;
B1.p = mod(-1, 3) + sign(-2) + floor(2.5) + round(2.5) + hypot(3, 4) + norm([3; 4]);
B1.r = [sind(30); cosd(60)] + zeros(2, 1);
Bodies = [B1];
""")
    assert bodies[0].m == pytest.approx(4 + 1 + 1 + 3 + 1)
    assert bodies[0].J == pytest.approx(1 + 1 + 0 + 1 + 1)
    assert bodies[0].p == pytest.approx(2 - 1 + 2 + 3 + 5 + 5)
    np.testing.assert_allclose(bodies[0].r, [0.5, 0.5])


def test_if_blocks_in_an_in_file(tmp_path):
    bodies = read_bodies(tmp_path, """
correct = 1;
B1 = Body_struct;
if correct == 1 && ~0
    B1.p = -0.0367;
elseif correct > 1
    B1.p = 1;
else
    B1.p = 340*pi/180;
end
Bodies = [B1];
""")
    assert bodies[0].p == -0.0367


def test_struct_values_are_copied_like_matlab(tmp_path):
    bodies = read_bodies(tmp_path, """
B1 = Body_struct;
B2 = B1;
B2.m = 7;
Bodies = [B1; B2];
B1.m = 3;
Bodies(1).J = 9;
""")
    assert [b.m for b in bodies] == [1.0, 7.0] and bodies[0].J == 9.0


def test_funct_file_named_either_way_and_coefficients(tmp_path):
    text = """function inFuncts
    include_global

F1 = Funct_struct;
F1.type = 'a';
F1.coeff = [0 -2*pi 0];

F2 = Funct_struct;
F2.type = 'c';
F2.t_end = 2.0;
F2.dfdt_end = -2*pi;

Functs = [F1; F2];
"""
    model = read_dapbc_folder(write_folder(tmp_path, {"inFuncs.m": None, "inFuncts.m": text}))
    np.testing.assert_allclose(model.functs[0].coeff, [0, -2 * math.pi, 0])
    assert model.functs[1].type == "c" and model.functs[1].dfdt_end == pytest.approx(-2 * math.pi)


def test_missing_optional_files_give_empty_arrays(tmp_path):
    rod = {"inBodies.m": """function inBodies
    include_global
B1 = Body_struct;
B1.m = 1.0;
B1.J = 0.01;
B1.r = [0; 1];
B1.p = pi/4;
B1.r_d = [0; -6];
Bodies = [B1];
""", "inPoints.m": """function inPoints
    include_global
P1 = Point_struct;
P1.Bindex = 1;
P1.sPlocal = [ 0; -1];
Points = [P1];
"""}
    model = read_dapbc_folder(write_folder(tmp_path, rod, base={}))
    assert model.nB == 1 and model.uvectors == [] and model.joints == [] and model.forces == []
    assert model.window.xmin is None


def test_animation_points_and_script_files(tmp_path):
    animate = """include_global
C = Point_struct; C.Bindex = 2; C.sPlocal = [0.1; 0];
Points_anim = [C];
"""
    model = read_dapbc_folder(write_folder(tmp_path, {"inAnimate.m": animate}))
    assert len(model.points_anim) == 1 and model.points_anim[0].Bindex == 2


def test_a_folder_without_in_bodies_is_not_dapbc(tmp_path):
    assert not is_dapbc_folder(tmp_path)


def test_octave_spellings_and_hash_comments(tmp_path):
    bodies = read_bodies(tmp_path, """# an Octave comment
B1 = Body_struct;
if 1 != 2
    B1.m = 3;
endif
Bodies = [B1];
endfunction
""")
    assert bodies[0].m == 3.0


def test_cli_reports_a_reader_error_with_exit_code_2(tmp_path, capsys):
    """The project's CLI wrapper turns the reader's ModelError into `error: file:line: ...`, exit 2."""
    import typer

    from mbds.cli.errors import EXIT_BAD_INPUT, reported_errors

    folder = write_folder(tmp_path, {"inPoints.m": SP["inPoints.m"].replace("P3.Bindex = 2;", "P3.Bindex = 7;")})
    with pytest.raises(typer.Exit) as info, reported_errors(debug=False):
        read_dapbc_folder(folder)
    assert info.value.exit_code == EXIT_BAD_INPUT == 2
    assert capsys.readouterr().err.strip() == (f"error: {folder / 'inPoints.m'}:13: Point 3: Bindex = 7 names "
                                               "no body; the model has 2 bodies")


def test_setting_fields_from_python_values_checks_them_like_the_in_files():
    """For campaign variations (force.1.k = 40000): same checks, same located errors."""
    from mbds.errors import ModelError
    from mbds.io.dapbc.fields import set_field_value
    from mbds.io.dapbc.records import SourcePos

    force, pos = Force(), SourcePos("job.ini", 7)
    set_field_value(force, "k", 40000, pos)
    set_field_value(force, "wgt", [0.0, -2.0], pos)
    set_field_value(force, "type", "rot-sda", pos)
    set_field_value(force, "iBindex", 2.0, pos)
    assert (force.k, list(force.wgt), force.type, force.iBindex) == (40000.0, [0.0, -2.0], "rot-sda", 2)
    assert force.where("k") == pos
    for name, value, message in (("k", "stiff", "must be a number, not text"), ("k", [1, 2], "must be a number"),
                                 ("kk", 1, "did you mean 'k'"), ("iBindex", 0.5, "whole number"),
                                 ("k", None, "not a finite number"), ("k", {}, "not a number")):
        with pytest.raises(ModelError, match=message) as info:
            set_field_value(force, name, value, pos)
        assert str(info.value).startswith("job.ini:7: ")
