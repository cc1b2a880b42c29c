"""Contact properties files (``.cop``): friction and restitution laws per body pair."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.ini import FRACTION, NOT_NEGATIVE, Located, format_settings, parse_ini, read_settings, setting
from mbds.io.text import parse_number

RESISTING = ("T:T", "T:F", "F:T")


@dataclass
class ContactLaw:
    """Keys of one section; the laws are expressions in constants, ``temp`` and ``vRel``."""

    resisting_penetration: str = setting("resistingPenetration", "text", "T:T")
    friction: Located = setting("friction", "expression", Located("0"))
    restitution_normal: Located = setting("restitutionNormal", "expression", Located("0"))
    restitution_tangent: Located = setting("restitutionTangent", "expression", Located("0"))
    parameter_ni: Located = setting("parameterNi", "expression", Located("0"))
    initial_temperature: float = setting("initialTemperature", "number", 0.0)
    heat_capacity: float = setting("heatCapacity", "number", 0.0, extension=True)  # J/°C per point; 0: none
    cooling_time: float = setting("coolingTime", "number", 0.0, extension=True)  # s; 0: no cooling


LAW_RULES = {"friction": NOT_NEGATIVE, "restitution_normal": FRACTION, "restitution_tangent": FRACTION}
"""The range of the law values (at every temperature and relative velocity)."""


def check_law_numbers(law: ContactLaw, path, separator: str = ".") -> None:
    """The law values written as plain numbers in their range; ModelError at their line."""
    for name, rule in LAW_RULES.items():
        item = getattr(law, name)
        try:
            value = parse_number(item.text, path, item.line, separator)
        except ModelError:  # an expression: checked at its initial temperature once the model is assembled
            continue
        if not rule.holds(value):
            key = ContactLaw.__dataclass_fields__[name].metadata["key"]
            raise ModelError(f"{key} = {item.text} {rule.says}", path, item.line)


@dataclass
class ContactSection:
    """``[a-b]`` (``second`` is the other body) or ``[a:all]`` (``second`` is None)."""

    first: str
    second: str | None
    law: ContactLaw
    keys: frozenset | None = None  # keys the section sets (lower case); None: all of them
    line: int | None = field(default=None, compare=False)

    @property
    def title(self) -> str:
        return f"{self.first}:all" if self.second is None else f"{self.first}-{self.second}"


@dataclass
class ContactsFile:
    sections: list[ContactSection] = field(default_factory=list)
    path: Path | None = field(default=None, compare=False)


def parse_contacts(text: str, path: str | Path | None = None, separator: str = ".") -> ContactsFile:
    sections = []
    for s in parse_ini(text, path):
        if not s.name:
            raise ModelError("entries before the first [body-body] or [body:all] section", path, s.entries[0].line)
        if s.name.lower().endswith(":all"):
            first, second = s.name[: -len(":all")].strip(), None
        elif s.name.count("-") == 1:
            first, second = (part.strip() for part in s.name.split("-"))
        else:
            raise ModelError(f"section [{s.name}] must be [body1-body2] or [body:all]", path, s.line)
        if not first or second == "":
            raise ModelError(f"section [{s.name}] names no body", path, s.line)
        if first == second:
            raise ModelError(f"section [{s.name}] pairs a body with itself", path, s.line)
        law = read_settings(ContactLaw, s, path, separator)
        law.resisting_penetration = law.resisting_penetration.upper().replace(" ", "")
        if law.resisting_penetration not in RESISTING:
            raise ModelError(
                f"resistingPenetration must be one of {', '.join(RESISTING)}, not '{law.resisting_penetration}'",
                path,
                next(e.line for e in s.entries if e.key.lower() == "resistingpenetration"),
            )
        check_law_numbers(law, path, separator)
        known = {f.metadata["key"].lower() for f in fields(ContactLaw)}
        keys = frozenset(e.key.lower() for e in s.entries) & known
        sections.append(ContactSection(first, second, law, keys, s.line))
    return ContactsFile(sections, Path(path) if path else None)


def format_contacts(cop: ContactsFile, separator: str = ".") -> str:
    lines = []
    for s in cop.sections:
        entries = format_settings(s.law, separator)
        if s.keys is not None:
            entries = [e for e in entries if e.split(" = ")[0].lower() in s.keys]
        lines += [f"[{s.title}]", *entries]
    return "\n".join(lines) + "\n" if lines else ""
