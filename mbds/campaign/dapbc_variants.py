"""Varied keys of a campaign over a DAP_BC model (docs/campaigns.md, "DAP_BC models").

- ``<element>.<index>.<field>`` sets a field of one element of the in-files, e.g.
  ``force.1.k = 20000, 40000``, ``body.2.m = 1, 2``, ``body.1.p = 0, pi/6``; a component of a
  vector field is ``body.1.r(1)``, a whole vector ``body.1.r = [1; 0.2], [1.2; 0.2]``. Elements:
  ``body``, ``point``, ``uvector``, ``force``, ``joint``, ``funct``; indices are 1-based as in
  the in-files. Values are written as in the in-files (``pi/6``, ``2*1e4``) and evaluated by
  mbds's reader of them. Only numbers may vary: an index or a type changes the model's structure.
- ``run.<key>`` sets a run setting of the job's ``[main]`` (``run.finalTime``, ``run.rtol``,
  ``run.analysis``, ...).

Each value is checked at the job file's line as the in-file reader checks a field (kind,
finiteness, component), masses and inertias must be positive, and each variant's run settings
must make valid settings. A varied element field goes into the model through
:func:`mbds.io.dapbc.fields.set_field`, so the rebuilt system loads the same compiled module with
new parameters.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mbds.analysis.dapbc import METHODS, DapbcSettings
from mbds.campaign.section import VariedKeys
from mbds.campaign.variants import Parameter, Variant, kind_product
from mbds.errors import ModelError
from mbds.io.dapbc.fields import did_you_mean, field_kind, set_field, set_field_value, unknown_field
from mbds.io.dapbc.interpreter import InFile
from mbds.io.dapbc_job import MODEL_FOLDER, DapbcJob, DapbcJobSettings
from mbds.io.dapbc.parser import parse
from mbds.io.dapbc.records import DapbcModel, SourcePos
from mbds.io.text import parse_flag, parse_number

ELEMENT, RUN_SETTING = "element", "run"
#: key word -> (DapbcModel list, in-file that makes it)
ELEMENTS = {"body": ("bodies", "inBodies.m"), "point": ("points", "inPoints.m"),
            "uvector": ("uvectors", "inUvectors.m"), "force": ("forces", "inForces.m"),
            "joint": ("joints", "inJoints.m"), "funct": ("functs", "inFuncts.m")}
POSITIVE_FIELDS = {("body", "m"), ("body", "J")}
_ELEMENT_KEY = re.compile(r"([A-Za-z]+)\.(\w+)\.(\w+)(?:\((\w+)\))?")
_RUN_FIELDS = {f.metadata["key"].lower(): f for f in dataclasses.fields(DapbcJobSettings)
               if f.metadata["key"] != MODEL_FOLDER}
_REFUSED = "DAP_BC runs draw no random numbers, so every replicate would repeat its variant's run bit for bit"


@dataclass(frozen=True)
class DapbcParameter(Parameter):
    """A varied key of a DAP_BC campaign: for an element field, ``section`` is the element word
    (``force``), ``index`` its 1-based index, ``name`` the field and ``component`` a 1-based
    component of a vector field (None: the whole field); for a run setting, ``name`` is the
    field of :class:`DapbcJobSettings`. ``values`` are numbers (or tuples of numbers, text for
    ``run.analysis`` and ``run.method``)."""

    index: int = 0
    component: int | None = None

    @property
    def target(self) -> tuple:
        return self.kind, self.section, self.index, self.name, self.component


def dapbc_keys(model: DapbcModel, job: DapbcJob) -> VariedKeys:
    """The keys a ``[campaign]`` section varies for the DAP_BC ``model`` of ``job``."""
    refused = {key: _REFUSED for key in ("seed", "replicates", "mode")}
    return VariedKeys(lambda key: bool(_ELEMENT_KEY.fullmatch(key)) or key.lower().startswith("run."),
                      lambda key, text, line: parse_dapbc_parameter(key, text, line, model, job),
                      "<element>.<index>.<field> (body, point, uvector, force, joint, funct), run.<key>", refused)


def split_values(text: str) -> list[str]:
    """The values of a key: separated by commas outside brackets (``[1; 0.2], [1.2; 0.2]``)."""
    items, depth, start = [], 0, 0
    for k, char in enumerate(text):
        depth += (char in "[(") - (char in "])")
        if char == "," and depth == 0:
            items.append(text[start:k].strip())
            start = k + 1
    return [*items, text[start:].strip()] if text.strip() else []


def evaluate(text: str, job_path: Path, line: int | None):
    """A value written as in the in-files, evaluated by mbds's in-file reader (a 1x1 array for a
    number, a column or row for a vector, text for quoted text); errors at the job's line."""
    program = parse("\n" * max((line or 1) - 1, 0) + f"value = {text};", str(job_path))
    return InFile(program, {}, {}).value(program.body[0].value)


def parse_dapbc_parameter(key: str, text: str, line: int | None, model: DapbcModel, job: DapbcJob) -> DapbcParameter:
    """A varied key of a DAP_BC campaign, each of its values checked at the job file's ``line``."""
    path = job.path
    texts = tuple(split_values(text))
    if not texts or not all(texts):
        raise ModelError(f"'{key}' needs values separated by commas (e.g. 20000, 40000)", path, line)
    if len(set(texts)) != len(texts):
        raise ModelError(f"'{key}' lists a value twice", path, line)
    if key.lower().startswith("run."):
        return _run_parameter(key, texts, line, job)
    word, index_text, name, component_text = _ELEMENT_KEY.fullmatch(key).groups()
    word = word.lower()
    if word not in ELEMENTS:
        raise ModelError(f"'{key}': unknown element '{word}'{did_you_mean(word, ELEMENTS, 'elements')}", path, line)
    kind, in_file = ELEMENTS[word]
    index = _whole(index_text, f"'{key}': the element index", path, line)
    elements = getattr(model, kind)
    if not 1 <= index <= len(elements):
        have = f"has {len(elements)} {kind}" if elements else f"has no {kind}"
        raise ModelError(f"'{key}': {word} {index} does not exist; the model {have} ({in_file})", path, line)
    record = elements[index - 1]
    if name not in record.field_names():
        raise ModelError(f"'{key}': {unknown_field(record, name)}", path, line)
    if field_kind(record, name) in ("index", "text"):
        raise ModelError(f"'{key}': {name} cannot be varied: it is {'an index' if field_kind(record, name) == 'index' else 'text'}, "
                         "which changes the model's structure (only numbers and vectors may vary)", path, line)
    component = None if component_text is None else _whole(component_text, f"'{key}': the component", path, line)
    parameter = DapbcParameter(key, ELEMENT, word, name, (), texts, line, index, component)
    values = []
    for item in texts:
        try:
            value = _plain(evaluate(item, path, line))
            if value is None:
                raise ModelError("not a number or a vector", path, line)
            set_element(record.copy(), parameter, value, path)
            if (word, name) in POSITIVE_FIELDS and not value > 0:
                raise ModelError(f"{name} must be positive", path, line)
        except ModelError as exc:
            raise ModelError(f"'{key}' value '{item}': {exc.message}", path, line) from None
        values.append(value)
    return dataclasses.replace(parameter, values=tuple(values))


def set_element(record, parameter: DapbcParameter, value, job_path: str | Path) -> None:
    """Set ``parameter``'s field (or component) of the element ``record`` to ``value`` with the
    in-file reader's checks, the job file's line recorded as where it was set."""
    pos = SourcePos(str(job_path), parameter.line or 0)
    if parameter.component is None:
        set_field_value(record, parameter.name, value, pos)
    elif isinstance(value, str) or np.ndim(value):
        raise ModelError(f"'{parameter.key}': a component takes a number, not {value!r}", pos.file, pos.line)
    else:
        set_field(record, parameter.name, np.array([[float(value)]]), pos, parameter.component)


def apply_variant(model: DapbcModel, variant: Variant | None, job_path: str | Path) -> DapbcModel:
    """``model`` with the variant's element fields set (in place)."""
    for parameter, pick in zip(variant.parameters if variant else (), variant.picks if variant else ()):
        if parameter.kind == ELEMENT:
            element = getattr(model, ELEMENTS[parameter.section][0])[parameter.index - 1]
            set_element(element, parameter, parameter.values[pick], job_path)
    return model


def run_settings(job: DapbcJob, variant: Variant | None) -> tuple[str, DapbcSettings]:
    """The analysis and settings of a variant's run: the job's ``[main]`` with the variant's
    ``run.<key>`` values; ModelError when they make no valid settings."""
    settings = job.settings
    for parameter, pick in zip(variant.parameters if variant else (), variant.picks if variant else ()):
        if parameter.kind == RUN_SETTING:
            settings = dataclasses.replace(settings, **{parameter.name: parameter.values[pick]})
    return settings.analysis, DapbcSettings(settings.final_time, settings.report_step, settings.correct_ic,
                                            settings.method, settings.rtol, settings.atol, settings.projection)


def check_run_settings(job: DapbcJob, parameters: tuple[Parameter, ...], links: tuple[tuple[int, ...], ...]) -> None:
    """Every combination of the varied run settings that a variant has (``links``: the ``zip``
    groups), with the job's own settings, makes valid settings; ModelError at the line of the
    first varied run key (or of ``[main]``) otherwise."""
    from mbds.analysis import analysis

    varied = tuple(p for p in parameters if p.kind == RUN_SETTING)
    for variant in kind_product(parameters, links, RUN_SETTING) or [None]:
        try:
            name, _ = run_settings(job, variant)
            analysis(name)
        except ModelError as exc:
            where = f"variant ({', '.join(f'{k} = {v}' for k, v in variant.values.items())}): " if variant else ""
            line = varied[0].line if varied else job.line("finalTime")
            raise ModelError(f"{where}{exc.message}", job.path, line) from None


def _run_parameter(key: str, texts: tuple[str, ...], line: int | None, job: DapbcJob) -> DapbcParameter:
    """A varied ``run.<key>``: numbers, flags, or the names of an analysis or method."""
    path, name = job.path, key[len("run."):]
    f = _RUN_FIELDS.get(name.lower())
    if f is None:
        known = [g.metadata["key"] for g in _RUN_FIELDS.values()]
        raise ModelError(f"'{key}': '{name}' is not a run setting{did_you_mean(name, known, 'settings')}", path, line)
    kind = f.metadata["kind"]
    if kind == "number":
        values = tuple(parse_number(t, path, line) for t in texts)
    elif kind == "flag":
        values = tuple(parse_flag(t, path, line) for t in texts)
    else:
        values = texts
        if f.name == "method":
            for t in texts:
                if t not in METHODS:
                    raise ModelError(f"'{key}': unknown method '{t}' (known: {', '.join(METHODS)})", path, line)
    return DapbcParameter(key, RUN_SETTING, "run", f.name, values, texts, line)


def _whole(text: str, what: str, path: Path, line: int | None) -> int:
    if not text.isdigit():
        raise ModelError(f"{what} must be a whole number, not '{text}'", path, line)
    return int(text)


def _plain(value):
    """An evaluated value as a plain number, tuple of numbers or text (None for a struct)."""
    if isinstance(value, np.ndarray):
        return float(value[0, 0]) if value.shape == (1, 1) else tuple(float(v) for v in value.reshape(-1))
    if isinstance(value, str):
        return value
    return None

