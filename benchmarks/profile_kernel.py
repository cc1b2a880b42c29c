"""Where a warm run's time goes in numba's compiled code, per function, with the share spent
pushing call arguments onto the stack.

Run from the repository root (Linux ``perf`` must be installed)::

    .venv/bin/python benchmarks/profile_kernel.py campaigns/woodpecker --time 2 --runs 6

A child process compiles the model and the kernel without any cache (so that numba hands every
function's LLVM module to its JIT, whose addresses this script can list; about two minutes),
writes ``/tmp/perf-PID.map`` (function names by address, which ``perf`` reads) and a copy of each
mbds function's machine code, then runs the model ``--runs`` times; ``perf record`` samples only
those runs. The table gives each function's share of all samples and the share of samples on its
``push`` instructions: numba passes every array as 7 (1-D) or 9 (2-D) words on the stack, so a
call with a bundle of 20 arrays pushes about 150 words, whatever the callee does with them.
``--omega`` sets c'omega of a wearballs copy.
"""

from __future__ import annotations

import argparse
import collections
import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def child(folder: Path, break_time: float, runs: int, out: Path) -> None:
    """Compile, write the perf map and the code copies, say so in out/ready, run."""
    from numba.core import codegen

    modules = []
    add_module = codegen.JitEngine.add_module

    def recording(engine, module):
        modules.append((engine, module))
        return add_module(engine, module)

    codegen.JitEngine.add_module = recording
    from mbds.model.load import load_model
    from mbds.simulation.buffers import RunSettings
    from mbds.simulation.run import simulate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = load_model(folder)
    simulate(model, RunSettings(break_time=1e-3))
    names = {}
    for engine, module in modules:
        for function in module.functions:
            if not function.is_declaration:
                address = engine._ee.get_function_address(function.name)
                if address:
                    names[address] = function.name
    starts = sorted(names)
    code = out / "code"
    code.mkdir()
    with open(f"/tmp/perf-{os.getpid()}.map", "w") as perf_map:
        for start, end in zip(starts, starts[1:] + [starts[-1] + 4096]):
            size = min(end - start, 1 << 20)  # up to the next function: the map has no sizes
            perf_map.write(f"{start:x} {size:x} {names[start]}\n")
            if "mbds" in names[start]:
                (code / f"{start:x}").write_bytes(ctypes.string_at(start, size))
                (code / f"{start:x}.name").write_text(names[start])
    (out / "ready").write_text("")
    for _ in range(runs):
        simulate(model, RunSettings(break_time=break_time))
    (out / "done").write_text("")
    deadline = time.monotonic() + 60.0
    while not (out / "stop").exists() and time.monotonic() < deadline:  # perf stops before the exit
        time.sleep(0.05)


def short(name: str) -> str:
    """A mangled numba name (``_ZN<len><word>...B<abi tag>...``) as its dotted words, without
    the type signature that follows them."""
    words, at = [], name.find("N") + 1
    while at and at < len(name) and name[at].isdigit():
        digits = re.match(r"\d+", name[at:]).group()
        at += len(digits)
        words.append(name[at : at + int(digits)])
        at += int(digits)
    return ".".join(words) or name[:60]


def analyse(data: Path, code: Path) -> None:
    """Print each function's share of the samples and of its push instructions."""
    script = subprocess.run(["perf", "script", "-i", str(data), "-F", "ip"], capture_output=True, text=True)
    samples = collections.Counter(int(ip, 16) for ip in script.stdout.split())
    total = sum(samples.values())
    rows = []
    for path in code.glob("*.name"):
        start = int(path.stem, 16)
        binary = code / path.stem
        inside = {a: n for a, n in samples.items() if start <= a < start + binary.stat().st_size}
        if not inside:
            continue
        listing = subprocess.run(["objdump", "-D", "-b", "binary", "-mi386:x86-64", f"--adjust-vma={start:#x}",
                                  str(binary)], capture_output=True, text=True).stdout
        pushes = sum(inside.get(int(m.group(1), 16), 0)
                     for m in re.finditer(r"^\s*([0-9a-f]+):\t[^\n]*\tpush ", listing, re.MULTILINE))
        rows.append((sum(inside.values()), pushes, short(path.read_text())))
    print(f"{total} samples\n\n| function | share | of it on push |\n|---|---|---|")
    for own, pushes, name in sorted(rows, reverse=True)[:25]:
        print(f"| {name} | {100 * own / total:.1f} % | {100 * pushes / total:.1f} % |")
    print(f"\nall push instructions of mbds functions: {100 * sum(r[1] for r in rows) / total:.1f} % of the samples")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--time", type=float, default=1.0, help="simulated time per run (s)")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--omega", type=float, help="c'omega of a copy of a wearballs folder (rad/s)")
    parser.add_argument("--child", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.folder, args.time, args.runs, args.child)
        return 0
    if shutil.which("perf") is None:
        print("profile_kernel: Linux perf is not installed", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="mbds-profile-") as temp:
        temp = Path(temp)
        folder = args.folder.resolve()
        if args.omega is not None:
            folder = Path(shutil.copytree(folder, temp / "model"))
            for cns in folder.glob("*.cns"):
                cns.write_text("".join(f"c'omega = {args.omega!r}\n" if line.startswith("c'omega") else line
                                       for line in cns.read_text().splitlines(keepends=True)))
        env = dict(os.environ, MBDS_CACHE_DIR=str(temp / "cache"), MBDS_JIT_CACHE="0")
        process = subprocess.Popen([sys.executable, __file__, str(folder), "--time", str(args.time), "--runs",
                                    str(args.runs), "--child", str(temp)], env=env)
        while not (temp / "ready").exists():
            if process.poll() is not None:
                return process.returncode or 1
            time.sleep(0.2)
        data = temp / "perf.data"
        recorder = subprocess.Popen(["perf", "record", "-F", "4000", "-p", str(process.pid), "-o", str(data)],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        while not (temp / "done").exists() and process.poll() is None:
            time.sleep(0.05)
        recorder.send_signal(signal.SIGINT)  # the runs only, not the interpreter's exit
        recorder.wait()
        (temp / "stop").write_text("")
        process.wait()
        analyse(data, temp / "code")
        Path(f"/tmp/perf-{process.pid}.map").unlink(missing_ok=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
