"""Job files (``.job``): which versions of a model to run, and how."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.ini import (
    Located,
    find_section,
    format_settings,
    parse_ini,
    read_settings,
    setting,
    split_list,
)
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


def parse_job(text: str, path: str | Path | None = None) -> JobFile:
    """A :class:`JobFile` from the text of a ``.job`` file.

    Sections other than ``[main]`` are kept, unparsed, in ``extra_sections`` (name -> list of
    (key, :class:`Located` value)) for the campaign layer to read.
    """
    sections = parse_ini(text, path)
    main = find_section(sections, "main")
    if main is None:
        raise ModelError("no [main] section", path, 1)
    settings = read_settings(JobSettings, main, path)
    lines = {"[main]": main.line, **{e.key.lower(): e.line for e in main.entries}}
    jobs_line = lines.get("jobs")
    versions = expand_versions(settings.jobs, path, jobs_line)
    if not versions:
        raise ModelError("'jobs' lists no versions (e.g. jobs = 000-013)", path, jobs_line or main.line)
    extra = {}
    for s in sections:
        if s.name.lower() == "main":
            continue
        if s.name.lower() != "campaign":
            warn(f"unknown section [{s.name}] (ignored)", path, s.line)
        extra[s.name] = [(e.key, Located(e.value, e.line)) for e in s.entries]
    for name in ("max_minutes_for_job", "max_minutes_for_jobs", "max_lines_in_log", "delay_start_minutes"):
        if getattr(settings, name) < 0:
            key = JobSettings.__dataclass_fields__[name].metadata["key"]
            raise ModelError(f"{key} must not be negative", path, main.line)
    lo, hi = settings.lexico_randomization_range
    if lo < 0 or hi < lo:
        raise ModelError("lexicoRandomizationRange must be 'min,max' with 0 <= min <= max", path, main.line)
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
