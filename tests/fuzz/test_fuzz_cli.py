"""Fuzzing every input file type through the command line: a mutated model file (``mbds check``),
job file or ``[campaign]`` section (``mbds-campaign status``) and DAP_BC in-file (its reader)
ends in exit code 0, or in exit code 2 with ``error: file:line: ...`` (or ``error: file: ...``
where no line exists) naming a file of the model; never another exit code, never a traceback,
and within a few seconds."""

from __future__ import annotations

import re
import shutil
import tempfile
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from typer.testing import CliRunner

from mbds.cli.campaign import app as campaign_app
from mbds.cli.main import app as mbds_app
from mbds.errors import ModelError
from mbds.io.dapbc import read_dapbc_folder
from tests.dapbc_io.folders import write_folder
from tests.examples import copy_example
from tests.fuzz.generators import mutated, write

SECONDS = 5.0
"""The longest one input may take to be accepted or refused."""
FUZZ = settings(max_examples=40, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
_ERROR = re.compile(r"^error: (?P<file>.+?)(:(?P<line>\d+))?: \S", re.M)


@pytest.fixture(scope="module")
def model(tmp_path_factory) -> Path:
    """A pristine copy of campaigns/2mass, copied again for each example."""
    return copy_example("2mass", tmp_path_factory.mktemp("fuzz") / "2mass")


def assert_clean(result, folder: Path, started: float) -> None:
    """Exit 0, or exit 2 with a located error naming a file in ``folder``; fast; no traceback."""
    elapsed = time.perf_counter() - started
    assert elapsed < SECONDS, f"took {elapsed:.1f} s"
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception  # shows the traceback
    assert result.exit_code in (0, 2), (result.exit_code, result.stderr)
    assert "Traceback" not in result.stderr
    if result.exit_code == 2:
        found = _ERROR.search(result.stderr)
        assert found, result.stderr
        assert Path(found["file"]).resolve().is_relative_to(folder.resolve()), result.stderr


def run_mutated(model: Path, name: str, text: str, app, *args: str) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "2mass"
        shutil.copytree(model, folder)
        write(folder, name, text)
        started = time.perf_counter()
        result = CliRunner().invoke(app, [*args, str(folder / name) if name.endswith(".job") else str(folder)])
        assert_clean(result, folder, started)


@FUZZ
@given(mutated("model"))
def test_mutated_model_files(model, mutation):
    run_mutated(model, *mutation, mbds_app, "check", "--no-compile")


@FUZZ
@given(mutated("job"))
def test_mutated_job_files(model, mutation):
    run_mutated(model, *mutation, campaign_app, "status")


@FUZZ
@given(mutated("campaign"))
def test_mutated_campaign_sections(model, mutation):
    run_mutated(model, *mutation, campaign_app, "status")


@FUZZ
@given(mutated("dapbc"))
def test_mutated_dapbc_in_files(mutation):
    name, text = mutation
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_folder(Path(tmp), {})
        write(folder, name, text)
        started = time.perf_counter()
        try:
            read_dapbc_folder(folder)
        except ModelError as error:
            assert error.file is not None and Path(error.file).parent == folder, str(error)
        assert time.perf_counter() - started < SECONDS


@pytest.mark.parametrize(("code", "stderr", "exception"), [
    (2, "error: no file named here\n", None),
    (2, "error: /elsewhere/2mass.wld:3: outside the model\n", None),
    (1, "", None),
    (1, "", ValueError("an uncaught error")),
])
def test_the_checks_refuse_what_they_must(tmp_path, code, stderr, exception):
    class Result:
        exit_code, exception = code, None

    Result.stderr, Result.exception = stderr, exception
    with pytest.raises((AssertionError, ValueError)):
        assert_clean(Result, tmp_path, time.perf_counter())
    if code == 2:
        Result.stderr = f"error: {tmp_path / '2mass.wld'}:3: a located error\n"
        assert_clean(Result, tmp_path, time.perf_counter())
