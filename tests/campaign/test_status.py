"""`mbds-campaign status`: chains by versions with their states, failures and progress; plain
text when the output is not a terminal."""

import io

from rich.console import Console

from mbds.campaign.ledger import DONE, FAILED, RUNNING, Ledger
from mbds.campaign.plan import expand
from mbds.cli.campaign_status import print_status
from tests.campaign.models import campaign, two_mass

SECTION = "c'gravity = 9.81, 5\ncontact.mass1-mass2.friction = 0.1\n"


def started(tmp_path):
    """A campaign of two chains of three versions: v00 stopped by a failure in 001, v01 at 001."""
    job = two_mass(tmp_path, SECTION)
    plan = expand(job)
    ledger = Ledger.load(plan.folder)
    ledger.bind(plan)
    for task_id in ("v00/prepare", "v00/000/run", "v00/000/wear", "v01/prepare", "v01/000/run", "v01/000/wear"):
        ledger.mark(task_id, DONE)
    ledger.mark("v00/001/run", FAILED, reason="2mass.wld:3: the run stopped")
    ledger.mark("v01/001/run", RUNNING, rank=1)
    return job, plan, ledger


def test_status_shows_each_chain_and_version_with_its_state(tmp_path):
    job, plan, ledger = started(tmp_path)
    code, out, err = campaign("status", job)
    assert code == 0, err
    lines = out.splitlines()
    header = next(i for i, line in enumerate(lines) if line.split()[:1] == ["chain"])
    assert lines[header].split() == ["chain", "000", "001", "002"]
    assert lines[header + 1].split() == ["v00", "done", "failed", "blocked"]
    assert lines[header + 2].split() == ["v01", "done", "running", "pending"]
    assert "failed v00/001/run: 2mass.wld:3: the run stopped" in out
    assert "6 of 14 tasks done, 1 running, 1 failed, 3 blocked, 3 pending" in out
    assert "\x1b[" not in out  # plain text in a pipe


def test_status_of_a_campaign_not_begun_is_all_pending(tmp_path):
    job = two_mass(tmp_path, SECTION)
    code, out, err = campaign("status", job)
    assert code == 0, err
    assert "0 of 14 tasks done, 14 pending" in out
    assert not (job.parent / "campaign").exists()  # status writes nothing


def test_status_on_a_terminal_colours_the_states(tmp_path):
    job, plan, ledger = started(tmp_path)
    buffer = io.StringIO()
    print_status(plan, ledger, Console(file=buffer, force_terminal=True, width=120))
    out = buffer.getvalue()
    assert "\x1b[" in out and "failed" in out and "variants" in out and "c'gravity" in out


def test_bit_identical_replicates_are_reported(tmp_path):
    """2mass never lets the lexicographic tolerance decide a pivot: its replicates' runs are
    bit-identical whatever their seeds, and status and the collected provenance say so."""
    import json

    import mbds

    job = two_mass(tmp_path, "replicates = 2\nmode = ensemble\nworld.breakTime = 0.1\n", jobs="000")
    job.write_text(job.read_text().replace("[main]", "[main]\nlexicoRandomizationRange = 1e-10, 1e-6", 1))
    code, _, err = campaign("run", job)
    assert code == 0, err
    code, out, _ = campaign("status", job)
    assert code == 0 and "replicates bit-identical in 1 of 1 versions run in full (v00/000)" in out
    assert campaign("collect", job)[0] == 0
    tree = mbds.open_campaign(expand(job).folder)
    assert json.loads(tree.ds.attrs["identical_replicates"]) == ["v00/000"]
    tree.close()


def test_status_of_a_100000_task_plan_answers_with_its_size_and_the_first_chains(tmp_path):
    """The plan is built without a path per task and the table is cut at 100 chains; how long
    it takes is measured by benchmarks/status.py (docs/performance.md), not here."""
    gravity = ", ".join(f"{9 + k / 100:.2f}" for k in range(100))
    job = two_mass(tmp_path, f"c'gravity = {gravity}\nreplicates = 143\n")  # 100 x 143 chains of 7 tasks
    plan = expand(job)
    out = io.StringIO()
    print_status(plan, Ledger.read(plan.folder), Console(file=out, width=160))
    assert len(plan.tasks) == 100_100 and "0 of 100100 tasks done" in out.getvalue()
    assert "... and 14200 more chains (first 100 shown)" in out.getvalue()
