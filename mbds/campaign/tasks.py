"""One task of a campaign, performed in this process: what every executor calls.

``run_task(task) -> dict`` never raises for a failing task (only KeyboardInterrupt and other
BaseExceptions pass); it returns the ledger state and info, ready for
``ledger.mark(task.id, **result)``:

- ``{"state": "done", "output": path, "wall": s}``, and for a run its ``digest``, equal for runs
  with bit-identical results (with ``note`` when there was nothing to do:
  a run that is complete already, a next version that exists already — a task cut off by a kill
  between its last write and the ledger's update is thus not done twice);
- ``{"state": "failed", "reason": "file:line: message", "wall": s}``: bad input, a run that did
  not reach its break time (``maxMinutesForJob``, ``maxLinesInLog``, a state not finite), a
  reshaping refused;
- ``{"state": "pending", "note": ...}``: a run stopped because ``stop()`` became true (the
  campaign was told to stop); what it computed is written, marked incomplete, and the task is
  run again in full when the campaign resumes.

The model's warnings met by a task are not printed but returned (``warnings``: their texts);
``compiled`` is the number of functions numba compiled during the task (0 when the campaign's
warm-up filled the cache).

Tasks of one chain must run in plan order (``depends_on``); tasks of different chains, and the
replicate runs of one version, may run at once in different processes.

Each task kind has its performer, registered with :func:`register_task_kind`: ``prepare``,
``run`` and ``wear`` here, ``dap_bc`` (a run of a DAP_BC model) in
:mod:`mbds.campaign.dapbc_tasks`.

Importing this module loads neither sympy, xarray nor numba: a task imports the simulation
layers it needs when it runs, so that many worker ranks starting at once start quickly
(docs/performance.md).
"""

from __future__ import annotations

import hashlib
import importlib
import sys
import time
import warnings
from collections.abc import Callable

import numpy as np

from mbds.campaign.compiles import counted_compiles
from mbds.campaign.ledger import DONE, FAILED, PENDING
from mbds.campaign.plan import PREPARE, RUN, WEAR, Task
from mbds.campaign.structures import structure
from mbds.campaign.variants import variant_files
from mbds.errors import ModelError, ModelWarning
from mbds.io.folder import read_model_files, version_name, version_number

STOPPED = "the campaign was told to stop"
PERFORMERS: dict[str, Callable[[Task, Callable[[], bool] | None], dict]] = {}
"""Task kind -> function(task, stop) performing it: the result of :func:`run_task` without
``wall``, ``compiled`` and ``warnings``."""
MODULES: dict[str, tuple[str, ...]] = {}
"""Task kind -> the modules its performer imports when it runs (see :func:`import_for`)."""


def register_task_kind(kind: str, modules: tuple[str, ...] = ()):
    """Function decorator: ``function(task, stop) -> dict`` performs the tasks of ``kind``,
    importing ``modules`` when it runs."""
    def add(function):
        PERFORMERS[kind] = function
        MODULES[kind] = modules
        return function
    return add


def performer(kind: str) -> Callable:
    """The function that performs tasks of ``kind``."""
    if kind not in PERFORMERS:
        import mbds.campaign.dapbc_tasks  # noqa: F401  (registers the DAP_BC run)
    return PERFORMERS[kind]


def import_for(kinds) -> None:
    """Import what performing tasks of ``kinds`` needs: a worker rank does it while rank 0
    expands the plan and warms up, so that its first task does not pay for the imports."""
    for kind in sorted(kinds):
        performer(kind)  # a kind registered by another module: that module is imported now
        for module in MODULES[kind]:
            importlib.import_module(module)
    if "numba" in sys.modules:
        _numba_numpy_support()


def import_ahead(told: Callable[[], bool]) -> None:
    """Make this worker ready for its first task before rank 0 has expanded the plan and said its
    task kinds, in steps, stopping as soon as ``told()`` (a message from rank 0 waits).

    First numba, and its set-up of its compiler's registries, which every kind needs and which
    numba otherwise makes when the first compiled function is loaded (0.17-0.23 s, measured);
    then the imports of the tasks of MBDS model folders (``prepare``, ``run``, ``wear``: most
    campaigns), module by module. A worker idles while rank 0 plans; a wrong guess (a DAP_BC
    campaign) costs no more than that idle time."""
    if told():
        return
    from numba.core.registry import cpu_target

    _numba_numpy_support()
    if told():
        return
    cpu_target.target_context.refresh()
    for module in MODULES[RUN]:
        if told():
            return
        importlib.import_module(module)


BLAS_CHECK = "scipy.linalg.cython_blas"
"""The module whose import numba's numpy support tries, to learn whether scipy's BLAS is there."""


def _numba_numpy_support() -> None:
    """Import numba's numpy support (``numba.np.arraymath``, which numba loads before it runs or
    loads any compiled function) without letting it import scipy.

    At import it checks whether scipy's BLAS can be imported, and that import is scipy.linalg:
    0.15-0.35 s of a worker's start-up (measured). The answer only chooses how numba *compiles*
    the inner products of ``np.cov`` and ``np.corrcoef`` (a loop instead of BLAS); mbds's compiled
    code uses neither, and a worker runs code compiled by the warm-up. The check is told that the
    module is missing; afterwards scipy imports as usual (``np.dot`` in a function compiled later
    still finds its BLAS)."""
    if "numba.np.arraymath" in sys.modules or BLAS_CHECK in sys.modules:
        return
    sys.modules[BLAS_CHECK] = None  # import of it raises ImportError, without importing scipy
    try:
        importlib.import_module("numba.np.arraymath")
    finally:
        if sys.modules.get(BLAS_CHECK, "") is None:
            del sys.modules[BLAS_CHECK]


def run_task(task: Task, stop: Callable[[], bool] | None = None) -> dict:
    """Perform ``task``; its ledger state and info (see the module docstring). ``stop`` is
    asked between chunks of a run whether to stop it now."""
    begun = time.monotonic()
    with warnings.catch_warnings(record=True) as caught, counted_compiles() as compiles:
        warnings.simplefilter("always", ModelWarning)
        try:
            result = performer(task.kind)(task, stop)
        except ModelError as exc:
            result = {"state": FAILED, "reason": str(exc)}
        except Exception as exc:  # a defect met by one task must not stop the other chains
            result = {"state": FAILED, "reason": f"{type(exc).__name__}: {exc}"}
    found = sorted({str(w.message) for w in caught if issubclass(w.category, ModelWarning)})
    return {**result, "wall": round(time.monotonic() - begun, 3), "compiled": compiles.count,
            **({"warnings": found} if found else {})}


SIMULATION = ("mbds.data.history", "mbds.kernel.stepper", "mbds.model.load", "mbds.simulation.job",
              "mbds.simulation.version_run", "mbds.simulation.versions")
"""The modules a run (and the model it loads and compiles) imports."""


@register_task_kind(PREPARE, SIMULATION)
def _prepare(task: Task, stop: Callable[[], bool] | None = None) -> dict:
    """The chain's model folder (a variant's: the model files with its values written in) and
    its version 000; ``structure``: the key of the compiled model its runs need
    (:mod:`mbds.campaign.structures`)."""
    from mbds.simulation.versions import create_model_copy, ensure_version

    files = read_model_files(task.source)
    if task.variant is None:
        version = ensure_version(task.folder, 0, task.source)
    else:
        changed, texts = variant_files(files, task.variant)
        create_model_copy(task.folder, changed, 0, texts)
        version = ensure_version(task.folder, 0)
    return {"state": DONE, "output": str(version), "structure": structure(files, task.variant, version)}


@register_task_kind(RUN, SIMULATION)
def _run(task: Task, stop: Callable[[], bool] | None) -> dict:
    """Run the version (or replicate) in ``task.folder`` unless its run is complete already."""
    from mbds.data.history import FILE_NAME as HISTORY
    from mbds.simulation.job import incomplete, time_limits
    from mbds.simulation.version_run import run_version
    from mbds.simulation.versions import create_model_copy

    folder = task.folder
    if version_number(folder) is None:  # a replicate: a copy of its version's model files
        create_model_copy(folder, read_model_files(folder.parent), task.version)
    elif not any(folder.glob("*.wld")):
        raise ModelError(f"version {version_name(task.version)} has not been made", folder)
    output = str(folder / HISTORY)
    if not incomplete(folder):
        return {"state": DONE, "output": output, "note": "complete already, not run again"}
    record = run_version(folder, task.options, time_limits(task.options.job, shown=_stopper(stop)))
    if record.stopped == STOPPED:
        return {"state": PENDING, "output": output, "note": f"stopped at t = {record.end_time:.9g} s; run again on resume"}
    if not record.complete:
        return {"state": FAILED, "output": output, "reason": f"the run stopped at t = {record.end_time:.9g} s "
                f"({record.stopped})"}
    return {"state": DONE, "output": output, "digest": result_digest(record)}


def result_digest(record) -> str:
    """A digest of a run's end state (q, u, clock, losses per point): equal for runs whose
    results are bit-identical, different otherwise (but for a sha256 collision)."""
    state = record.final_state
    digest = hashlib.sha256()
    for array in (state.q, state.u, state.clock, state.point_loss):
        digest.update(np.ascontiguousarray(array).tobytes())
    return digest.hexdigest()[:16]


@register_task_kind(WEAR, SIMULATION)
def _wear(task: Task, stop: Callable[[], bool] | None = None) -> dict:
    """Version N + 1, worn by the losses of N's run (the mean over its replicates' runs)."""
    from mbds.simulation.job import next_version

    target = task.folder.parent / version_name(task.version + 1)
    if any(target.glob("*.wld")):
        return {"state": DONE, "output": str(target), "note": "exists already, not replaced"}
    return {"state": DONE, "output": str(next_version(task.folder, task.inputs))}


def _stopper(stop: Callable[[], bool] | None):
    """A progress callback that ends the run once ``stop()`` is true (None without ``stop``)."""
    if stop is None:
        return None
    from mbds.simulation.run import RunStopped

    def check(start, now, end, steps):
        if stop():
            raise RunStopped(STOPPED)

    return check
