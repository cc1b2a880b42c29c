"""Malformed and nonsensical input, as a new user or an attacker would write it: each case is
refused with ``file:line: what is wrong`` (or the file, where there is no line) and exit code 2,
never a traceback, never accepted."""

import re
import time

import numpy as np
import pytest

from mbds.model.load import load_model
from tests.campaign.models import campaign, two_mass
from tests.cli.test_run import example, mbds


def edited(tmp_path, name, old, new):
    """A copy of campaigns/2mass with ``old`` replaced by ``new`` in file ``name``."""
    folder = example(tmp_path, "2mass")
    path = folder / name
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new, 1))
    return folder


def refused(result, where: str, *words: str) -> str:
    """The error output of a command that must exit 2 with ``where`` (``file:line``) and ``words``."""
    code, out, err = result
    assert code == 2, (code, out, err)
    assert "Traceback" not in err
    message = " ".join(err.split())
    assert f"error: {where}: " in message, message
    for word in words:
        assert word in message, (word, message)
    return message


MODEL_CASES = [  # file, old text, new text, file:line of the error (file name, line), words
    ("2mass.wld", "maximumTimestep = 5e-4", "LCPPivotToleranceMin = 1e3\nLCPPivotToleranceMax = 1e3",
     ("2mass.wld", 4), ["LCPPivotToleranceMin", "between 0 and 1"]),
    ("2mass.wld", "numberOfGeneralizedCoodinates = 3", "numberOfGeneralizedCoodinates = -3",
     ("2mass.wld", 2), ["must not be negative"]),
    ("2mass.wld", "breakTime = 0.5", "breakTime = 0.5\nwriteToHistoryMultipleOfMaximumTimestep = 0",
     ("2mass.wld", 7), ["writeToHistoryMultipleOfMaximumTimestep", "positive"]),
    ("2mass.wld", "body1 = mass1.bdy", "body1 = .", ("2mass.wld", 9), ["is a folder"]),
    ("2mass.wld", "dependentCoordinatesFile = current.dc", "dependentCoordinatesFile = missing.dc",
     ("2mass.wld", 7), ["missing.dc", "not found"]),
    ("2mass.cop", "friction=0.1", "friction=-0.1", ("2mass.cop", 2), ["friction", "must not be negative"]),
    ("2mass.cop", "restitutionNormal=0.7", "restitutionNormal=2", ("2mass.cop", 3), ["between 0 and 1"]),
    ("2mass.cop", "restitutionNormal=0.7", "restitutionNormal=-1", ("2mass.cop", 3), ["between 0 and 1"]),
    ("2mass.cop", "friction=0.1\nrestitutionNormal=0.7\nrestitutionTangent=0.2\nparameterNi=0\ninitialTemperature=0",
     "friction=0.1 - 0.01*temp\nrestitutionNormal=0.7\nrestitutionTangent=0.2\nparameterNi=0\ninitialTemperature=20",
     ("2mass.cop", 2), ["is -0.1 at temp = 20"]),
    ("mass1.bdy", "density = 2500", "density = -2500", ("mass1.bdy", 6), ["density", "positive"]),
    ("mass1.bdy", "shapeFile = mass1.exs", "shapeFile = nothing.exs", ("mass1.bdy", 5), ["nothing.exs"]),
]


@pytest.mark.parametrize(("name", "old", "new", "where", "words"), MODEL_CASES)
def test_nonsensical_model_values_are_refused_at_their_line(tmp_path, name, old, new, where, words):
    folder = edited(tmp_path, name, old, new)
    refused(mbds("check", "--no-compile", folder), f"{folder / where[0]}:{where[1]}", *words)


def test_binary_data_names_the_file_and_line(tmp_path):
    folder = example(tmp_path, "2mass")
    (folder / "2mass.cns").write_bytes(b"c'gravity = 9.81\nc'x = \x00\x01\n")
    refused(mbds("check", "--no-compile", folder), f"{folder / '2mass.cns'}:2", "NUL")


@pytest.mark.parametrize(("matrix", "words"), [
    ("0 0 0\n0 0 0\n0 0 0\n", ["not positive definite", "eigenvalues are 0, 0, 0"]),
    ("-b'mass1'm 0 0\n0 -b'mass1'm 0\n0 0 -b'mass1'Jzz\n", ["not positive definite"]),
    ("b'mass1'm b'mass1'm 0\nb'mass1'm b'mass1'm 0\n0 0 b'mass1'Jzz\n", ["not positive definite"]),
    ("b'mass1'm 1 0\n0 b'mass1'm 0\n0 0 b'mass1'Jzz\n", ["not symmetric"]),
])
def test_a_mass_matrix_not_symmetric_positive_definite_at_the_start_is_refused(tmp_path, matrix, words):
    folder = example(tmp_path, "2mass")
    (folder / "2mass.mmx").write_text(matrix)
    refused(mbds("check", "--no-compile", folder), str(folder / "2mass.mmx"), *words)


def test_mass_without_inertia_scales_the_shapes_inertia_and_says_so(tmp_path):
    plain = load_model(example(tmp_path / "a", "2mass"), compile=False)
    folder = edited(tmp_path / "b", "mass1.bdy", "correctOrigin =0", "correctOrigin =0\n[Mass properties]\nmass = 3")
    with pytest.warns(UserWarning, match="mass given without InertiaZZ"):
        given = load_model(folder, compile=False)
    # The same shape: Jzz / m is a property of the shape alone (radius of gyration squared).
    assert given.bodies[0].mass == 3
    assert np.isclose(given.bodies[0].inertia / 3, plain.bodies[0].inertia / plain.bodies[0].mass, rtol=1e-12)


JOB_CASES = [  # [campaign] text, line of the error in the job file, words
    ("contact.mass1-mass2.friction = 0.1, abc\n", 5, ["'abc'"]),
    ("contact.mass1-mass2.friction = 0.1, -0.2\n", 5, ["must not be negative"]),
    ("contact.mass1-mass2.restitutionNormal = 0.5, 1.5\n", 5, ["between 0 and 1"]),
    ("contact.mass1-mass2.friction = 0.1, nan\n", 5, ["nan"]),
    ("contact.mass1-mass2.friction = 0.1, inf\n", 5, ["inf"]),
    ("world.breakTime = 0.5, -1\n", 5, ["breakTime must be a positive time"]),
    ("world.breakTime = 0.5, nan\n", 5, ["nan"]),
    ("world.maximumTimestep = 1e-4, 0\n", 5, ["maximumTimestep", "positive"]),
    ("world.LCPPivotToleranceMin = 1e3\n", 5, ["between 0 and 1"]),
    ("c'gravity = 9.81, inf\n", 5, ["inf"]),
    ("contact.mass1-mass2.friction = 0.2; 0.4\n", 5, ["separate values by commas"]),
    ("contact.mass1-mass2.friction = 0.2 0.4\n", 5, ["separate values by commas"]),
    ("world.breakTime = 0.2 0.4\n", 5, ["separate values by commas"]),
    ("folder = ../../..\n", 5, ["not inside the job file's folder"]),
    ("folder = .\n", 5, ["not inside the job file's folder"]),
    ("folder = 000\n", 5, ["version folders"]),
    ("folder = /tmp/x\n", 5, ["relative to the job file"]),
    ("seed = 1\n[campaign]\nseed = 2\n", 6, ["given twice"]),
    ("replicates = 100000000000\n", 5, ["the plan has 500,000,000,000 tasks", "maxTasks"]),
    ("c'gravity = " + ", ".join(f"{9 + k / 1000:.3f}" for k in range(3000)) + "\n"
     + "contact.mass1-mass2.friction = " + ", ".join(f"{k / 10000:.4f}" for k in range(3000)) + "\n",
     5, ["9,000,000 variants", "maxTasks"]),
    ("maxTasks = 9\nreplicates = 2\n", 5, ["the plan has 10 tasks", "maxTasks = 9"]),
]


@pytest.mark.parametrize(("section", "line", "words"), JOB_CASES)
def test_bad_campaign_values_are_refused_at_their_job_file_line_by_status_and_run(tmp_path, section, line, words):
    job = two_mass(tmp_path, section, jobs="000-001")
    for command in ("status", "run"):
        start = time.perf_counter()
        refused(campaign(command, job), f"{job}:{line}", *words)
        assert time.perf_counter() - start < 10
    assert not (job.parent / "campaign").exists()


def test_a_world_file_that_is_not_one_is_named_with_the_job_files_line(tmp_path):
    job = two_mass(tmp_path, None)
    job.write_text(job.read_text() + "worldFile = /etc/passwd\n")
    refused(mbds("job", job), f"{job}:4", "not a .wld world file")
    refused(campaign("status", job), f"{job}:4", "not a .wld world file")


@pytest.fixture(scope="module")
def ran_2mass(tmp_path_factory):
    """campaigns/2mass with version 000 run for 0.01 s."""
    folder = example(tmp_path_factory.mktemp("ran"), "2mass")
    assert mbds("run", folder, "--break-time", 0.01)[0] == 0
    return folder


def test_a_complete_run_is_replaced_only_with_force(ran_2mass):
    version = ran_2mass / "000"
    refused(mbds("run", version, "--break-time", 0.01), str(version), "complete run", "--force")
    assert mbds("run", version, "--break-time", 0.01, "--force")[0] == 0


def test_edited_model_files_are_named_and_need_force_or_next(ran_2mass):
    cop = ran_2mass / "2mass.cop"
    cop.write_text(cop.read_text().replace("friction=0.1", "friction=0.3"))
    message = refused(mbds("run", ran_2mass, "--break-time", 0.01), str(ran_2mass), "2mass.cop", "--force", "mbds next")
    assert "mass1.bdy" not in message
    assert mbds("run", ran_2mass, "--break-time", 0.01, "--force")[0] == 0
    assert "friction=0.3" in (ran_2mass / "000" / "2mass.cop").read_text()


def test_an_output_replaced_by_a_folder_is_an_error_not_a_traceback(ran_2mass):
    version = ran_2mass / "000"
    (version / "data.txt").unlink()
    (version / "data.txt").mkdir()
    message = refused(mbds("run", version, "--break-time", 0.01, "--force"), str(version / "data.txt"), "folder")
    assert re.search("move it away", message)
    (version / "data.txt").rmdir()


def test_check_covers_the_job_files_and_their_campaign_folders(tmp_path):
    job = two_mass(tmp_path, "folder = ../..\n")
    for target in (job.parent, job):
        refused(mbds("check", "--no-compile", target), f"{job}:5", "not inside the job file's folder")
    job.write_text(job.read_text().replace("folder = ../..", "folder = runs"))
    code, out, err = mbds("check", "--no-compile", job.parent)
    assert code == 0, err
    assert f"ok {job}: 7 tasks in 1 chain(s)" in " ".join(out.split())
