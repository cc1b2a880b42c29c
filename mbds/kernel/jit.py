"""The one place for numba settings of the kernel.

Environment overrides (read once, at import):

- ``MBDS_JIT_CACHE`` (default ``1``): cache compiled code on disk.
- ``MBDS_FASTMATH`` (default ``0``): allow fast-math; off keeps results bit-reproducible.
- ``MBDS_BOUNDSCHECK`` (default ``0``): check array bounds (slow; for debugging).

numba keys a cached function by the text of its own file, but a kernel function's machine code
also holds the functions it calls from other kernel files. The kernel's cached functions are
therefore keyed by all of its files together (:func:`kernel_source_hash`): after any change to the
kernel (an upgrade, an edit) each of them compiles again instead of running stale callees.

A function that only Python calls (``entry=True``: the stepper's driver, the DAP_BC analyses)
keeps on disk its machine code and the names of the symbols it defines, not the LLVM IR that
numba stores beside them so that other compiled functions can inline it (1.7 MB for the
stepper, 0.22 s to parse at every start of a process).
"""

from __future__ import annotations

import functools
import hashlib
import os
from pathlib import Path

import llvmlite.binding as llvm
import numba
from numba.core import caching, compiler

KERNEL_FOLDER = Path(__file__).resolve().parent


def _flag(name: str, default: bool) -> bool:
    value = os.environ.get(name)
    if value is None:
        return default
    return value.strip().lower() not in ("0", "false", "no", "off", "")


CACHE = _flag("MBDS_JIT_CACHE", True)
FASTMATH = _flag("MBDS_FASTMATH", False)
BOUNDSCHECK = _flag("MBDS_BOUNDSCHECK", False)


def jit(*args, refcount=True, entry=False, **kwargs):
    """``numba.njit`` with the project's settings; keyword arguments override them.

    ``refcount=False`` compiles without numba's reference counting of arrays: no atomic
    increment and decrement of every array argument, namedtuple field and view a function
    touches (the larger part of the stepper's cost per step when it had them). Only for
    functions that work on arrays their caller owns: they may not create an array or return
    one (numba then refuses to compile them).

    ``entry=True``: a function that only Python calls, never another compiled function; its disk
    cache holds no IR for inlining it elsewhere (see the module's docstring).
    """
    options = {"cache": CACHE, "fastmath": FASTMATH, "boundscheck": BOUNDSCHECK, "nogil": True}
    if not refcount:
        options["_nrt"] = False
    options.update(kwargs)
    cached_entry = entry and options["cache"]
    if args and callable(args[0]) and len(args) == 1:
        return _entry_cache(numba.njit(**options)(args[0]), cached_entry)
    return lambda function: _entry_cache(numba.njit(*args, **options)(function), cached_entry)


def _entry_cache(dispatcher, entry: bool):
    """``dispatcher``, caching with :class:`_EntryCache` if ``entry`` (a cached entry function)."""
    if entry:
        dispatcher._cache = _EntryCache(dispatcher.py_func)
    return dispatcher


class _EntryCacheImpl(caching.CompileResultCacheImpl):
    """numba's cache of a compile result, less the IR for linking: its place holds an empty
    module, and the names of the symbols the machine code defines are stored instead, for
    numba's JIT engine to find the function by (it would otherwise read them from that IR)."""

    def reduce(self, cres):
        (name, kind, (machine_code, _)), *rest = cres._reduce()
        linking = cres.library._get_module_for_linking()
        defined = sorted(value.name for values in (linking.functions, linking.global_variables)
                         for value in values if not value.is_declaration)
        empty = llvm.parse_assembly("").as_bitcode()
        return ((name, kind, (machine_code, empty)), tuple(defined), *rest)

    def rebuild(self, target_context, payload):
        libdata, defined, *rest = payload
        target_context.codegen()._engine._defined_symbols.update(defined)
        return compiler.CompileResult._rebuild(target_context, libdata, *rest)


class _EntryCache(caching.FunctionCache):
    """numba's function cache with :class:`_EntryCacheImpl`."""

    _impl_class = _EntryCacheImpl


@functools.cache
def kernel_source_hash() -> str:
    """Hash of the source files of mbds.kernel (names and bytes), 20 hex digits."""
    digest = hashlib.sha256()
    for path in sorted(KERNEL_FOLDER.glob("*.py")):
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:20]


class _WholeKernelStamp:
    """A numba cache locator for functions defined in the kernel's files, stamped with the hash of
    all of them; it declines every other file (numba's own locators then take it)."""

    def get_source_stamp(self):
        return kernel_source_hash()

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent != KERNEL_FOLDER:
            return None
        return super().from_function(py_func, py_file)


def _kernel_locators() -> list[type]:
    """numba's file-backed locators (in their order), each stamped by the whole kernel."""
    return [type(f"Kernel{base.__name__}", (_WholeKernelStamp, base), {})
            for base in (caching.UserProvidedCacheLocator, caching.InTreeCacheLocator, caching.UserWideCacheLocator)]


if not any(issubclass(c, _WholeKernelStamp) for c in caching.CacheImpl._locator_classes):
    caching.CacheImpl._locator_classes[:0] = _kernel_locators()
