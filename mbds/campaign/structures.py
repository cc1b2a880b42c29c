"""Which compiled model each variant of a campaign needs, each made ready once before its runs.

A variant's *structure* is the hash of its generated model source (:mod:`mbds.expr.codegen`):
variants that differ only in numbers (constants, masses, contact-law values, world settings)
share one, and with it one compiled module and stepper. Finding a variant's structure costs an
assembly of its model and a code generation (about 0.1 s), which for a campaign of many variants
would keep every worker waiting before the first task. So each chain's prepare task, on a worker,
finds its variant's structure and returns it (``structure`` in its ledger entry), and the
scheduling process makes each structure ready (compiles it, or loads it from the cache, and runs
its stepper for no time) before it hands out the first run that needs it. No task compiles.

A cache that holds a structure compiled already is asked instead (:mod:`mbds.campaign.known_structures`):
the structure of inputs seen before is remembered, and a structure compiled before is marked, so
the scheduling process of a campaign whose models were compiled before imports neither sympy nor
numba; each worker loads the first variant's compiled model before its first task
(:func:`load_first`). A prepare task that has to find its structure keeps its chain's model
record too, and :func:`keep_record` keeps a variant's, so that the runs (and ``load_first``)
assemble their models without sympy (:mod:`mbds.model.known`).
"""

from __future__ import annotations

import tempfile
import warnings
from pathlib import Path

from mbds.campaign import known_structures as known
from mbds.campaign.plan import PREPARE, Plan
from mbds.errors import ModelWarning
from mbds.io.folder import read_model_files


def structure(files, variant=None, copy=None) -> str:
    """The structure key of the model of ``files`` (a folder's model files, as read) with
    ``variant``'s values written in: remembered by the cache for these inputs, else found by
    code generation and remembered. ``copy``: a folder holding that model (the chain's version
    000), whose record the cache then keeps too (:mod:`mbds.model.known`)."""
    digest = known.input_digest(files, variant)
    key = known.remembered(digest)
    if key is None:
        key = _found(read_model_files(copy)) if copy is not None else _key(_assembled(_with_values(files, variant)))
        known.remember(digest, key)
    return key


def _found(files) -> str:
    """The structure of the model of ``files`` (read from a folder), its record kept."""
    from mbds.model.load import find_structure

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        return find_structure(files)


def _with_values(files, variant):
    """The model ``files`` with ``variant``'s values written in (None: as they are)."""
    from mbds.campaign.variants import variant_files

    return files if variant is None else variant_files(files, variant)[0]


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


def _run_for_no_time(model) -> None:
    """Compile ``model`` (or load it from the cache), run its stepper for no time, and mark its
    structure compiled in the cache."""
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        simulate(model, RunSettings(break_time=0.0))
    known.mark_compiled(model.compiled.source_hash)


def load_first(world, variant) -> None:
    """Load the compiled model of ``variant`` of the model of ``world`` in this process (a
    worker, before its first task) and run its stepper for no time: without sympy when the
    cache holds the record of the chain's first version (:mod:`mbds.model.known`)."""
    from mbds.campaign.variants import variant_files
    from mbds.model.load import remembered_model

    files, texts = read_model_files(world), None
    if variant is not None:
        files, texts = variant_files(files, variant)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        model = remembered_model(files, 0, texts)
    _run_for_no_time(model if model is not None else _assembled(files))


def keep_record(files, variant) -> None:
    """Keep the record of the model of ``files`` with ``variant``'s values written in
    (:mod:`mbds.model.known`) in the cache unless it is there: as its chain's first run would,
    from a copy of that model in a temporary folder."""
    from mbds.campaign.variants import variant_files
    from mbds.model.known import remembered
    from mbds.simulation.versions import create_model_copy

    changed, texts = (files, None) if variant is None else variant_files(files, variant)
    if remembered(changed, texts) is not None:
        return
    with tempfile.TemporaryDirectory(prefix="mbds-record-") as temporary:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelWarning)
            copy = create_model_copy(Path(temporary) / "000", changed, 0, texts)
        _found(read_model_files(copy))


def _name(variant) -> str | None:
    return variant.id if variant is not None else None


class Structures:
    """The structures made ready in this process, and each variant's structure as far as known."""

    def __init__(self, plan: Plan):
        self._base = read_model_files(plan.job.world_path())
        self._variant_of = {task.id: _name(task.variant) for task in plan.tasks if task.kind == PREPARE}
        self._ready: set[str] = set()
        self._of: dict[str | None, str] = {}

    def learn(self, task_id: str, entry: dict) -> None:
        """Note the structure a prepare task found (its ledger ``entry``), if it did."""
        if task_id in self._variant_of and "structure" in entry:
            self._of[self._variant_of[task_id]] = entry["structure"]

    def make_ready(self, variant) -> bool:
        """Make the structure of ``variant`` (None: the job's own model) ready unless it is;
        whether it had to be (a structure new to this process). A structure the cache holds
        compiled is ready without loading it here."""
        name = _name(variant)
        if name not in self._of:
            self._of[name] = structure(self._base, variant)
        key = self._of[name]
        if key in self._ready:
            return False
        if not known.compiled(key):
            _run_for_no_time(_assembled(_with_values(self._base, variant)))
        self._ready.add(key)
        return True

    def keep_record(self, variant) -> None:
        """Keep the record of ``variant``'s model in the cache (see :func:`keep_record`)."""
        keep_record(self._base, variant)

    @property
    def count(self) -> int:
        """How many distinct structures are ready."""
        return len(self._ready)
