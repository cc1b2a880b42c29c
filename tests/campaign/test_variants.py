"""Variant folders: a copy of the model with the variant's values written in, read back with
mbds.io; the files a variant does not change are copied byte for byte."""

import hashlib
import re

import pytest

from mbds.campaign.ledger import DONE
from mbds.campaign.plan import expand
from mbds.campaign.tasks import run_task
from mbds.errors import ModelError
from mbds.io.folder import read_model_files
from tests.campaign.models import two_mass

SECTION = "c'gravity = 9.81, 1.62\ncontact.mass1-mass2.friction = 0.1, 2*c'gravity/10\nworld.maximumTimestep = 2e-4\n"


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_each_variant_folder_holds_its_values(tmp_path):
    job = two_mass(tmp_path, SECTION, jobs="000", create=0)
    originals = {p.name: digest(p) for p in job.parent.iterdir() if p.is_file()}
    plan = expand(job)
    for task in plan.tasks[::2]:
        assert task.kind == "prepare"
        result = run_task(task)
        assert result["state"] == DONE, result
        assert result["output"] == str(task.folder / "000")
    expected = [(9.81, "0.1"), (9.81, "2*c'gravity/10"), (1.62, "0.1"), (1.62, "2*c'gravity/10")]
    for chain, (gravity, friction) in zip(plan.chains, expected):
        for folder in (chain.folder, chain.folder / "000"):
            files = read_model_files(folder)
            assert files.constants.values["gravity"] == gravity
            (section,) = files.contacts.sections
            assert section.law.friction.text == friction
            assert section.law.restitution_normal.text == "0.7"  # kept
            assert files.world.settings.maximum_timestep == pytest.approx(2e-4)
            assert files.world.settings.break_time.text == "0.5"
            assert [b.text for b in files.world.bodies] == ["mass1.bdy", "mass2.bdy"]
            for name in ("mass1.bdy", "mass1.exs", "2mass.mmx", "2mass.gc"):
                assert digest(folder / name) == originals[name]
    assert {p.name: digest(p) for p in job.parent.iterdir() if p.is_file()} == originals  # the model is untouched


def test_a_variant_world_that_fails_the_world_checks_is_refused_at_its_line(tmp_path):
    job = two_mass(tmp_path, "replicates = 1\nworld.minimumTimestep = 1e-12, 1\n")
    with pytest.raises(ModelError) as caught:
        expand(job)
    assert caught.value.line == 6 and caught.value.file == str(job)
    assert "variant v01 (world.minimumTimestep = 1): minimumTimestep is larger than maximumTimestep" in str(caught.value)


def test_a_value_that_breaks_the_model_is_refused_at_its_job_file_line(tmp_path):
    job = two_mass(tmp_path, "contact.mass1-mass2.friction = 0.1, 2*c'nothing\n", jobs="000")
    with pytest.raises(ModelError) as caught:
        expand(job)
    assert str(caught.value).startswith(f"{job}:5: ") and "c'nothing" in str(caught.value)
    assert not (job.parent / "campaign").exists()


def test_values_are_written_with_the_models_decimal_separator(tmp_path):
    job = two_mass(tmp_path, "c'gravity = 1.62\ncontact.mass1-mass2.friction = 0.25\nworld.maximumTimestep = 2.5e-4\n",
                   jobs="000", create=0)
    for path in job.parent.iterdir():  # the same model written with decimalSeparator = ,
        if path.suffix != ".job":
            path.write_text(re.sub(r"(\d)\.(\d)", r"\1,\2", path.read_text()))
    world = job.parent / "2mass.wld"
    world.write_text(world.read_text().replace("[main]\n", "[main]\ndecimalSeparator = ,\n", 1))
    task = expand(job).task("v00/prepare")
    assert run_task(task)["state"] == DONE
    files = read_model_files(task.folder / "000")
    assert files.constants.values["gravity"] == 1.62 and "c'gravity = 1,62" in (task.folder / "2mass.cns").read_text()
    assert files.contacts.sections[0].law.friction.text == "0,25"
    assert files.world.settings.maximum_timestep == 2.5e-4


def test_linked_keys_take_their_values_together(tmp_path):
    job = two_mass(tmp_path, "c'gravity = 9.81, 5, 1.62\ncontact.mass1-mass2.friction = 0.1, 0.2, 0.3\n"
                   "contact.mass1-mass2.restitutionNormal = 0.5, 0.7\n"
                   "zip = c'gravity, contact.mass1-mass2.friction\n", jobs="000", create=0)
    plan = expand(job)
    assert [tuple(v.values.values()) for v in plan.variants] == [
        ("9.81", "0.1", "0.5"), ("9.81", "0.1", "0.7"), ("5", "0.2", "0.5"), ("5", "0.2", "0.7"),
        ("1.62", "0.3", "0.5"), ("1.62", "0.3", "0.7")]


@pytest.mark.parametrize(("zip_line", "words"), [
    ("zip = c'gravity, contact.mass1-mass2.restitutionNormal", "as many values each"),
    ("zip = c'gravity, c'nothing", "'c'nothing' is not a varied key"),
    ("zip = c'gravity", "two varied keys or more"),
])
def test_bad_links_are_refused_at_their_line(tmp_path, zip_line, words):
    job = two_mass(tmp_path, "c'gravity = 9.81, 5\ncontact.mass1-mass2.restitutionNormal = 0.5, 0.6, 0.7\n"
                   + zip_line + "\n", jobs="000", create=0)
    with pytest.raises(ModelError) as caught:
        expand(job)
    assert str(caught.value).startswith(f"{job}:7: ") and words in str(caught.value)
