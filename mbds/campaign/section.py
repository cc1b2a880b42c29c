"""The ``[campaign]`` section of a job file (docs/campaigns.md): where the campaign lives, its
seed, replicates and mode, and the keys whose values make the variants."""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from mbds.campaign.variants import Parameter, is_parameter_key, parse_parameter
from mbds.errors import ModelError
from mbds.io.folder import ModelFiles, version_number
from mbds.io.job import JobFile
from mbds.io.text import parse_integer

CHAINS, ENSEMBLE = "chains", "ensemble"
_COMMON = ("seed", "replicates", "mode", "folder", "maxTasks", "zip")
MAX_TASKS = 10**6
"""The most tasks a plan may have unless ``maxTasks`` in ``[campaign]`` says otherwise."""


@dataclass(frozen=True)
class CampaignSection:
    """``folder`` (relative to the job file), ``seed`` (of the replicates' seeds),
    ``replicates`` (runs per variant), ``mode`` (chains or ensemble), the varied
    ``parameters``, ``line``: the section's first line in the job file (for errors), and
    ``max_tasks``: the largest plan accepted; ``links``: groups of indices of ``parameters``
    that take their k-th values together (``zip`` keys)."""

    folder: str = "campaign"
    seed: int = 0
    replicates: int = 1
    mode: str = CHAINS
    parameters: tuple[Parameter, ...] = ()
    line: int | None = None
    max_tasks: int = MAX_TASKS
    links: tuple[tuple[int, ...], ...] = ()


@dataclass(frozen=True)
class VariedKeys:
    """The keys a ``[campaign]`` section varies for one kind of model: ``accepts(key)`` says
    whether a key is one, ``parse(key, text, line)`` reads it into a :class:`Parameter` (checked
    against the model), ``listing`` names them for the unknown-key message, and ``refused`` maps
    campaign keys that do not apply to this kind of model to the reason."""

    accepts: Callable[[str], bool]
    parse: Callable[[str, str, int | None], Parameter]
    listing: str
    refused: dict[str, str] = field(default_factory=dict)


def mbds_keys(files: ModelFiles, job_path: Path) -> VariedKeys:
    """The varied keys of an MBDS model: constants, world settings and contact laws."""
    return VariedKeys(is_parameter_key, lambda key, text, line: parse_parameter(key, text, line, files, job_path),
                      "c'name, world.<key>, contact.<section>.<key>")


def _checked_folder(text: str, job_path, line: int | None) -> str:
    """The ``folder`` value: a folder inside the job file's folder (not that folder itself, not
    a version folder's name such as 000, no control characters)."""
    relative = PurePosixPath(text.replace("\\", "/"))
    if not text or relative.is_absolute() or re.search(r"[\x00-\x1f\x7f]", text):
        raise ModelError("folder must be a folder name relative to the job file", job_path, line)
    base = Path(job_path).resolve().parent if job_path else Path.cwd()
    target = (base / text).resolve()
    if target == base or not target.is_relative_to(base):
        raise ModelError(f"folder '{text}' is not inside the job file's folder {base}", job_path, line)
    first = target.relative_to(base).parts[0]
    if version_number(first) is not None:
        raise ModelError(f"folder '{text}' would mix the campaign with the model's version folders "
                         f"({first}); give it another name", job_path, line)
    return text


def campaign_folder(job: JobFile) -> Path:
    """The campaign folder ``job`` names (its ``[campaign]`` section's ``folder``, checked), read
    without the model: for commands that only read what a campaign wrote."""
    name = next((n for n in job.extra_sections if n.lower() == "campaign"), None)
    given = [located for key, located in job.extra_sections.get(name, []) if key.lower() == "folder"]
    folder = _checked_folder(given[0].text, job.path, given[0].line) if given else CampaignSection.folder
    return job.path.parent / folder


def parse_campaign(job: JobFile, files: ModelFiles | None, varied: VariedKeys | None = None) -> CampaignSection | None:
    """The job's ``[campaign]`` section checked against the model ``files`` (an MBDS model), or
    with the ``varied`` keys of another kind of model; None without one."""
    name = next((n for n in job.extra_sections if n.lower() == "campaign"), None)
    if name is None:
        return None
    entries = job.extra_sections[name]
    path = job.path
    varied = varied or mbds_keys(files, path)
    values: dict = {"line": entries[0][1].line if entries else job.line("jobs")}
    parameters: list[Parameter] = []
    seen: dict = {}  # key (or what a varied key changes) -> line
    zips: list = []  # (key, Located list of the varied keys it links)
    for key, located in entries:
        text, line = located.text, located.line
        parameter = varied.parse(key, text, line) if varied.accepts(key) else None
        folded = parameter.target if parameter else key.lower()
        if folded in seen:
            raise ModelError(f"'{key}' given twice (first on line {seen[folded]})", path, line)
        seen[folded] = line
        if parameter:
            parameters.append(parameter)
        elif folded in varied.refused:
            raise ModelError(f"{key}: {varied.refused[folded]}", path, line)
        elif folded in ("seed", "replicates"):
            number = parse_integer(text, path, line)
            if number < (0 if folded == "seed" else 1):
                raise ModelError(f"{key} must be {'0 or more' if folded == 'seed' else '1 or more'}", path, line)
            values[folded] = number
        elif folded == "mode":
            if text.lower() not in (CHAINS, ENSEMBLE):
                raise ModelError(f"mode must be '{CHAINS}' or '{ENSEMBLE}', not '{text}'", path, line)
            values["mode"] = text.lower()
        elif folded == "folder":
            values["folder"] = _checked_folder(text, path, line)
        elif folded.startswith("zip"):
            zips.append((key, located))
        elif folded == "maxtasks":
            values["max_tasks"] = parse_integer(text, path, line)
            if values["max_tasks"] < 1:
                raise ModelError(f"{key} must be 1 or more", path, line)
        else:
            raise ModelError(
                f"unknown key '{key}' in [campaign] ({', '.join(k for k in _COMMON if k.lower() not in varied.refused)}, "
                f"{varied.listing})", path, line)
    links = tuple(_link(key, located, parameters, path) for key, located in zips)
    linked = [i for group in links for i in group]
    if len(set(linked)) != len(linked):
        raise ModelError("a varied key is linked by two zip keys", path, zips[-1][1].line)
    return CampaignSection(parameters=tuple(parameters), links=links, **values)


def _link(key: str, located, parameters: list[Parameter], path) -> tuple[int, ...]:
    """The indices of the varied keys a ``zip`` key names; they must list as many values each."""
    names = [n.strip() for n in located.text.split(",")]
    index = {p.key.lower(): i for i, p in enumerate(parameters)}
    if len(names) < 2 or not all(names):
        raise ModelError(f"{key} needs two varied keys or more, separated by commas", path, located.line)
    missing = [n for n in names if n.lower() not in index]
    if missing:
        raise ModelError(f"{key}: '{missing[0]}' is not a varied key of this [campaign] section", path, located.line)
    group = tuple(index[n.lower()] for n in names)
    if len(set(group)) != len(group):
        raise ModelError(f"{key} names a key twice", path, located.line)
    counts = {parameters[i].key: len(parameters[i].values) for i in group}
    if len(set(counts.values())) != 1:
        listed = ", ".join(f"{k} {n}" for k, n in counts.items())
        raise ModelError(f"{key}: linked keys must list as many values each ({listed})", path, located.line)
    return group
