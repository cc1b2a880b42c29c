"""Slurm batch scripts of campaigns: ``mbds-campaign submit`` fills the template
``slurm.sbatch`` (beside this module) and hands the script to ``sbatch``.

The template's ``{{name}}`` placeholders are filled with :class:`SlurmOptions` and the
campaign's paths; a line whose placeholder has an empty value is left out (an optional
``#SBATCH`` directive not asked for). Nothing reaches the script unchecked: names (job name,
account, partition) are limited to ``[A-Za-z0-9._-]``, times and counts are parsed, paths are
quoted for their context (the shell's quotes on command lines, sbatch's double quotes in
``#SBATCH`` lines) and refused when they hold a control character such as a newline, which no
quoting keeps on its line. The script launches ``srun <this interpreter> -m mpi4py -m
mbds.cli.campaign run JOB`` with one thread per rank, and passes the ``USR1`` Slurm sends
``signal_seconds`` before the time limit on to the campaign.
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import Plan
from mbds.campaign.section import ENSEMBLE
from mbds.errors import ModelError
from mbds.io.text import read_text, write_atomic

TEMPLATE = Path(__file__).with_name("slurm.sbatch")
"""The template, shipped inside the package (a wheel has no workflows/ folder)."""
SCRIPT_NAME = "campaign.sbatch"
TIME_FORMAT = re.compile(r"\d+(:\d+){0,2}|\d+-\d+(:\d+){0,2}")
"""Slurm's --time: minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS."""
SLURM_NAME = re.compile(r"[A-Za-z0-9._-]+")
"""What a job name, account or partition may hold: nothing the shell or sbatch reads specially."""
MEMORY = re.compile(r"\d+[KMGT]?")
"""Slurm's memory sizes: a number of megabytes, or with the unit K, M, G or T."""
NODES = re.compile(r"[1-9]\d*(-[1-9]\d*)?")
"""Slurm's --nodes: a count, or min-max."""
_DIRECTIVE_PLAIN = re.compile(r"[A-Za-z0-9._/%+,:@=-]+")
_CONTROL = re.compile(r"[\x00-\x1f\x7f]")
_PLACEHOLDER = re.compile(r"\{\{(\w+)\}\}")
_SUBMITTED = re.compile(r"Submitted batch job (\d+)")


@dataclass
class SlurmOptions:
    """``ntasks``: MPI ranks (0: one scheduler and one worker for each task that can run at
    once); ``time``: Slurm's limit (empty: the partition's); ``signal_seconds``: how long before
    the limit the campaign is told to stop (s); ``job_name`` (empty: ``mbds-<job>``);
    ``nodes`` and ``mem_per_cpu`` (empty: Slurm's defaults); ``mpi``: srun's ``--mpi=`` plugin
    (empty: the cluster's default); ``preamble``: a file whose shell lines go before the launch
    (``module load ...``, activating an environment: the user's own commands, put in as written);
    ``max_requeues``: how often the job may requeue itself when its time limit stops the campaign
    with tasks left (None: never; :mod:`mbds.campaign.requeue`)."""

    ntasks: int = 0
    time: str = ""
    account: str = ""
    partition: str = ""
    job_name: str = ""
    signal_seconds: int = 300
    nodes: str = ""
    mem_per_cpu: str = ""
    mpi: str = ""
    preamble: Path | None = None
    max_requeues: int | None = 5

    def check(self) -> None:
        """ModelError naming the option whose value could change the script's meaning."""
        for option, value in (("--job-name", self.job_name), ("--account", self.account),
                              ("--partition", self.partition), ("--mpi", self.mpi)):
            if value and not SLURM_NAME.fullmatch(value):
                raise ModelError(f"{option} {value!r}: use only letters, digits, '.', '_' and '-'")
        if self.time and not TIME_FORMAT.fullmatch(self.time):
            raise ModelError(f"--time {self.time!r}: Slurm's format is minutes, HH:MM:SS or D-HH:MM:SS")
        if self.nodes and not NODES.fullmatch(self.nodes):
            raise ModelError(f"--nodes {self.nodes!r}: a count of nodes (2) or a range (1-4)")
        if self.mem_per_cpu and not MEMORY.fullmatch(self.mem_per_cpu):
            raise ModelError(f"--mem-per-cpu {self.mem_per_cpu!r}: megabytes, or a size such as 2G")
        if not 0 <= self.ntasks or self.ntasks == 1:
            raise ModelError(f"--ntasks {self.ntasks}: a campaign needs 2 ranks or more (one schedules)")
        if not 1 <= self.signal_seconds <= 65535:
            raise ModelError(f"--signal-seconds {self.signal_seconds}: must be 1 to 65535")


def script_path(path: Path, what: str) -> str:
    """``path`` as text fit for the script: refused (ModelError) when it holds a control character."""
    text = str(path)
    if _CONTROL.search(text):
        raise ModelError(f"{what} holds a control character (a newline?), which a batch script cannot "
                         f"hold safely: {text!r}")
    return text


def directive_value(text: str) -> str:
    """``text`` as one argument of an ``#SBATCH`` line: as it is when plain, else in sbatch's
    double quotes with ``\\`` and ``"`` escaped (sbatch ends an argument at unquoted blanks and
    ``#``, and reads quotes and backslash escapes: ``_get_argument`` in Slurm's
    src/sbatch/opt.c)."""
    if _DIRECTIVE_PLAIN.fullmatch(text):
        return text
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def read_preamble(path: Path) -> str:
    """The shell lines of a preamble file; ModelError (at its line) for one that would end the
    script's ``#SBATCH`` directives' meaning (an ``#SBATCH`` line, which sbatch ignores there)."""
    text = read_text(path).rstrip("\n")
    for number, line in enumerate(text.splitlines(), start=1):
        if line.lstrip().upper().startswith("#SBATCH"):
            raise ModelError("#SBATCH lines go in submit's options, not in the preamble (sbatch reads none "
                             "after the first command)", path, number)
    return f"# Preamble from {Path(script_path(path, 'the preamble path')).name}:\n{text}"


def default_job_name(job: Path) -> str:
    """``mbds-<job file name>``, with anything but ``[A-Za-z0-9._-]`` replaced by ``_``."""
    return "mbds-" + re.sub(r"[^A-Za-z0-9._-]", "_", job.stem)


def parallel_width(plan: Plan) -> int:
    """How many tasks of the plan can run at once: one per chain, or per replicate of a chain
    in ensemble mode."""
    ensemble = plan.campaign is not None and plan.campaign.mode == ENSEMBLE
    return len(plan.chains) * (plan.campaign.replicates if ensemble else 1)


def render_script(plan: Plan, options: SlurmOptions, python: str = sys.executable, template: Path = TEMPLATE) -> str:
    """The batch script of the plan's campaign."""
    options.check()
    job = plan.job.path.resolve()
    job_text = script_path(job, "the job file's path")
    values = {
        "job_file": shlex.quote(job_text),
        "job_name": options.job_name or default_job_name(job),
        "ntasks": str(int(options.ntasks or 1 + parallel_width(plan))),
        "time": options.time,
        "account": options.account,
        "partition": options.partition,
        "workdir": directive_value(script_path(job.parent, "the job file's folder")),
        "output": directive_value(script_path(plan.folder.resolve() / "slurm-%j.out", "the campaign folder")),
        "signal_seconds": str(int(options.signal_seconds)),
        "python": shlex.quote(script_path(Path(python), "the Python interpreter's path")),
        "nodes": options.nodes,
        "mem_per_cpu": options.mem_per_cpu,
        "srun_options": f"--mpi={options.mpi} " if options.mpi else "",
        "preamble": read_preamble(options.preamble) if options.preamble else "",
        "requeue": "requeue" if options.max_requeues is not None else "no-requeue",
        "max_requeues": str(int(options.max_requeues)) if options.max_requeues is not None else "",
    }
    return fill(template.read_text(encoding="utf-8"), values, template)


INLINE = frozenset({"srun_options"})
"""Placeholders that may be empty without their line being left out."""


def fill(text: str, values: dict[str, str], path: Path | None = None) -> str:
    """``text`` with each ``{{name}}`` replaced by ``values[name]``; lines with an empty value
    (of a placeholder not in :data:`INLINE`) left out."""
    lines = []
    for number, line in enumerate(text.splitlines(keepends=True), start=1):
        names = _PLACEHOLDER.findall(line)
        unknown = [n for n in names if n not in values]
        if unknown:
            raise ModelError(f"unknown placeholder {{{{{unknown[0]}}}}}", path, number)
        if all(values[n] for n in names if n not in INLINE):
            lines.append(_PLACEHOLDER.sub(lambda m: values[m.group(1)], line))
    return "".join(lines)


def submit(plan: Plan, script: str, ledger: Ledger) -> str:
    """Write ``script`` into the campaign folder, submit it with the ``sbatch`` found on PATH
    and record the Slurm job id in the ledger; return the id."""
    sbatch = shutil.which("sbatch")
    if sbatch is None:
        raise ModelError("sbatch not found on PATH (not a Slurm machine? --dry-run prints the script)")
    path = plan.folder.resolve() / SCRIPT_NAME  # sbatch runs in the job's folder, not the caller's
    plan.folder.mkdir(parents=True, exist_ok=True)
    write_atomic(path, script)
    done = subprocess.run([sbatch, str(path)], capture_output=True, text=True, cwd=plan.job.path.resolve().parent)
    found = _SUBMITTED.search(done.stdout)
    if done.returncode != 0 or not found:
        said = (done.stderr or done.stdout).strip() or f"exit code {done.returncode}"
        raise ModelError(f"sbatch did not submit the script: {said}", path)
    ledger.record_submission(found.group(1), path)
    return found.group(1)
