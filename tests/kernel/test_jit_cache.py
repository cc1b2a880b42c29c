"""The kernel's cached machine code is keyed by all kernel files together (mbds.kernel.jit):
numba keys a function by its own file only, so an edit to a callee in another kernel file would
otherwise leave callers running the old callee's code from the cache."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys

from mbds.kernel import jit as kernel_jit
from mbds.kernel.lcp import lemke
from mbds.kernel.stepper import _step_size


def test_kernel_functions_are_stamped_by_the_whole_kernel():
    for function in (lemke, _step_size):
        locator = function._cache._impl.locator
        assert isinstance(locator, kernel_jit._WholeKernelStamp)
        assert locator.get_source_stamp() == kernel_jit.kernel_source_hash()


def test_an_edit_to_any_kernel_file_changes_the_stamp(tmp_path, monkeypatch):
    copy = tmp_path / "kernel"
    shutil.copytree(kernel_jit.KERNEL_FOLDER, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(kernel_jit, "KERNEL_FOLDER", copy)
    kernel_jit.kernel_source_hash.cache_clear()
    try:
        before = kernel_jit.kernel_source_hash()
        (copy / "lcp.py").write_text((copy / "lcp.py").read_text() + "\n# an edit\n")
        kernel_jit.kernel_source_hash.cache_clear()
        assert kernel_jit.kernel_source_hash() != before
    finally:
        kernel_jit.kernel_source_hash.cache_clear()


def test_functions_outside_the_kernel_keep_numbas_own_stamp(tmp_path):
    source = tmp_path / "elsewhere.py"
    source.write_text("import numba\n\n@numba.njit(cache=True)\ndef twice(x):\n    return 2 * x\n")
    spec = importlib.util.spec_from_file_location("elsewhere", source)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    locator = module.twice._cache._impl.locator
    assert not isinstance(locator, kernel_jit._WholeKernelStamp)
    assert locator.get_source_stamp() != kernel_jit.kernel_source_hash()


ENTRY_MODULE = """
import numpy as np
from mbds.kernel.jit import jit


@jit(refcount=False)
def _weight(x, k):
    return (k + 1.0) * x[k]


@jit(refcount=False, entry=True)
def weighted_sum(x):
    s = 0.0
    for k in range(x.shape[0]):
        s += _weight(x, k)
    return s
"""

ENTRY_CALL = """
import sys
import numpy as np
sys.path.insert(0, sys.argv[1])
from entry_module import weighted_sum
value = weighted_sum(np.arange(5.0))
library = next(iter(weighted_sum.overloads.values())).library
print(value, sum(weighted_sum.stats.cache_hits.values()), len(list(library._get_module_for_linking().functions)))
"""


def test_an_entry_function_loads_from_the_cache_without_its_linking_ir(tmp_path):
    """An ``entry=True`` function (the stepper's driver) is cached without the IR numba keeps for
    inlining it elsewhere; a new process loads it from the cache, finds its entry point by the
    stored symbol names, and computes what it computed when compiled (0*1 + 1*2 + 2*3 + 3*4 + 4*5)."""
    (tmp_path / "entry_module.py").write_text(ENTRY_MODULE)
    runs = []
    for _ in range(2):  # the first process compiles and writes the cache, the second loads it
        done = subprocess.run([sys.executable, "-c", ENTRY_CALL, str(tmp_path)], capture_output=True, text=True,
                              env={**os.environ, "MBDS_JIT_CACHE": "1"}, check=True)
        value, hits, functions = done.stdout.split()
        runs.append((float(value), int(hits), int(functions)))
    (compiled_value, compiled_hits, compiled_functions), (loaded_value, loaded_hits, loaded_functions) = runs
    assert compiled_value == loaded_value == 40.0
    assert compiled_hits == 0 and compiled_functions > 0
    assert loaded_hits == 1 and loaded_functions == 0


def test_the_stepper_driver_is_cached_as_an_entry_function():
    from mbds.kernel.stepper import advance

    assert isinstance(advance._cache, kernel_jit._EntryCache)
    assert not isinstance(lemke._cache, kernel_jit._EntryCache)


def test_an_entry_function_without_the_cache_is_not_cached():
    @kernel_jit.jit(entry=True, cache=False)
    def twice(x):
        return 2.0 * x

    assert twice(1.5) == 3.0
    assert not isinstance(twice._cache, kernel_jit._EntryCache)
