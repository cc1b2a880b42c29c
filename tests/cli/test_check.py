"""`mbds check`: exit 0 on every example, exit 2 with file and line on broken copies."""

import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from mbds.cli.main import app
from tests.examples import copy_example

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ["2mass", "wearballs", "woodpecker", "double_pendulum"]


def run(*args):
    result = CliRunner().invoke(app, list(map(str, args)))
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("example", EXAMPLES)
def test_check_examples(example):
    code, out, err = run("check", ROOT / "campaigns" / example)
    assert code == 0, err
    assert "ok" in out and "bodies" in out and "contact pairs" in out


def test_check_console_script_runs_installed_entry_point():
    exe = Path(sys.executable).with_name("mbds")
    result = subprocess.run([str(exe), "check", "--no-compile", ROOT / "campaigns" / "2mass"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "mass1" in result.stdout and "0.735" in result.stdout


@pytest.fixture
def broken(tmp_path):
    folder = tmp_path / "2mass"
    copy_example("2mass", folder)
    return folder


def _replace(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))


def test_bad_number_in_body_file(broken):
    _replace(broken / "mass1.bdy", "density = 2500", "density = 25OO")
    code, out, err = run("check", "--no-compile", broken)
    assert code == 2
    assert f"{broken / 'mass1.bdy'}:" in err and "'25OO' is not a number" in err
    assert "Traceback" not in err


def test_unknown_constant_in_h_vector(broken):
    _replace(broken / "2mass.hv", "c'gravity", "c'gravitation")
    code, _, err = run("check", "--no-compile", broken)
    assert code == 2
    assert f"{broken / '2mass.hv'}:2: unknown constant c'gravitation" in err


def test_clockwise_shape(broken):
    exs = broken / "mass1.exs"
    lines = exs.read_text().splitlines()
    data = lines.index("%%data")
    xs, ys = lines[data + 1].split(), lines[data + 2].split()
    lines[data + 1], lines[data + 2] = " ".join(reversed(xs)), " ".join(reversed(ys))
    exs.write_text("\n".join(lines) + "\n")
    code, _, err = run("check", "--no-compile", broken)
    assert code == 2
    assert f"{exs}:{data + 1}:" in err and "clockwise" in err


def test_debug_shows_traceback(broken):
    _replace(broken / "2mass.hv", "c'gravity", "c'gravitation")
    code, _, err = run("check", "--no-compile", "--debug", broken)
    assert code == 2 and "Traceback" in err


def test_missing_folder(tmp_path):
    code, _, err = run("check", tmp_path / "nothing")
    assert code == 2 and "no such file or folder" in err
