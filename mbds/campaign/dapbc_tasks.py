"""The run task of a campaign over a DAP_BC model (task kind ``dap_bc``): read the model folder,
set the variant's element fields, take the system of the folder (built once per process; the
compiled module is the one the warm-up made) with the variant's numbers, run the analysis and write ``history.nc`` in the task's folder,
with the variant and its values in the attributes."""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from pathlib import Path

import numpy as np

from mbds.campaign.dapbc_variants import apply_variant
from mbds.campaign.ledger import DONE, PENDING
from mbds.campaign.plan import DAP_BC, Task
from mbds.campaign.tasks import STOPPED, register_task_kind
from mbds.data.dapbc_history import FILE_NAME, write_dapbc_history
from mbds.dapbc import analyse
from mbds.io.dapbc import read_dapbc_folder
from mbds.io.dapbc.records import DapbcModel
from mbds.model.dapbc import build_system
from mbds.model.dapbc.renumber import same_structure, with_numbers
from mbds.model.dapbc.system import DapbcSystem


_BASES: dict = {}
"""Model folder (and its files' modification times) -> the system built from it, in this process."""


def variant_system(folder: Path, model: DapbcModel) -> DapbcSystem:
    """The system of ``model``, a variant of the model in ``folder``: the folder's system,
    built once per process, with the variant's numbers (:func:`with_numbers`; no sympy, the
    same compiled module); built in full when the structure differs."""
    key = (str(folder.resolve()), tuple(sorted((p.name, p.stat().st_mtime_ns) for p in folder.iterdir())))
    if key not in _BASES:
        _BASES.clear()
        _BASES[key] = build_system(read_dapbc_folder(folder))
    base = _BASES[key]
    return with_numbers(base, model) if same_structure(base.model, model) else build_system(model)


class _Stopped(Exception):
    """Raised from the progress callback when the campaign is told to stop."""


@register_task_kind(DAP_BC)
def run_dapbc(task: Task, stop: Callable[[], bool] | None = None) -> dict:
    """Run the DAP_BC variant of ``task`` unless its ``history.nc`` is there already."""
    output = task.folder / FILE_NAME
    if output.is_file():
        return {"state": DONE, "output": str(output), "note": "complete already, not run again"}
    model = apply_variant(read_dapbc_folder(task.source), task.variant, task.options.job)
    system = variant_system(task.source, model)

    def progress(now, end, nfev):
        if stop is not None and stop():
            raise _Stopped

    try:
        result, dataset = analyse(system, task.options.analysis, task.options.settings, progress)
    except _Stopped:
        return {"state": PENDING, "note": f"{STOPPED}; run again on resume"}
    if task.variant is not None:
        dataset.attrs.update(variant=task.variant.id, variant_values=json.dumps(task.variant.values))
    task.folder.mkdir(parents=True, exist_ok=True)
    write_dapbc_history(output, dataset)
    digest = hashlib.sha256(np.ascontiguousarray(result.y).tobytes()).hexdigest()[:16]
    return {"state": DONE, "output": str(output), "digest": digest}
