"""INI-style files of MBDS (world, job, body, contact properties, watches).

Sections are ``[name]``; entries are ``key = value``. Keys are matched in any letter case.
Settings classes declare their keys once, as dataclass fields whose metadata names the key and
its kind; :func:`read_settings` and :func:`format_settings` use that declaration both ways, so
reading what was written gives the same settings.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mbds.errors import ModelError, warn
from mbds.io.text import (
    MAXINT,
    format_number,
    parse_flag,
    parse_integer,
    parse_number,
    significant_lines,
)


@dataclass(frozen=True)
class Located:
    """A text value (an expression, a name) and the line it was read from."""

    text: str
    line: int | None = field(default=None, compare=False)

    def __str__(self) -> str:
        return self.text


@dataclass
class Entry:
    key: str
    value: str
    line: int


@dataclass
class Section:
    """One ``[name]`` section with its entries in file order."""

    name: str
    line: int
    entries: list[Entry] = field(default_factory=list)


def parse_ini(text: str, file: str | Path | None) -> list[Section]:
    """Sections of an INI text; entries before the first header go to a section named ``""``."""
    sections = [Section("", 0)]
    for line in significant_lines(text, file):
        content = line.text
        if content.startswith("["):
            if not content.endswith("]") or len(content) < 3:
                raise ModelError(f"malformed section header '{content}'", file, line.number)
            sections.append(Section(content[1:-1].strip(), line.number))
        elif "=" in content:
            key, _, value = content.partition("=")
            if not key.strip():
                raise ModelError(f"missing key before '=' in '{content}'", file, line.number)
            sections[-1].entries.append(Entry(key.strip(), value.strip(), line.number))
        else:
            raise ModelError(f"expected 'key = value' or '[section]', found '{content}'", file, line.number)
    if not sections[0].entries:
        sections.pop(0)
    return sections


def find_section(sections: list[Section], name: str) -> Section | None:
    """The section called ``name`` in any letter case (the last one if repeated)."""
    found = [s for s in sections if s.name.lower() == name.lower()]
    return found[-1] if found else None


# --- declared settings ---------------------------------------------------------------------


def setting(key: str, kind: str, default: Any, *aliases: str, extension: bool = False):
    """A dataclass field read from ``key`` (or an alias), parsed as ``kind``; an ``extension``
    (a key of mbds, not of the original program) is written only when it is not at its default.

    Kinds: ``number``, ``integer``, ``minutes`` (a number, or ``MaxInt``), ``flag``, ``text``, ``expression`` (kept as :class:`Located`
    text), ``pair`` (two numbers ``a,b``), ``list`` (comma-separated names), ``numbers``
    (comma-separated numbers).
    """
    if isinstance(default, (list, tuple)):
        factory = (lambda d=default: type(d)(d))
        return field(default_factory=factory, metadata={"key": key, "kind": kind, "aliases": aliases,
                                                         "extension": extension})
    return field(default=default, metadata={"key": key, "kind": kind, "aliases": aliases, "extension": extension})


def _parse_value(kind: str, entry: Entry, file, separator: str):
    value, line = entry.value, entry.line
    if kind == "number":
        return parse_number(value, file, line, separator)
    if kind == "integer":
        return parse_integer(value, file, line)
    if kind == "minutes":
        return MAXINT if value.strip().lower() == "maxint" else parse_number(value, file, line, separator)
    if kind == "flag":
        return parse_flag(value, file, line)
    if kind == "text":
        return value
    if kind == "expression":
        if not value:
            raise ModelError(f"'{entry.key}' needs an expression", file, line)
        return Located(value, line)
    if kind == "pair":
        parts = split_list(value, separator)
        if len(parts) != 2:
            raise ModelError(f"'{entry.key}' needs two numbers 'a,b', found '{value}'", file, line)
        return tuple(parse_number(p, file, line, separator) for p in parts)
    if kind == "list":
        return [p.strip() for p in split_list(value, separator) if p.strip()]
    if kind == "numbers":
        return [parse_number(p, file, line, separator) for p in split_list(value, separator)]
    raise AssertionError(kind)


def split_list(value: str, separator: str = ".") -> list[str]:
    """Items of a list value: separated by ``,`` (or ``;`` when the decimal separator is ``,``)."""
    delimiter = ";" if separator == "," else ","
    return [part.strip() for part in value.split(delimiter)] if value.strip() else []


def _format_value(kind: str, value, separator: str) -> str:
    delimiter = ";" if separator == "," else ","
    if kind == "number":
        return format_number(value, separator)
    if kind == "minutes":
        return "MaxInt" if value == MAXINT else format_number(value, separator)
    if kind == "flag":
        return "1" if value else "0"
    if kind in ("pair", "numbers"):
        return delimiter.join(format_number(v, separator) for v in value)
    if kind == "list":
        return delimiter.join(value)
    return str(value)


def read_settings(cls, section: Section | None, file, separator: str = ".", **values):
    """An instance of the settings dataclass ``cls`` from ``section``.

    Keys are matched in any letter case; unknown keys are warned about; keys given twice warn
    and the last one counts. ``values`` pre-set fields that do not come from the section.
    """
    by_key = {}
    for f in dataclasses.fields(cls):
        if "key" in f.metadata:
            for name in (f.metadata["key"], *f.metadata["aliases"]):
                by_key[name.lower()] = f
    seen: dict[str, int] = {}
    for entry in section.entries if section else []:
        f = by_key.get(entry.key.lower())
        if f is None:
            warn(f"unknown key '{entry.key}' in [{section.name}] (ignored)", file, entry.line)
            continue
        if f.name in seen:
            warn(f"'{entry.key}' given again (first on line {seen[f.name]}); the last one counts", file, entry.line)
        seen[f.name] = entry.line
        values[f.name] = _parse_value(f.metadata["kind"], entry, file, separator)
    return cls(**values)


@dataclass(frozen=True)
class Rule:
    """A range a setting must lie in: ``holds(value)``, and ``says`` what it must be."""

    holds: Any
    says: str


POSITIVE = Rule(lambda v: v > 0, "must be positive")
NOT_NEGATIVE = Rule(lambda v: v >= 0, "must not be negative")
OPEN_FRACTION = Rule(lambda v: 0 < v < 1, "must lie between 0 and 1 (both excluded)")
FRACTION = Rule(lambda v: 0 <= v <= 1, "must lie between 0 and 1")


def key_line(section: Section | None, cls, name: str) -> int | None:
    """The line of the key (or an alias) of field ``name`` of ``cls`` in ``section``; the
    section's header line when the key is not there."""
    f = cls.__dataclass_fields__[name]
    keys = {k.lower() for k in (f.metadata["key"], *f.metadata["aliases"])}
    found = [e.line for e in section.entries if e.key.lower() in keys] if section else []
    return found[-1] if found else (section.line if section else None)


def check_rules(obj, rules: dict, section: Section | None, file) -> None:
    """Each field of the settings ``obj`` named in ``rules`` (field -> :class:`Rule`) that is
    set satisfies its rule; ModelError at the line of its key otherwise."""
    for name, rule in rules.items():
        value = getattr(obj, name)
        if value is not None and not rule.holds(value):
            key = type(obj).__dataclass_fields__[name].metadata["key"]
            raise ModelError(f"{key} = {format_number(value)} {rule.says}", file, key_line(section, type(obj), name))


def format_settings(obj, separator: str = ".", *, skip_defaults: bool = False) -> list[str]:
    """``key = value`` lines for the declared fields of a settings dataclass."""
    lines = []
    for f in dataclasses.fields(obj):
        if "key" not in f.metadata:
            continue
        value = getattr(obj, f.name)
        if (skip_defaults or f.metadata.get("extension")) and _is_default(f, value):
            continue
        lines.append(f"{f.metadata['key']} = {_format_value(f.metadata['kind'], value, separator)}")
    return lines


def _is_default(f: dataclasses.Field, value) -> bool:
    if f.default is not dataclasses.MISSING:
        return value == f.default
    if f.default_factory is not dataclasses.MISSING:
        return value == f.default_factory()
    return False
