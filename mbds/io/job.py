"""Job files (``.job``): which versions of a model to run, and how."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.ini import (
    NOT_NEGATIVE,
    Located,
    Section,
    check_rules,
    key_line,
    find_section,
    format_settings,
    parse_ini,
    read_settings,
    setting,
    split_list,
)
from mbds.io.folder import version_name
from mbds.io.text import MAXINT, read_text


@dataclass
class JobSettings:
    """The ``[main]`` section of a job file, with the manual's defaults (times in minutes, which
    may be fractional: ``delayStartMinutes = 0.05`` waits 3 s)."""

    world_file: str = setting("worldFile", "text", "")
    jobs: str = setting("jobs", "text", "")
    lexico_randomization_range: tuple = setting("lexicoRandomizationRange", "pair", (0.0, 0.0))
    create_next_version_at_end: bool = setting("createNextVersionAtEnd", "flag", False)
    max_lines_in_log: int = setting("maxLinesInLog", "integer", 0)
    max_minutes_for_job: float = setting("maxMinutesForJob", "minutes", MAXINT)
    max_minutes_for_jobs: float = setting("maxMinutesForJobs", "minutes", MAXINT)
    frames_per_second: int = setting("framesPerSecond", "integer", 0)
    delay_start_minutes: float = setting("delayStartMinutes", "minutes", 0)
    exit_at_finish: bool = setting("exitAtFinish", "flag", False)


RULES = {name: NOT_NEGATIVE for name in ("max_minutes_for_job", "max_minutes_for_jobs", "max_lines_in_log",
                                          "delay_start_minutes", "frames_per_second")}


@dataclass
class JobFile:
    """A job file. ``versions`` is the expanded ``jobs`` list (3-digit version numbers);
    ``lines`` gives the line of each ``[main]`` key (lower case) and of ``[main]`` itself."""

    settings: JobSettings = field(default_factory=JobSettings)
    versions: list[int] = field(default_factory=list)
    extra_sections: dict = field(default_factory=dict)
    path: Path | None = field(default=None, compare=False)
    lines: dict[str, int] = field(default_factory=dict, compare=False)

    def line(self, key: str) -> int | None:
        """The line of ``key`` in ``[main]``, else of the ``[main]`` header."""
        return self.lines.get(key.lower(), self.lines.get("[main]"))

    def world_path(self) -> Path:
        """The world file: ``worldFile``, or the job file's name with ``.wld``."""
        folder = self.path.parent if self.path else Path.cwd()
        name = self.settings.world_file.strip()
        if not name:
            return folder / ((self.path.stem if self.path else "default") + ".wld")
        return folder / name


def expand_versions(text: str, file=None, line=None) -> list[int]:
    """Version numbers of a ``jobs`` value: lists (``000,001,005``) and ranges (``005-015``)."""
    versions: list[int] = []
    for item in split_list(text):
        m = re.fullmatch(r"(\d+)\s*(?:-\s*(\d+))?", item)
        if not m:
            raise ModelError(f"'{item}' is not a version number or range like 005-015", file, line)
        first = int(m.group(1))
        last = int(m.group(2)) if m.group(2) else first
        if last < first:
            raise ModelError(f"range '{item}' runs backwards", file, line)
        if last > 999:
            raise ModelError(f"version {last} has more than three digits", file, line)
        for v in range(first, last + 1):
            if v in versions:
                raise ModelError(f"version {v:03d} listed twice", file, line)
            versions.append(v)
    return versions


def job_sections(text: str, path: str | Path | None) -> tuple[Section, dict[str, int], dict]:
    """The ``[main]`` section of a job file's text, the line of each of its keys (lower case)
    and of ``[main]`` itself, and the other sections unparsed (name -> list of (key,
    :class:`Located` value)); a section given twice is an error, one other than ``[campaign]``
    is warned about."""
    sections = parse_ini(text, path)
    seen: dict[str, int] = {}
    for s in sections:
        if s.name.lower() in seen:
            raise ModelError(f"section [{s.name}] given twice (first on line {seen[s.name.lower()]})", path, s.line)
        seen[s.name.lower()] = s.line
    main = find_section(sections, "main")
    if main is None:
        raise ModelError("no [main] section", path, 1)
    lines = {"[main]": main.line, **{e.key.lower(): e.line for e in main.entries}}
    extra = {}
    for s in sections:
        if s.name.lower() == "main":
            continue
        if s.name.lower() != "campaign":
            warn(f"unknown section [{s.name}] (ignored)", path, s.line)
        extra[s.name] = [(e.key, Located(e.value, e.line)) for e in s.entries]
    return main, lines, extra


def parse_job(text: str, path: str | Path | None = None) -> JobFile:
    """A :class:`JobFile` from the text of a ``.job`` file.

    Sections other than ``[main]`` are kept, unparsed, in ``extra_sections`` (name -> list of
    (key, :class:`Located` value)) for the campaign layer to read.
    """
    main, lines, extra = job_sections(text, path)
    settings = read_settings(JobSettings, main, path)
    jobs_line = lines.get("jobs")
    versions = expand_versions(settings.jobs, path, jobs_line)
    if not versions:
        raise ModelError("'jobs' lists no versions (e.g. jobs = 000-013)", path, jobs_line or main.line)
    check_rules(settings, RULES, main, path)
    lo, hi = settings.lexico_randomization_range
    if lo < 0 or hi < lo:
        raise ModelError("lexicoRandomizationRange must be 'min,max' with 0 <= min <= max", path,
                         key_line(main, JobSettings, "lexico_randomization_range"))
    return JobFile(settings, versions, extra, Path(path) if path else None, lines)


def read_job(path: str | Path) -> JobFile:
    """The job file at ``path``."""
    return parse_job(read_text(path), path)


def format_job(job: JobFile) -> str:
    """The text of a ``.job`` file."""
    lines = ["[main]", *format_settings(job.settings)]
    for name, entries in job.extra_sections.items():
        lines.append(f"[{name}]")
        lines += [f"{key} = {value.text}" for key, value in entries]
    return "\n".join(lines) + "\n"


def read_checked_job(path: str | Path) -> JobFile:
    """The job file at ``path``, checked before anything runs: its world file exists, and each
    listed version exists, is 000 (made from the model files) or is made by the version listed
    just before it (its predecessor, with ``createNextVersionAtEnd = 1``)."""
    path = Path(path)
    if path.suffix.lower() != ".job":
        raise ModelError("expected a .job file", path)
    job = read_job(path)
    world = job.world_path()
    if not world.is_file():
        raise ModelError(f"world file {world.name} not found", path, job.line("worldFile"))
    if world.suffix.lower() != ".wld":
        raise ModelError(f"worldFile {job.settings.world_file.strip()} is not a .wld world file", path,
                         job.line("worldFile"))
    previous = None
    for number in job.versions:
        made = number == 0 or (job.settings.create_next_version_at_end and previous == number - 1)
        if not made and not version_exists(path.parent / version_name(number)):
            creates = "" if job.settings.create_next_version_at_end else " (createNextVersionAtEnd = 0)"
            raise ModelError(
                f"version {version_name(number)} does not exist and the version listed before it "
                f"does not create it{creates}", path, job.line("jobs"))
        previous = number
    return job


def version_exists(version: Path) -> bool:
    """Whether the version folder is there with its world file."""
    return version.is_dir() and any(version.glob("*.wld"))
