"""Each variant's compiled model is made ready once, before its first run: the prepare task finds
the variant's structure (the hash of its generated source) on the worker, and the scheduling
process compiles or loads each structure before it hands out a run that needs it, so no task
compiles and the workers need not wait for a check of every variant before the first task."""

import json

from mbds.campaign.executors import Sequential
from mbds.campaign.plan import expand
from mbds.campaign.run import run_campaign, warm_up_first
from tests.campaign.models import campaign, two_mass

# a friction law that depends on the sliding speed is code; a number is a parameter
TWO_STRUCTURES = "contact.mass1-mass2.friction = 0.1, 0.2, 0.1 + 0.01*vRel\nworld.breakTime = 0.02\n"


def test_variants_of_two_structures_each_made_ready_before_their_runs(tmp_path):
    plan = expand(two_mass(tmp_path, TWO_STRUCTURES, jobs="000-001"))
    structures = warm_up_first(plan)
    assert structures.count == 1  # only the first variant's, before any task
    outcome = run_campaign(plan, Sequential(lambda: False), lambda: False, structures=structures)
    assert len(outcome.done) == len(plan.tasks) and not outcome.failed
    assert structures.count == 2
    ledger = json.loads((plan.folder / "ledger.json").read_text())["tasks"]
    keys = {chain: ledger[f"{chain}/prepare"]["structure"] for chain in ("v00", "v01", "v02")}
    assert keys["v00"] == keys["v01"] != keys["v02"]
    assert {entry["compiled"] for entry in ledger.values()} == {0}


def test_the_command_says_the_other_variants_are_checked_as_they_come(tmp_path):
    job = two_mass(tmp_path, TWO_STRUCTURES, jobs="000")
    code, _, err = campaign("run", job)
    assert code == 0, err
    assert "warm-up: 1 distinct model(s) ready, the other variants' checked as their chains are prepared" in err
    ledger = json.loads((job.parent / "campaign" / "ledger.json").read_text())["tasks"]
    assert {entry["compiled"] for entry in ledger.values()} == {0}
