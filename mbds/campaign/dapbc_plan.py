"""Plans of campaigns over a DAP_BC model: one run task per variant.

A job file whose ``[main]`` names a DAP_BC folder (``modelFolder``) expands into a
:class:`~mbds.campaign.plan.Plan` of model kind ``dap_bc``: the variants of its ``[campaign]``
section (:mod:`mbds.campaign.dapbc_variants`; one variant with nothing changed without it), each
a chain of one task of kind ``dap_bc`` (id ``v00/000/run``) that runs the model with the
variant's values and writes ``<campaign folder>/v00/000/history.nc``, as ``mbds run FOLDER``
writes ``FOLDER/000/history.nc``. DAP_BC models have no versions and no wear, and their runs draw
no random numbers: no replicates, no seeds.

``warm_up_dapbc(plan)`` compiles the model once: the variants vary numbers only, which the
compiled module takes as parameters, so they share it.
"""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path
from typing import NamedTuple

from mbds.analysis.dapbc import DapbcSettings
from mbds.campaign.dapbc_variants import check_run_settings, dapbc_keys, run_settings
from mbds.campaign.plan import DAP_BC, Chain, Plan, Task
from mbds.campaign.section import parse_campaign
from mbds.campaign.variants import product, variant_count
from mbds.errors import ModelError, ModelWarning
from mbds.io.dapbc import read_dapbc_folder
from mbds.io.dapbc_job import read_dapbc_job
from mbds.io.folder import version_name


WARM_UP_TIME = 1e-3
"""The longest time (s) the warm-up runs an analysis for."""


class DapbcRun(NamedTuple):
    """What a DAP_BC run task runs: the ``analysis`` and its ``settings``; ``job``: the job
    file (where the variant's values are written, for errors)."""

    analysis: str
    settings: DapbcSettings
    job: Path


def expand_dapbc(job_path: Path) -> Plan:
    """The plan of the DAP_BC job file at ``job_path``; ModelError (``file:line``) on bad input."""
    job = read_dapbc_job(job_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        model = read_dapbc_folder(job.model_folder())
    campaign = parse_campaign(job, None, dapbc_keys(model, job))
    parameters, links = (campaign.parameters, campaign.links) if campaign else ((), ())
    count = variant_count(parameters, links)
    if campaign and count > campaign.max_tasks:
        raise ModelError(f"the plan has {count:,} tasks (one per variant), more than maxTasks = "
                         f"{campaign.max_tasks:,}; vary fewer values, or raise maxTasks in [campaign] if you mean it",
                         job.path, campaign.line)
    check_run_settings(job, parameters, links)
    variants = product(parameters, links)
    folder = job.path.parent / (campaign.folder if campaign else "campaign")
    chains = [Chain(v.id, f"{folder}/{v.id}", v, None, 0) for v in variants]
    tasks = []
    for chain in chains:
        analysis, settings = run_settings(job, chain.variant)
        tasks.append(Task(f"{chain.id}/{version_name(0)}/run", DAP_BC, chain.id, chain.variant, None, 0,
                          f"{chain.place}/{version_name(0)}", 0, options=DapbcRun(analysis, settings, job.path),
                          source=job.model_folder()))
    return Plan(job, folder, campaign, variants, chains, tasks, model=DAP_BC)


def warm_up_dapbc(plan: Plan) -> int:
    """Compile the model of a DAP_BC plan (or load it from the cache) and run each of its
    analyses (with each integrator) over one short report step, so that the tasks compile
    nothing; 1, the number of distinct compiled modules (the variants share one). An analysis
    that refuses the model is left to its tasks, which fail with the reason."""
    from mbds.dapbc import analyse
    from mbds.model.dapbc import build_system

    system = build_system(read_dapbc_folder(plan.job.model_folder()))
    for analysis, settings, _ in {(t.options.analysis, t.options.settings.method): t.options for t in plan.tasks}.values():
        step = min(settings.report_step, WARM_UP_TIME)
        try:
            analyse(system, analysis, dataclasses.replace(settings, final_time=step, report_step=step))
        except ModelError:
            continue
    return 1
