"""Job files that name a DAP_BC model folder (docs/campaigns.md, "DAP_BC models"): ``[main]``
holds ``modelFolder`` and the run settings of ``mbds run FOLDER`` (final time, report step,
analysis, ...); ``[campaign]`` the values to vary, read by the campaign layer."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.dapbc.reader import is_dapbc_folder
from mbds.io.ini import Located, find_section, parse_ini, read_settings, setting
from mbds.io.text import read_text

MODEL_FOLDER = "modelFolder"


@dataclass
class DapbcJobSettings:
    """The ``[main]`` section of a DAP_BC job file: the model folder (relative to the job file)
    and the run settings, with the defaults of ``mbds run`` (times in s)."""

    model_folder: str = setting(MODEL_FOLDER, "text", "")
    final_time: float = setting("finalTime", "number", 0.0)
    report_step: float = setting("reportStep", "number", 0.0)
    analysis: str = setting("analysis", "text", "forward")
    correct_ic: bool = setting("correctIC", "flag", True)
    method: str = setting("method", "text", "dopri5")
    rtol: float = setting("rtol", "number", 1e-6)
    atol: float = setting("atol", "number", 1e-9)
    projection: bool = setting("projection", "flag", True)


@dataclass
class DapbcJob:
    """A DAP_BC job file: its ``settings``, its other sections unparsed (``extra_sections``, as
    :class:`mbds.io.job.JobFile` keeps them), its ``path`` and the line of each ``[main]`` key.
    ``versions`` is ``[0]``: each variant is one run, written where ``mbds run`` writes it
    (``000``)."""

    settings: DapbcJobSettings
    extra_sections: dict
    path: Path
    lines: dict[str, int] = field(default_factory=dict)
    versions: list[int] = field(default_factory=lambda: [0])

    def line(self, key: str) -> int | None:
        """The line of ``key`` in ``[main]``, else of the ``[main]`` header."""
        return self.lines.get(key.lower(), self.lines.get("[main]"))

    def model_folder(self) -> Path:
        """The DAP_BC model folder the job names."""
        return self.path.parent / self.settings.model_folder.strip()


def is_dapbc_job(path: str | Path) -> bool:
    """Whether the job file at ``path`` names a DAP_BC model (``modelFolder`` in ``[main]``);
    False for a file that cannot be read as one (its reader reports why)."""
    try:
        main = find_section(parse_ini(read_text(path), path), "main")
    except ModelError:
        return False
    return main is not None and any(e.key.lower() == MODEL_FOLDER.lower() for e in main.entries)


def read_dapbc_job(path: str | Path) -> DapbcJob:
    """The DAP_BC job file at ``path``, its model folder checked to be a DAP_BC folder; the
    run settings are checked where they are used (mbds.campaign.dapbc)."""
    path = Path(path)
    sections = parse_ini(read_text(path), path)
    seen: dict[str, int] = {}
    for s in sections:
        if s.name.lower() in seen:
            raise ModelError(f"section [{s.name}] given twice (first on line {seen[s.name.lower()]})", path, s.line)
        seen[s.name.lower()] = s.line
    main = find_section(sections, "main")
    if main is None:
        raise ModelError("no [main] section", path, 1)
    settings = read_settings(DapbcJobSettings, main, path)
    lines = {"[main]": main.line, **{e.key.lower(): e.line for e in main.entries}}
    job = DapbcJob(settings, {}, path, lines)
    folder = job.model_folder()
    if not settings.model_folder.strip() or not is_dapbc_folder(folder):
        raise ModelError(f"{MODEL_FOLDER} = {settings.model_folder.strip()} is not a DAP_BC model folder "
                         "(a folder with inBodies.m)", path, job.line(MODEL_FOLDER))
    for s in sections:
        if s.name.lower() == "main":
            continue
        if s.name.lower() != "campaign":
            warn(f"unknown section [{s.name}] (ignored)", path, s.line)
        job.extra_sections[s.name] = [(e.key, Located(e.value, e.line)) for e in s.entries]
    return job
