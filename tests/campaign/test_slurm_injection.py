"""Hostile values through every option of `mbds-campaign submit --dry-run` and through the job
file's name and folder: each is refused (exit 2, no traceback) or lands in the script quoted, so
that the script is valid bash, every ``#SBATCH`` line stands before the first command, and the
script runs no command but the template's."""

import re
import shlex
import shutil
import subprocess

import pytest

from mbds.campaign.slurm import TEMPLATE
from tests.campaign.models import campaign, two_mass

HOSTILE = [
    "a\nid", "a\rid", "$(touch pwned)", "`touch pwned`", "a'b", 'a"b', "a b", "n\u00e9", "a;id", "a#b",
    "a\\", "--x", "a=b", "$HOME", "a&&id", "*", "a\tb", "",
]
OPTIONS = ["--job-name", "--account", "--partition", "--time", "--ntasks", "--signal-seconds", "--nodes",
           "--mem-per-cpu", "--mpi", "--preamble"]
NAMES = ("--job-name", "--account", "--partition", "--mpi")
MARK = "PLACEHOLDER"


def template_commands() -> list[list[str]]:
    """The template's command lines as shell words, each placeholder one word ``MARK`` (srun's
    options left out, the preamble line too: no preamble is given)."""
    text = TEMPLATE.read_text().replace("{{srun_options}}", "").replace("{{preamble}}\n", "")
    text = re.sub(r"\{\{\w+\}\}", MARK, text)
    return [shlex.split(line, comments=True) for line in text.splitlines() if _is_command(line)]


def _is_command(line: str) -> bool:
    return bool(line.strip()) and not line.lstrip().startswith("#")


def sbatch_argument(value: str) -> str | None:
    """The one argument sbatch reads from a directive's value, as sbatch's parser does
    (quotes, backslash escapes, an unquoted blank or ``#`` ends it); None when anything but
    blanks follows it."""
    out, quote, escape, k = [], "", False, 0
    while k < len(value):
        ch = value[k]
        if escape:
            out.append(ch)
            escape = False
        elif ch == "\\":
            escape = True
        elif quote:
            if ch == quote:
                quote = ""
            else:
                out.append(ch)
        elif ch in "\"'":
            quote = ch
        elif ch.isspace() or ch == "#":
            break
        else:
            out.append(ch)
        k += 1
    return "".join(out) if not value[k:].strip() else None


def assert_safe(script: str, tmp_path) -> None:
    """The checks of the module docstring."""
    path = tmp_path / "check.sbatch"
    path.write_text(script)
    checked = subprocess.run(["bash", "-n", str(path)], capture_output=True, text=True)
    assert checked.returncode == 0, checked.stderr
    lines = script.splitlines()
    assert lines[0] == "#!/bin/bash"
    first = next(k for k, line in enumerate(lines) if _is_command(line))
    for k, line in enumerate(lines):
        if line.startswith("#SBATCH"):
            assert k < first, f"#SBATCH after the first command: {line!r}"
            option, _, value = line[len("#SBATCH "):].partition("=")
            assert re.fullmatch(r"--[a-z-]+", option), line
            assert sbatch_argument(value) is not None, line
        elif not _is_command(line):
            assert line == "" or line.startswith("#"), line
    commands = [shlex.split(line, comments=True) for line in lines if _is_command(line)]
    commands = [[w for w in words if not (words[0] == "srun" and re.fullmatch(r"--mpi=[A-Za-z0-9._-]+", w))]
                for words in commands]
    expected = template_commands()
    assert len(commands) == len(expected)
    for words, pattern in zip(commands, expected):
        assert len(words) == len(pattern), words
        for word, want in zip(words, pattern):
            assert re.fullmatch(re.escape(want).replace(MARK, ".+"), word, re.S), (words, pattern)


def submit_dry_run(job, *options):
    code, out, err = campaign("submit", job, "--dry-run", *options)
    assert code in (0, 2), err
    assert "Traceback" not in err
    if code == 2:
        assert "error:" in err or "Invalid value" in err
    return code, out


@pytest.mark.parametrize("option", OPTIONS)
def test_hostile_option_values_are_refused_or_harmless(tmp_path, option):
    job = two_mass(tmp_path, "c'gravity = 9.81, 5\n")
    for value in HOSTILE:
        code, out = submit_dry_run(job, option, value)
        if code == 0:
            assert_safe(out, tmp_path)
            assert "pwned" not in out or option not in NAMES
        if option in NAMES and not re.fullmatch(r"[A-Za-z0-9._-]*", value):
            assert code == 2, (option, value)


@pytest.mark.parametrize("name", [v for v in HOSTILE if v and "/" not in v])
def test_hostile_job_file_names_and_folders_are_refused_or_harmless(tmp_path, name):
    job = two_mass(tmp_path, "c'gravity = 9.81, 5\n")
    text = job.read_text().replace("[main]\n", "[main]\nworldFile = 2mass.wld\n")
    folder = tmp_path / f"x{name}y"
    shutil.copytree(job.parent, folder)
    hostile_job = folder / f"x{name}.job"
    hostile_job.write_text(text)
    code, out = submit_dry_run(hostile_job)
    if "\n" in name or "\r" in name or "\t" in name:
        assert code == 2
    else:
        assert code == 0
        assert_safe(out, tmp_path)
        assert re.search(r"^#SBATCH --job-name=mbds-[A-Za-z0-9._-]+$", out, re.M)


def test_the_checker_catches_an_injected_line(tmp_path):
    job = two_mass(tmp_path, None)
    code, out = submit_dry_run(job)
    assert code == 0
    assert_safe(out, tmp_path)
    with pytest.raises(AssertionError):
        assert_safe(out.replace("#SBATCH --ntasks", "touch pwned\n#SBATCH --ntasks"), tmp_path)
    with pytest.raises(AssertionError):
        assert_safe(out.replace("export OMP", "id; export OMP"), tmp_path)
