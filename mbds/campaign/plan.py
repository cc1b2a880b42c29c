"""Campaign plans: a job file expanded into chains of versions and the tasks that make them.

``expand(job_path) -> Plan`` reads the job file and its optional ``[campaign]`` section
(docs/campaigns.md) and checks them against the model; nothing is written. A plan has

- ``variants``: the cartesian product of the varied keys, linked keys (``zip``) taking their
  values together (``v00``, ``v01``, ...);
- ``chains``: one per variant (and per replicate in ``mode = chains``), each a model folder
  ``<campaign folder>/<variant>[/r<k>]`` whose versions 000, 001, ... follow one another. A job
  file without ``[campaign]`` is one chain in the job file's own folder, run as ``mbds job``
  runs it (same versions, seed 0, versions with a complete run not run again);
- ``tasks``, in an order where every task comes after those it depends on:

  ========  ==================================================================================
  kind      what :func:`mbds.campaign.tasks.run_task` does
  ========  ==================================================================================
  prepare   write the chain's model folder (the variant's values in) and its version 000
  run       run one version (``folder`` = the version folder) or, in ``mode = ensemble``, one
            replicate of it (``folder`` = ``NNN/r<k>``), with ``options`` (seed, job settings)
  wear      create version N + 1 from version N (``folder``), worn by the losses of its run or,
            in ensemble mode, by the mean of the losses of the runs in ``inputs``
  ========  ==================================================================================

Task ids are stable and readable: ``v01/prepare``, ``v01/003/run``, ``v01/003/r2/run`` (an
ensemble replicate), ``v01/r2/003/run`` (a chain of replicate 2), ``v01/003/wear`` (makes 004).

``ready_tasks(plan, ledger)`` gives the tasks a scheduler may start now: pending, with every
task they depend on done. ``task_states(plan, ledger)`` adds the derived state ``blocked``: a
task after a failed one of its chain, never started; other chains go on.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np

from mbds.campaign.ledger import BLOCKED, DONE, FAILED, PENDING, Ledger
from mbds.campaign.section import ENSEMBLE, CampaignSection, parse_campaign
from mbds.campaign.variants import Variant, check_world_combinations, product, variant_count
from mbds.errors import ModelError, ModelWarning
from mbds.io.dapbc_job import is_dapbc_job
from mbds.io.folder import read_model_files, replicate_name, version_name
from mbds.io.job import JobFile, read_checked_job
from mbds.simulation.options import RunOptions

PREPARE, RUN, WEAR = "prepare", "run", "wear"
MBDS, DAP_BC = "mbds", "dap_bc"
"""Kinds of model a plan runs (``Plan.model``); ``dap_bc`` is also the kind of a DAP_BC run task."""
RUN_KINDS = (RUN, DAP_BC)
"""Task kinds whose result is a run's ``history.nc``."""


@dataclass(frozen=True)
class Chain:
    """Versions that follow one another in the model folder ``folder``: of ``variant`` (None
    for a job without ``[campaign]``), of one ``replicate`` in ``mode = chains`` (else None),
    run with ``seed`` (each replicate its own in ensemble mode). The folder is kept as given
    (text or path) and made a path when asked, so that a plan of 10^5 tasks is made quickly."""

    id: str
    place: str | Path
    variant: Variant | None
    replicate: int | None
    seed: int

    @property
    def folder(self) -> Path:
        return Path(self.place)


class Task(NamedTuple):
    """One step of a chain (see the module docstring for ``kind``). ``folder``: the folder the
    task writes (prepare: the chain's model folder; run: the run folder; wear: version N);
    ``depends_on``: ids of the tasks that must be done first; ``options``: of a run;
    ``inputs``: run folders whose losses a wear task averages (empty: ``folder``'s own run);
    ``source``: the world file a prepare task copies the model from. ``place`` is the folder
    as given (text or path), made a path when asked. A named tuple: a plan of 10^5 tasks is
    made in a fraction of a second."""

    id: str
    kind: str
    chain: str
    variant: Variant | None
    replicate: int | None
    version: int
    place: str | Path
    seed: int
    depends_on: tuple[str, ...] = ()
    options: RunOptions | None = None
    inputs: tuple[Path, ...] = ()
    source: Path | None = None

    @property
    def folder(self) -> Path:
        return Path(self.place)


@dataclass
class Plan:
    """A job file expanded: ``folder`` is the campaign folder (the ledger is there),
    ``campaign`` the ``[campaign]`` section (None without one), ``model`` the kind of model
    (``mbds``, or ``dap_bc`` for a job naming a DAP_BC folder: ``job`` is then a
    :class:`mbds.io.dapbc_job.DapbcJob`)."""

    job: JobFile
    folder: Path
    campaign: CampaignSection | None
    variants: list[Variant]
    chains: list[Chain]
    tasks: list[Task]
    model: str = MBDS

    def task(self, task_id: str) -> Task:
        """The task with id ``task_id`` (KeyError when there is none)."""
        for task in self.tasks:
            if task.id == task_id:
                return task
        raise KeyError(task_id)

    @property
    def line(self) -> int | None:
        """The job file's line for errors about the campaign as a whole."""
        return self.campaign.line if self.campaign else self.job.line("jobs")


def replicate_seed(seed: int, variant: int, replicate: int) -> int:
    """The seed (0 <= seed < 2**32) of ``replicate`` of ``variant`` in a campaign of ``seed``:
    deterministic, and distinct streams for distinct (variant, replicate)."""
    sequence = np.random.SeedSequence(seed, spawn_key=(variant, replicate))
    return int(sequence.generate_state(1, dtype=np.uint32)[0])


def expand(job_path: str | Path) -> Plan:
    """The plan of the job file at ``job_path``; ModelError (``file:line``) on bad input."""
    if is_dapbc_job(job_path):
        from mbds.campaign.dapbc_plan import expand_dapbc  # the DAP_BC reader, only for its jobs

        return expand_dapbc(Path(job_path))
    job = read_checked_job(job_path)
    with warnings.catch_warnings():  # the runs repeat the model's warnings when they load it
        warnings.simplefilter("ignore", ModelWarning)
        files = read_model_files(job.world_path())
    campaign = parse_campaign(job, files)
    if campaign is None:
        chains = [Chain(job.path.stem, job.path.parent, None, None, 0)]
        return Plan(job, job.path.parent / "campaign", None, [], chains, _tasks(job, chains, None))
    _check_consecutive(job)
    folder = job.path.parent / campaign.folder
    _check_size(job, campaign)
    check_world_combinations(files, campaign.parameters, job.path, campaign.links)
    variants = product(campaign.parameters, campaign.links)
    n, base = campaign.replicates, str(folder)
    if campaign.mode == ENSEMBLE:
        chains = [Chain(v.id, f"{base}/{v.id}", v, None, 0) for v in variants]
    else:
        chains = [
            Chain(v.id if n == 1 else f"{v.id}/{replicate_name(r)}",
                  f"{base}/{v.id}" if n == 1 else f"{base}/{v.id}/{replicate_name(r)}",
                  v, r, replicate_seed(campaign.seed, v.index, r))
            for v in variants for r in range(n)
        ]
    return Plan(job, folder, campaign, variants, chains, _tasks(job, chains, campaign))


def task_states(plan: Plan, ledger: Ledger) -> dict[str, str]:
    """The state of each task: the ledger's, or ``blocked`` for a task not done that depends
    on a failed or blocked one."""
    states: dict[str, str] = {}
    for task in plan.tasks:
        state = ledger.state(task.id)
        if state != DONE and any(states[d] in (FAILED, BLOCKED) for d in task.depends_on):
            state = BLOCKED
        states[task.id] = state
    return states


def done_count(plan: Plan, ledger: Ledger) -> int:
    """How many tasks of the plan are done."""
    return sum(state == DONE for state in task_states(plan, ledger).values())


def ready_tasks(plan: Plan, ledger: Ledger) -> list[Task]:
    """The tasks to start now, in plan order: pending, with every task they depend on done."""
    states = task_states(plan, ledger)
    return [t for t in plan.tasks if states[t.id] == PENDING and all(states[d] == DONE for d in t.depends_on)]


def plan_size(job: JobFile, campaign: CampaignSection) -> tuple[int, int, int]:
    """(tasks, variants, tasks per variant) of the plan, counted without making it."""
    variants = variant_count(campaign.parameters, campaign.links)
    versions = len(job.versions)
    runs = versions * campaign.replicates
    wears = versions * campaign.replicates if job.settings.create_next_version_at_end else 0
    if campaign.mode == ENSEMBLE:
        per_variant = (job.versions[0] == 0) + runs + wears // campaign.replicates
    else:
        per_variant = campaign.replicates * (job.versions[0] == 0) + runs + wears
    return variants * per_variant, variants, per_variant


def _check_size(job: JobFile, campaign: CampaignSection) -> None:
    """ModelError, before anything is made, when the plan has more than ``maxTasks`` tasks."""
    tasks, variants, per_variant = plan_size(job, campaign)
    if tasks > campaign.max_tasks:
        raise ModelError(f"the plan has {tasks:,} tasks ({variants:,} variants x {per_variant:,} tasks each), "
                         f"more than maxTasks = {campaign.max_tasks:,}; vary fewer values, or raise maxTasks "
                         "in [campaign] if you mean it", job.path, campaign.line)


def _check_consecutive(job: JobFile) -> None:
    """A campaign starts its chains at 000, each later version made by the one before it."""
    versions = job.versions
    if versions != list(range(len(versions))) or (len(versions) > 1 and not job.settings.create_next_version_at_end):
        raise ModelError("a campaign's jobs must be consecutive versions from 000 (000-013), each made by the "
                         "one before it (createNextVersionAtEnd = 1)", job.path, job.line("jobs"))


def _tasks(job: JobFile, chains: list[Chain], campaign: CampaignSection | None) -> list[Task]:
    """The tasks of every chain, chain after chain, each after those it depends on."""
    tasks: list[Task] = []
    wear = job.settings.create_next_version_at_end
    ensemble = campaign is not None and campaign.mode == ENSEMBLE
    source = job.world_path()
    for chain in chains:
        made_by: dict[int, str] = {}  # version -> id of the task that makes its folder
        options = RunOptions(seed=chain.seed, job=job.settings)
        if job.versions[0] == 0:
            prepare = Task(f"{chain.id}/prepare", PREPARE, chain.id, chain.variant, chain.replicate, 0,
                           chain.place, chain.seed, source=source)
            tasks.append(prepare)
            made_by[0] = prepare.id
        for number in job.versions:
            version = f"{chain.place}/{version_name(number)}"
            before = (made_by[number],) if number in made_by else ()
            replicates = range(campaign.replicates) if ensemble else [None]
            runs = [_run(job, chain, number, version, before, campaign, r, options) for r in replicates]
            tasks += runs
            if wear:
                task = Task(f"{chain.id}/{version_name(number)}/wear", WEAR, chain.id, chain.variant,
                            chain.replicate, number, version, chain.seed, tuple(r.id for r in runs),
                            inputs=tuple(r.folder for r in runs) if ensemble else ())
                tasks.append(task)
                made_by[number + 1] = task.id
    return tasks


def _run(job: JobFile, chain: Chain, number: int, version: str, before: tuple[str, ...],
         campaign: CampaignSection | None, replicate: int | None, options: RunOptions) -> Task:
    """The run of version ``number`` of ``chain`` (of one ``replicate`` in ensemble mode);
    ``options``: those of the chain's runs."""
    name = version_name(number)
    if replicate is None:
        return Task(f"{chain.id}/{name}/run", RUN, chain.id, chain.variant, chain.replicate, number, version,
                    chain.seed, before, options)
    seed = replicate_seed(campaign.seed, chain.variant.index, replicate)
    return Task(f"{chain.id}/{name}/{replicate_name(replicate)}/run", RUN, chain.id, chain.variant, replicate,
                number, f"{version}/{replicate_name(replicate)}", seed, before, RunOptions(seed=seed, job=job.settings))
