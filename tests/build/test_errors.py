"""Errors point at the declaration in the user's script that is wrong (file:line)."""

import inspect
import subprocess
import sys

import pytest
import sympy

from mbds.build import ModelBuilder
from mbds.build import energies as E
from mbds.build import shapes
from mbds.errors import ModelError

SQUARE = shapes.polygon([(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)])
HERE = __file__


def line_of(marker: str) -> int:
    """The line of this file that holds ``marker`` (a comment at the end of a declaration)."""
    lines = inspect.getsource(inspect.getmodule(line_of)).splitlines()
    return next(i for i, text in enumerate(lines, start=1) if text.rstrip().endswith(f"# {marker}"))


def raises_at(marker: str, message: str):
    return pytest.raises(ModelError, match=rf"^{HERE}:{line_of(marker)}: .*{message}")


def block(mb: ModelBuilder, **kwargs):
    return mb.body("block", SQUARE, mass=1.0, inertia=0.01, **kwargs)


def test_undefined_constant_names_the_energy_line():
    mb = ModelBuilder()
    b = block(mb)
    mb.generalized(b.y)
    mb.kinetic_energy(E.rigid_body_kinetic(b))
    mb.potential_energy(E.gravity(b.m, b.y, sympy.Symbol("c`g", real=True)))  # undefined constant
    with raises_at("undefined constant", r"potential energy: undefined constant c'g \(declare it"):
        mb.derive()


def test_undefined_symbol_and_undeclared_body():
    mb = ModelBuilder()
    b = block(mb)
    mb.generalized(b.x)
    mb.kinetic_energy(E.rigid_body_kinetic(b) + sympy.Symbol("k") * b.x**2)  # plain symbol
    with raises_at("plain symbol", "undefined symbol 'k'"):
        mb.derive()
    mb = ModelBuilder()
    b = block(mb)
    mb.generalized(b.x)
    ghost = sympy.Function("b`ghost`x", real=True)(sympy.Symbol("t", real=True))
    mb.kinetic_energy(E.rigid_body_kinetic(b) + sympy.diff(ghost) ** 2)  # no such body
    with raises_at("no such body", "no body 'ghost' is declared"):
        mb.derive()


def test_coordinate_in_no_energy_names_its_declaration():
    mb = ModelBuilder()
    b = block(mb)
    mb.generalized(b.x, b.y)  # y in no energy
    mb.kinetic_energy(b.m * sympy.diff(b.x) ** 2 / 2)
    with raises_at("y in no energy", r"b'block'y\[t\] appears in no energy, dissipation or virtual work"):
        mb.derive()


def test_coordinate_without_kinetic_energy():
    mb = ModelBuilder()
    b = block(mb)
    k = mb.constant("k", 1.0)
    mb.generalized(b.x, b.y)  # y only in V
    mb.kinetic_energy(b.m * sympy.diff(b.x) ** 2 / 2)
    mb.potential_energy(E.spring(k, b.y))
    with raises_at("y only in V", "has no kinetic energy"):
        mb.derive()


def test_singular_mass_matrix_at_the_start_state():
    """Two angles of one point mass on a rod, at φ1 = φ2: the mass matrix m l² [[1, c], [c, 1]]
    with c = cos(φ1 − φ2) is singular where the angles are equal."""
    mb = ModelBuilder()
    m, l = mb.constant("m", 1.0), mb.constant("l", 0.5)
    p1, p2 = mb.free("p1", 0.3), mb.free("p2", 0.3)
    mb.generalized(p1, p2)
    x = l * sympy.cos(p1) + l * sympy.cos(p2)
    y = l * sympy.sin(p1) + l * sympy.sin(p2)
    mb.kinetic_energy(E.point_mass_kinetic(m, x, y))  # singular at the start
    with raises_at("singular at the start", r"the mass matrix is singular at the start state .* g'p1\[t\], g'p2\[t\]"):
        mb.derive()


def test_open_and_clockwise_shapes_name_the_body_declaration():
    mb = ModelBuilder()
    with raises_at("open shape", "shape of body 'lid': not closed"):
        mb.body("lid", SQUARE[:-1], mass=1.0, inertia=0.01)  # open shape
    with raises_at("clockwise shape", "shape of body 'lid': .*clockwise"):
        mb.body("lid", SQUARE[::-1], mass=1.0, inertia=0.01)  # clockwise shape


def test_declaration_mistakes():
    mb = ModelBuilder()
    b = block(mb)
    with raises_at("duplicate constant", "declared twice"):
        mb.constant("g", 1.0), mb.constant("g", 2.0)  # duplicate constant
    with raises_at("twice a coordinate", "already a coordinate"):
        mb.generalized(b.x, b.x)  # twice a coordinate
    with raises_at("virtual first", "which is not declared"):
        mb.body("side", SQUARE, virtual_to="nothing")  # virtual first
    with raises_at("no mass", "needs mass and inertia, or density and thickness"):
        mb.body("light", SQUARE)  # no mass
    with raises_at("bad world key", "unknown world setting 'max_step'"):
        mb.world(max_step=1e-5)  # bad world key
    with raises_at("unknown watch body", "watch names body 'nobody'"):
        mb.watch("nobody")  # unknown watch body
    with raises_at("undeclared law constant", r"friction uses c'mu: only declared constants, temp and vRel"):
        mb.contact(b, friction=sympy.Symbol("c`mu", real=True))  # undeclared law constant


def test_velocity_in_potential_and_non_linear_virtual_work():
    mb = ModelBuilder()
    b = block(mb)
    mb.generalized(b.x)
    mb.kinetic_energy(E.rigid_body_kinetic(b))
    mb.potential_energy(sympy.diff(b.x) ** 2)  # velocity in V
    with raises_at("velocity in V", "may not depend on velocities"):
        mb.derive()
    mb = ModelBuilder()
    b = block(mb)
    mb.generalized(b.x)
    mb.kinetic_energy(E.rigid_body_kinetic(b))
    mb.virtual_work(E.force(1, 0, b.x, 0) ** 2)  # squared variation
    with raises_at("squared variation", "linear in the variations"):
        mb.derive()


def test_error_from_a_script_is_a_located_cli_style_message(tmp_path):
    """A script's error reads file:line: message, as the readers' errors do."""
    script = tmp_path / "model.py"
    script.write_text(
        "from mbds.build import ModelBuilder, shapes\n"
        "mb = ModelBuilder()\n"
        "mb.body('b', shapes.polygon([(0, 0), (0, 1), (1, 1), (1, 0)]), mass=1, inertia=1)\n"
    )
    with pytest.raises(ModelError) as error:
        exec(compile(script.read_text(), str(script), "exec"), {})
    assert str(error.value).startswith(f"{script}:3: shape of body 'b':")


def test_a_build_script_reports_its_error_with_exit_code_2(tmp_path):
    script = tmp_path / "model.py"
    script.write_text(
        "from mbds.build import ModelBuilder, shapes\n"
        "from mbds.build.script import run_build\n"
        "def build(folder):\n"
        "    mb = ModelBuilder()\n"
        "    mb.body('b', shapes.polygon([(0, 0), (0, 1), (1, 1), (1, 0)]), mass=1, inertia=1)\n"
        "run_build(build, 'unused')\n"
    )
    result = subprocess.run([sys.executable, str(script)], capture_output=True, text=True)
    assert result.returncode == 2
    assert result.stderr.startswith(f"error: {script}:5: shape of body 'b': the interior is on the right")
    assert "Traceback" not in result.stderr
