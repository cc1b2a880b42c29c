"""Plan expansion: variants as a cartesian product, chains and replicates, stable task ids,
seeds, dependencies; a job file without [campaign] is the chain `mbds job` runs."""

import pytest

from mbds.campaign.ledger import DONE, FAILED, RUNNING, Ledger
from mbds.campaign.plan import (
    PREPARE,
    RUN,
    WEAR,
    expand,
    ready_tasks,
    replicate_seed,
    task_states,
)
from mbds.errors import ModelError
from mbds.io.job import read_job
from tests.campaign.models import campaign, two_mass

VARIED = "c'gravity = 9.81, 5\ncontact.mass1-mass2.friction = 0.1, 0.2, 0.3\n"


def test_variants_are_the_cartesian_product_last_key_fastest(tmp_path):
    plan = expand(two_mass(tmp_path, VARIED))
    assert [v.id for v in plan.variants] == ["v00", "v01", "v02", "v03", "v04", "v05"]
    assert [tuple(v.values.values()) for v in plan.variants] == [
        ("9.81", "0.1"), ("9.81", "0.2"), ("9.81", "0.3"), ("5", "0.1"), ("5", "0.2"), ("5", "0.3")]
    assert [c.folder for c in plan.chains] == [tmp_path / "2mass" / "campaign" / v.id for v in plan.variants]


def test_task_ids_are_stable_and_name_chain_version_and_kind(tmp_path):
    job = two_mass(tmp_path, VARIED + "replicates = 2\nmode = ensemble\n", jobs="000-001")
    first, again = expand(job), expand(job)
    assert [t.id for t in first.tasks] == [t.id for t in again.tasks]
    assert [t.id for t in first.tasks[:7]] == [
        "v00/prepare", "v00/000/r0/run", "v00/000/r1/run", "v00/000/wear",
        "v00/001/r0/run", "v00/001/r1/run", "v00/001/wear"]
    assert len({t.id for t in first.tasks}) == len(first.tasks) == 6 * 7
    run = first.task("v00/001/r1/run")
    assert run.folder == tmp_path / "2mass" / "campaign" / "v00" / "001" / "r1" and run.version == 1
    wear = first.task("v00/001/wear")
    assert wear.inputs == (run.folder.parent / "r0", run.folder)


def test_replicate_chains_have_their_own_folders_and_distinct_deterministic_seeds(tmp_path):
    job = two_mass(tmp_path, VARIED + "replicates = 3\nseed = 11\n")
    plan = expand(job)
    assert len(plan.chains) == 18
    assert plan.chains[1].id == "v00/r1" and plan.chains[1].folder == tmp_path / "2mass" / "campaign" / "v00" / "r1"
    seeds = [c.seed for c in plan.chains]
    assert len(set(seeds)) == 18
    assert seeds == [c.seed for c in expand(job).chains]
    assert seeds[4] == replicate_seed(11, 1, 1)
    assert all(t.seed == t.options.seed for t in plan.tasks if t.kind == RUN)
    assert plan.task("v01/r1/002/run").options.seed == replicate_seed(11, 1, 1)
    job.write_text(job.read_text().replace("seed = 11", "seed = 12"))
    assert not set(seeds) & {c.seed for c in expand(job).chains}


def test_every_task_comes_after_the_tasks_it_depends_on(tmp_path):
    plan = expand(two_mass(tmp_path, VARIED + "replicates = 2\nmode = ensemble\n"))
    seen = set()
    for task in plan.tasks:
        assert set(task.depends_on) <= seen
        seen.add(task.id)
    assert plan.task("v03/002/r0/run").depends_on == ("v03/001/wear",)
    assert plan.task("v03/000/r1/run").depends_on == ("v03/prepare",)
    assert plan.task("v03/002/wear").depends_on == ("v03/002/r0/run", "v03/002/r1/run")


def test_job_without_campaign_section_is_the_chain_mbds_job_runs(tmp_path):
    job = two_mass(tmp_path, None, jobs="000-003")
    plan = expand(job)
    assert plan.variants == [] and len(plan.chains) == 1
    (chain,) = plan.chains
    assert chain.folder == job.parent and chain.seed == 0
    runs = [t for t in plan.tasks if t.kind == RUN]
    assert [t.version for t in runs] == read_job(job).versions == [0, 1, 2, 3]
    assert [t.folder for t in runs] == [job.parent / f"{n:03d}" for n in range(4)]
    assert all(t.options.seed == 0 and t.options.job == read_job(job).settings for t in runs)
    assert [t.kind for t in plan.tasks] == [PREPARE] + [RUN, WEAR] * 4
    assert plan.task("2mass/prepare").source == job.parent / "2mass.wld"
    assert [t.kind for t in expand(two_mass(tmp_path / "b", None, jobs="000", create=0)).tasks] == [PREPARE, RUN]


def test_failed_task_blocks_only_the_rest_of_its_chain(tmp_path):
    plan = expand(two_mass(tmp_path, "c'gravity = 9.81, 5\n", jobs="000-001"))
    ledger = Ledger(plan.folder)
    assert [t.id for t in ready_tasks(plan, ledger)] == ["v00/prepare", "v01/prepare"]
    for task_id in ("v00/prepare", "v01/prepare", "v01/000/run"):
        ledger.mark(task_id, DONE)
    ledger.mark("v00/000/run", FAILED, reason="the run stopped")
    states = task_states(plan, ledger)
    assert [states[f"v00/{t}"] for t in ("000/wear", "001/run", "001/wear")] == ["blocked"] * 3
    assert [t.id for t in ready_tasks(plan, ledger)] == ["v01/000/wear"]
    ledger.mark("v01/000/wear", RUNNING, rank=2)
    assert ready_tasks(plan, ledger) == []


@pytest.mark.parametrize("section, line, message", [
    ("seed = 1\nreplicate = 2\n", 6, "unknown key 'replicate'"),
    ("c'gravity = 1\nc'mu = 0.1, 0.2\n", 6, "constant c'mu is not in the model's constants file"),
    ("contact.mass1-wall.friction = 0.1\n", 5, "has no section [mass1-wall] (it has [mass1-mass2])"),
    ("contact.mass1-mass2.resistingPenetration = T:F\n", 5, "cannot be varied"),
    ("world.constantListFile = a.cns, b.cns\n", 5, "cannot be varied"),
    ("world.maximumTimestp = 1e-5\n", 5, "'maximumTimestp' is not a world file [main] key"),
    ("world.maximumTimestep = 1e-5, fast\n", 5, "'fast' is not a number"),
    ("c'gravity = 1, 2, 1\n", 5, "lists a value twice"),
    ("mode = parallel\n", 5, "mode must be 'chains' or 'ensemble'"),
    ("replicates = 0\n", 5, "replicates must be 1 or more"),
    ("seed = 1\nseed = 2\n", 6, "'seed' given twice (first on line 5)"),
    ("world.maximumTimestep = 1e-5\nworld.MAXIMUMTIMESTEP = 2e-5\n", 6, "given twice (first on line 5)"),
])
def test_bad_campaign_section_names_job_file_and_line(tmp_path, section, line, message):
    job = two_mass(tmp_path, section)
    with pytest.raises(ModelError) as caught:
        expand(job)
    assert caught.value.line == line and message in caught.value.message
    code, out, err = campaign("status", job)
    assert code == 2 and f"{job}:{line}: " in err and "Traceback" not in err


def test_campaign_versions_must_start_at_000_and_follow_one_another(tmp_path):
    job = two_mass(tmp_path, "c'gravity = 1\n", jobs="001-002")
    (job.parent / "001").mkdir()
    (job.parent / "001" / "2mass.wld").write_text("")  # an existing version in the model folder: not in a variant's
    with pytest.raises(ModelError, match="consecutive versions from 000") as caught:
        expand(job)
    assert caught.value.line == 2


def test_ready_tasks_start_with_the_chain_with_most_work_left(tmp_path):
    """Longest-processing-time first: a chain with more versions left starts before one that is
    nearly done, whatever their order in the plan."""
    from mbds.campaign.priority import by_remaining_work

    plan = expand(two_mass(tmp_path, "c'gravity = 9.81, 5\n", jobs="000-002"))
    ledger = Ledger(plan.folder)
    ahead = [t for t in plan.tasks if t.chain == "v01"][:5]  # v01: prepare, 000 run and wear, 001 run and wear
    for task in ahead:
        ledger.mark(task.id, DONE, save=False, wall={"prepare": 0.01, "run": 2.0, "wear": 0.2}[task.kind])
    ready = ready_tasks(plan, ledger)
    assert [t.id for t in ready] == ["v00/prepare", "v01/002/run"]  # plan order
    assert [t.id for t in by_remaining_work(plan, ledger, ready)] == ["v00/prepare", "v01/002/run"]
    ledger.mark("v00/prepare", DONE, save=False, wall=0.01)
    ready = ready_tasks(plan, ledger)
    assert [t.id for t in by_remaining_work(plan, ledger, ready)] == ["v00/000/run", "v01/002/run"]
    # v01 has the longer tasks left once v00 is far ahead
    for task in [t for t in plan.tasks if t.chain == "v00"][1:5]:
        ledger.mark(task.id, DONE, save=False, wall={"run": 2.0, "wear": 0.2}[task.kind])
    ledger.tasks.pop("v01/001/wear")  # v01 is back at 001's wear: two tasks more than v00
    ready = ready_tasks(plan, ledger)
    assert [t.id for t in by_remaining_work(plan, ledger, ready)] == ["v01/001/wear", "v00/002/run"]
