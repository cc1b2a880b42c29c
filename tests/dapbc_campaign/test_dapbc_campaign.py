"""Campaigns over a DAP_BC model (docs/campaigns.md, "DAP_BC models"): the plan of a job naming
a DAP_BC folder, its errors at the job file's line, runs in one process and on 2 MPI ranks with
bit-identical collected results, resume, and the physics across variants."""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import mbds
from mbds.campaign.collect import collect
from mbds.campaign.dapbc_variants import apply_variant
from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import DAP_BC, expand
from mbds.cli.main import app as mbds_app
from mbds.errors import ModelError
from mbds.io.dapbc import read_dapbc_folder
from mbds.model.dapbc import build_system
from tests.campaign.models import campaign

ROOT = Path(__file__).resolve().parents[2]
SWEEP = ROOT / "campaigns" / "dap_bc_sweep"
MPIEXEC = Path(sys.executable).parent / "mpiexec"
MAIN = "[main]\nmodelFolder = oscillator\nfinalTime = 3\nreportStep = 0.005\nrtol = 1e-9\natol = 1e-12\n"
TWO = "[campaign]\nforce.1.k = 20, 80\n"


def sweep_job(tmp_path: Path, text: str, name: str = "sweep") -> Path:
    """A copy of campaigns/dap_bc_sweep/oscillator beside a job file of ``text``."""
    folder = tmp_path / name
    if not (folder / "oscillator").is_dir():
        shutil.copytree(SWEEP / "oscillator", folder / "oscillator")
    job = folder / "sweep.job"
    job.write_text(text)
    return job


def test_the_example_plans_one_run_per_variant():
    plan = expand(SWEEP / "sweep.job")
    assert plan.model == DAP_BC
    assert [v.values for v in plan.variants] == [
        {"force.1.k": "20", "body.1.m": "1"}, {"force.1.k": "20", "body.1.m": "2"},
        {"force.1.k": "80", "body.1.m": "1"}, {"force.1.k": "80", "body.1.m": "2"}]
    assert [t.id for t in plan.tasks] == [f"v0{k}/000/run" for k in range(4)]
    assert {t.kind for t in plan.tasks} == {DAP_BC} and all(not t.depends_on for t in plan.tasks)
    assert plan.tasks[3].folder == plan.folder / "v03" / "000"


def test_the_sliding_pendulum_sweep_plans_twelve_runs_of_the_manuals_model():
    plan = expand(SWEEP / "sp_sweep.job")
    assert len(plan.tasks) == 12 and plan.job.model_folder().resolve() == (ROOT / "campaigns" / "dap_bc" / "SP")
    assert plan.variants[2].values == {"force.1.k": "20", "body.2.m": "2", "body.2.p": "pi/6"}
    assert plan.campaign.parameters[2].values == (np.pi / 6, np.pi / 4)


def test_run_settings_and_element_values_are_read_as_in_the_in_files(tmp_path):
    text = (MAIN + "[campaign]\nbody.1.p = 0, pi/6\nbody.1.r = [0.6; 0], [0.7; 0]\nrun.rtol = 1e-6, 1e-8\n"
            "run.analysis = forward, static\nzip = run.rtol, run.analysis\n")
    plan = expand(sweep_job(tmp_path, text))
    assert len(plan.variants) == 2 * 2 * 2
    p, r = plan.campaign.parameters[:2]
    assert p.values == (0.0, np.pi / 6) and r.values == ((0.6, 0.0), (0.7, 0.0))
    last = plan.tasks[-1].options
    assert (last.analysis, last.settings.rtol, last.settings.final_time) == ("static", 1e-8, 3.0)
    model = apply_variant(read_dapbc_folder(plan.job.model_folder()), plan.variants[-1], plan.job.path)
    assert model.bodies[0].p == pytest.approx(np.pi / 6) and list(model.bodies[0].r) == [0.7, 0.0]


def test_zipped_run_settings_are_checked_as_the_variants_have_them(tmp_path):
    """finalTime 1 with reportStep 0.5, and 0.01 with 0.005: valid together, not crossed."""
    zipped = "[campaign]\nrun.finalTime = 1, 0.01\nrun.reportStep = 0.5, 0.005\nzip = run.finalTime, run.reportStep\n"
    plan = expand(sweep_job(tmp_path, MAIN + zipped))
    assert [t.options.settings.report_step for t in plan.tasks] == [0.5, 0.005]
    with pytest.raises(ModelError, match="report step must be positive and at most the final time"):
        expand(sweep_job(tmp_path, MAIN + zipped.replace("zip =", "% zip =")))


def test_a_varied_field_reuses_the_compiled_module(tmp_path):
    """The variants differ in parameters only: rebuilding with a variant's values loads the
    module the base model compiled, with the new stiffness among its parameters."""
    plan = expand(sweep_job(tmp_path, MAIN + TWO))
    base = build_system(read_dapbc_folder(plan.job.model_folder()))
    stiff = build_system(apply_variant(read_dapbc_folder(plan.job.model_folder()), plan.variants[1], plan.job.path))
    assert stiff.module is base.module
    assert stiff.data.par[base.parameter_labels.index("force 1 k")] == 80.0


@pytest.mark.parametrize("line, message", [
    ("spring.1.k = 1", "unknown element 'spring'"),
    ("force.1.kk = 1", "Force has no field 'kk'; did you mean 'k'?"),
    ("force.2.k = 1", "force 2 does not exist; the model has 1 forces (inForces.m)"),
    ("body.1.r(3) = 1", "has no component 3"),
    ("force.1.k = 20, foo", "'force.1.k' value 'foo': 'foo' is not defined"),
    ("body.1.m = 1, -1", "'body.1.m' value '-1': m must be positive"),
    ("force.1.iPindex = 2", "cannot be varied: it is an index"),
    ("body.1.r = [1; 2; 3]", "must be a 2-vector"),
    ("replicates = 3", "DAP_BC runs draw no random numbers"),
    ("run.finalTime = 1, 0.001", "variant (run.finalTime = 0.001): the report step must be positive"),
    ("run.method = rk4", "unknown method 'rk4'"),
    ("run.analysis = dynamic", "unknown analysis 'dynamic'"),
    ("run.tolerance = 1", "'tolerance' is not a run setting"),
])
def test_bad_input_is_reported_at_its_line_with_exit_code_2(tmp_path, line, message):
    job = sweep_job(tmp_path, MAIN + "[campaign]\n" + line + "\n")
    with pytest.raises(ModelError) as caught:
        expand(job)
    assert caught.value.line == 8 and message in caught.value.message
    code, _, err = campaign("status", job)
    assert code == 2 and f"{job}:8: " in err and message in err
    result = CliRunner().invoke(mbds_app, ["check", "--no-compile", str(job)])
    assert result.exit_code == 2 and message in result.stderr


@pytest.mark.parametrize("change, where", [
    (("= oscillator", "= elsewhere"), "2: modelFolder = elsewhere is not a DAP_BC model folder"),
    (("finalTime = 3\n", ""), "1: finalTime is missing"),
    (("rtol = 1e-9", "rtol = fast"), "5: 'fast' is not a number"),
])
def test_errors_of_the_main_section(tmp_path, change, where):
    job = sweep_job(tmp_path, MAIN.replace(*change) + TWO)
    code, _, err = campaign("status", job)
    assert code == 2 and f"{job}:{where}" in err, err


def test_mbds_check_accepts_the_example():
    result = CliRunner().invoke(mbds_app, ["check", "--no-compile", str(SWEEP / "sweep.job")])
    assert result.exit_code == 0 and "4 tasks in 4 chain(s)" in result.stdout


@pytest.fixture(scope="module")
def sequential(tmp_path_factory):
    """The two-variant campaign run in one process, and collected."""
    job = sweep_job(tmp_path_factory.mktemp("one_process"), MAIN + TWO)
    code, _, err = campaign("run", job)
    assert code == 0, err
    return job, mbds.open_campaign(collect(expand(job)), load=True)


def test_the_collected_campaign(sequential):
    job, tree = sequential
    summary = tree.ds
    assert list(summary["force_1_k"].values) == [20.0, 80.0] and summary["force_1_k"].attrs["key"] == "force.1.k"
    assert list(summary["status"].values) == ["done", "done"]
    assert (summary["nfev"].values > 0).all() and (summary["end_time"].values == 3.0).all()
    run = tree["v01/000"].ds
    assert run.attrs["kind"] == "dap_bc" and run.attrs["variant_values"] == '{"force.1.k": "80"}'
    assert {"r", "p", "Lam", "eng", "rP", "Jac"} <= set(run.data_vars)
    assert np.array_equal(summary["end_r"].sel(variant="v01").values, run["r"].values[-1])
    ledger = Ledger.read(expand(job).folder)
    assert {e["compiled"] for e in ledger.tasks.values()} == {0}  # the warm-up compiled everything
    code, _, err = campaign("plot", job)
    assert code == 2 and "draws wear campaigns" in err


def test_period_scales_with_the_square_root_of_mass_over_stiffness(sequential):
    """A block of mass m on a spring of stiffness k, sliding without friction, released 0.1 m
    from the spring's undeformed length at rest: x(t) = L0 + 0.1 cos(sqrt(k/m) t), period
    2 pi sqrt(m/k) (the undamped linear oscillator; e.g. Meriam & Kraige, Engineering Mechanics:
    Dynamics, Sec. 8/2). k = 20 and 80 N/m at m = 1 kg: periods 1.405 s and 0.702 s."""
    _, tree = sequential
    for variant, k in ((v, float(tree.ds["force_1_k"].sel(variant=v))) for v in ("v00", "v01")):
        run = tree[f"{variant}/000"].ds
        t, x = run["time"].values, run["r"].sel(body=1, axis="x").values
        assert np.abs(x - (0.5 + 0.1 * np.cos(np.sqrt(k / 1.0) * t))).max() < 1e-8
        rising = np.flatnonzero((x[:-1] < 0.5) & (x[1:] >= 0.5))  # upward crossings of L0
        crossings = t[rising] + (0.5 - x[rising]) / (x[rising + 1] - x[rising]) * (t[rising + 1] - t[rising])
        assert np.diff(crossings).mean() == pytest.approx(2 * np.pi * np.sqrt(1.0 / k), rel=1e-4)
        energy = run["eng"].sel(energy="total").values
        assert np.abs(energy - 0.5 * k * 0.1**2).max() < 1e-8 * k


def test_running_again_resumes(sequential):
    """Done runs are not run again; a run whose ledger entry and output are gone is."""
    job, _ = sequential
    plan = expand(job)
    times = {t.id: (t.folder / "history.nc").stat().st_mtime_ns for t in plan.tasks}
    ledger = Ledger.read(plan.folder)
    del ledger.tasks["v00/000/run"]
    ledger.save()
    (plan.tasks[0].folder / "history.nc").unlink()
    code, _, err = campaign("run", job)
    assert code == 0 and "1 tasks done, 0 failed" in err, err
    after = {t.id: (t.folder / "history.nc").stat().st_mtime_ns for t in plan.tasks}
    assert after["v01/000/run"] == times["v01/000/run"] and after["v00/000/run"] != times["v00/000/run"]
    code, _, err = campaign("run", job)
    assert code == 0 and "0 tasks done, 0 failed" in err


@pytest.mark.mpi
def test_two_mpi_ranks_give_bit_identical_results(sequential, tmp_path):
    _, reference = sequential
    job = sweep_job(tmp_path, MAIN + TWO)
    command = [str(MPIEXEC), "-n", "2", sys.executable, "-m", "mpi4py", "-m", "mbds.cli.campaign", "run", str(job)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert {e.get("rank") for e in Ledger.read(expand(job).folder).tasks.values()} == {1}
    tree = mbds.open_campaign(collect(expand(job)), load=True)
    for node in reference.subtree:
        for name, variable in node.ds.data_vars.items():
            if name != "wall":
                assert np.array_equal(variable.values, tree[node.path].ds[name].values), (node.path, name)


@pytest.mark.parametrize("folder", [SWEEP / "oscillator", ROOT / "campaigns" / "dap_bc" / "SP"])
def test_a_variant_takes_its_numbers_without_building_the_equations_again(folder):
    """with_numbers (what a campaign task uses) gives the kernel data, initial coordinates and
    module that a full build gives, with every number of every element changed."""
    from mbds.io.dapbc.fields import field_kind
    from mbds.model.dapbc.renumber import same_structure, with_numbers

    base = build_system(read_dapbc_folder(folder))
    model = read_dapbc_folder(folder)
    rng = np.random.default_rng(7)
    for kind in ("bodies", "points", "uvectors", "forces", "joints", "functs"):
        for element in getattr(model, kind):
            for name in element.field_names():
                kind = field_kind(element, name)
                if kind == "num":
                    setattr(element, name, getattr(element, name) * (1 + 0.1 * rng.random()))
                elif kind in ("vec2", "vector"):
                    value = getattr(element, name)
                    setattr(element, name, value * (1 + 0.1 * rng.random(value.shape)))
    assert same_structure(base.model, model)
    fast, full = with_numbers(base, model), build_system(model)
    assert full.module is base.module is fast.module
    assert all(np.array_equal(a, b) for a, b in zip(fast.data, full.data))
    assert np.array_equal(fast.q0, full.q0) and np.array_equal(fast.qd0, full.qd0)
    assert not np.array_equal(fast.data.par, base.data.par)
