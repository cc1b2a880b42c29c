"""Cold compile time and cached load time of each example model.

Each measurement runs in a fresh Python process: the first with an empty expression cache
(`MBDS_CACHE_DIR` pointing to a new folder), so everything is generated and compiled; the second
with the same folder, so the compiled functions come from the disk cache. Times are wall-clock
seconds measured inside the process: importing mbds, reading and assembling the model, and
generating plus compiling (or loading) its functions; the compiled functions have explicit
signatures, so loading the module compiles or loads every one of them.

Run: .venv/bin/python benchmarks/model_load.py
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from bytecode import write_bytecode

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ["2mass", "wearballs", "woodpecker"]

CHILD = r"""
import json, sys, time
t0 = time.perf_counter()
import numpy as np
from mbds.model.load import load_model
t1 = time.perf_counter()
model = load_model(sys.argv[1], compile=False)
t2 = time.perf_counter()
compiled = model.compile()
t3 = time.perf_counter()
misses = sum(sum(f.stats.cache_misses.values()) for f in compiled.dispatchers().values())
print(json.dumps({"imports": t1 - t0, "assemble": t2 - t1, "compile": t3 - t2, "misses": misses}))
"""


def measure(example: str, cache: str) -> dict:
    env = dict(os.environ, MBDS_CACHE_DIR=cache)
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(ROOT / "campaigns" / example)],
        env=env, capture_output=True, text=True, check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    write_bytecode()
    print(f"{'model':<12} {'imports s':>10} {'assemble s':>11} {'cold compile s':>15} {'cached load s':>14} {'cached misses':>14}")
    for example in EXAMPLES:
        with tempfile.TemporaryDirectory() as cache:
            cold = measure(example, cache)
            warm = measure(example, cache)
        print(
            f"{example:<12} {warm['imports']:>10.2f} {warm['assemble']:>11.2f} {cold['compile']:>15.2f} "
            f"{warm['compile']:>14.3f} {warm['misses']:>14d}"
        )


if __name__ == "__main__":
    main()
