"""The kernel's cached machine code is keyed by all kernel files together (mbds.kernel.jit):
numba keys a function by its own file only, so an edit to a callee in another kernel file would
otherwise leave callers running the old callee's code from the cache."""

from __future__ import annotations

import importlib.util
import shutil

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
