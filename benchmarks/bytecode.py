"""Bytecode of mbds's modules for the benchmarks that time new processes.

Installing a wheel writes the bytecode of every module (pip compiles at install). An editable
install gets it from the first import that may write it, never where ``PYTHONDONTWRITEBYTECODE``
is set (as in many container images, and on the machine these figures come from): there every
new process compiles the sources of the mbds modules it imports, about 0.1 s of a campaign
worker's imports (0.66 against 0.77 s, docs/performance.md "Bytecode"). The benchmarks that time
a process's start write the bytecode first, so that they measure mbds as installed.
"""

from __future__ import annotations

import compileall
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "mbds"


def write_bytecode() -> None:
    """Compile mbds's modules into their ``__pycache__`` folders (the files out of date only; git
    ignores them) and say so where the environment would not have written them."""
    if not compileall.compile_dir(PACKAGE, quiet=1):
        raise SystemExit(f"compiling the bytecode of {PACKAGE} failed")
    if sys.flags.dont_write_bytecode:
        print(f"(PYTHONDONTWRITEBYTECODE is set: the bytecode of {PACKAGE} was written first, as a wheel "
              "install has it)", file=sys.stderr)
