"""Job files that name a DAP_BC model folder (docs/campaigns.md, "DAP_BC models"): ``[main]``
holds ``modelFolder`` and the run settings of ``mbds run FOLDER`` (final time, report step,
analysis, ...); ``[campaign]`` the values to vary, read by the campaign layer. Outside the
package :mod:`mbds.io.dapbc`, whose import costs a second, so that any job file can be asked
whether it is one quickly."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.ini import find_section, parse_ini, read_settings, setting
from mbds.io.job import job_sections
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
    from mbds.io.dapbc.reader import is_dapbc_folder

    path = Path(path)
    main, lines, extra = job_sections(read_text(path), path)
    job = DapbcJob(read_settings(DapbcJobSettings, main, path), extra, path, lines)
    if not job.settings.model_folder.strip() or not is_dapbc_folder(job.model_folder()):
        raise ModelError(f"{MODEL_FOLDER} = {job.settings.model_folder.strip()} is not a DAP_BC model folder "
                         "(a folder with inBodies.m)", path, job.line(MODEL_FOLDER))
    for key, what in (("finalTime", "the final time T"), ("reportStep", "the report step DT")):
        if key.lower() not in lines:
            raise ModelError(f"{key} is missing: {what} in s", path, job.line(key))
    return job
