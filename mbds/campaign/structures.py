"""Which compiled model each variant of a campaign needs, each made ready once before its runs.

A variant's *structure* is the hash of its generated model source (:mod:`mbds.expr.codegen`):
variants that differ only in numbers (constants, masses, contact-law values, world settings)
share one, and with it one compiled module and stepper. Finding a variant's structure costs an
assembly of its model and a code generation (about 0.1 s), which for a campaign of many variants
would keep every worker waiting before the first task. So each chain's prepare task, on a worker,
finds its variant's structure and returns it (``structure`` in its ledger entry), and the
scheduling process makes each structure ready (compiles it, or loads it from the cache, and runs
its stepper for no time) before it hands out the first run that needs it. No task compiles.
"""

from __future__ import annotations

import warnings

from mbds.campaign.plan import PREPARE, Plan
from mbds.errors import ModelWarning


def structure(files) -> str:
    """The structure key of the model in ``files`` (a folder's model files, variant values
    written in)."""
    return _key(_assembled(files))


def _assembled(files):
    """The model of ``files``, assembled (its warnings are the runs' to report)."""
    from mbds.model.load import assemble_model

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        return assemble_model(files)


def _key(model) -> str:
    """The structure key of an assembled model: the hash of its generated source."""
    from mbds.expr.cache import source_hash
    from mbds.expr.codegen import generate_source

    return source_hash(generate_source(model.expressions))


def _name(variant) -> str | None:
    return variant.id if variant is not None else None


class Structures:
    """The structures made ready in this process, and each variant's structure as far as known."""

    def __init__(self, plan: Plan):
        from mbds.io.folder import read_model_files

        self._base = read_model_files(plan.job.world_path())
        self._variant_of = {task.id: _name(task.variant) for task in plan.tasks if task.kind == PREPARE}
        self._ready: set[str] = set()
        self._of: dict[str | None, str] = {}

    def _files(self, variant):
        from mbds.campaign.variants import variant_files

        return self._base if variant is None else variant_files(self._base, variant)[0]

    def learn(self, task_id: str, entry: dict) -> None:
        """Note the structure a prepare task found (its ledger ``entry``), if it did."""
        if task_id in self._variant_of and "structure" in entry:
            self._of[self._variant_of[task_id]] = entry["structure"]

    def make_ready(self, variant) -> bool:
        """Make the structure of ``variant`` (None: the job's own model) ready unless it is;
        whether it had to be (a structure new to this process)."""
        from mbds.simulation.buffers import RunSettings
        from mbds.simulation.run import simulate

        name = _name(variant)
        model = None
        if name not in self._of:
            model = _assembled(self._files(variant))
            self._of[name] = _key(model)
        if self._of[name] in self._ready:
            return False
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelWarning)
            simulate(model or _assembled(self._files(variant)), RunSettings(break_time=0.0))
        self._ready.add(self._of[name])
        return True

    @property
    def count(self) -> int:
        """How many distinct structures are ready."""
        return len(self._ready)
