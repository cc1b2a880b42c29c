"""Variants of a campaign: ``[campaign]`` keys that list values for a constant, a world setting
or a contact law; their cartesian product (keys linked by ``zip`` vary together); and the model
files of one variant.

Keys (docs/campaigns.md): ``c'name`` (a constant of the ``.cns`` file), ``world.<key>`` (a
number, flag or expression key of the world file's ``[main]``) and ``contact.<section>.<key>``
(a law key of section ``[section]`` of the ``.cop`` file, e.g. ``contact.mass1-mass2.friction``).
Values are separated by commas, and by nothing else (``0.2 0.4`` or ``0.2; 0.4`` is an error, not
one value); each value is checked as the model file would check it, at the job file's line; numbers use ``.`` as decimal mark, as everywhere in a job file
(expressions are written into a model whose ``decimalSeparator`` is ``,`` with ``,``).
"""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import math
import re
from dataclasses import dataclass
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.constants import format_constants
from mbds.io.contacts import ContactLaw, ContactSection, ContactsFile, format_contacts
from mbds.io.folder import ModelFiles
from mbds.io.ini import Entry, Located, Section, check_rules, read_settings, split_list
from mbds.io.text import QUOTES, parse_number
from mbds.io.world import RULES as WORLD_RULES
from mbds.io.world import WorldSettings, format_world, parse_world

CONSTANT, WORLD, CONTACT = "constant", "world", "contact"
_VARIED_KINDS = ("number", "flag", "expression")  # settings kinds a variant may change
_SEVERAL = re.compile(r"[\w.)\]`'\u2018\u2019]\s+[\w.(\[]")
"""Two operands side by side with only blanks between them: several values, not one."""


@dataclass(frozen=True)
class Parameter:
    """One varied key: ``kind`` (constant, world or contact), the contact ``section`` title,
    the constant name or settings field ``name``, the ``values`` (parsed) and ``texts`` (as
    written), and its ``line`` in the job file."""

    key: str
    kind: str
    section: str
    name: str
    values: tuple
    texts: tuple[str, ...]
    line: int | None

    @property
    def target(self) -> tuple:
        """What the key changes: two keys with one target are one key given twice."""
        return self.kind, self.section, self.name


@dataclass(frozen=True)
class Variant:
    """One combination of values: ``picks[i]`` is the index of the value of ``parameters[i]``.
    ``id`` is ``v00``, ``v01``, ... in the order of the cartesian product."""

    id: str
    index: int
    parameters: tuple[Parameter, ...]
    picks: tuple[int, ...]

    @property
    def values(self) -> dict[str, str]:
        """The value of each key, as written in the job file."""
        return {p.key: p.texts[k] for p, k in zip(self.parameters, self.picks)}


def is_parameter_key(key: str) -> bool:
    """Whether a ``[campaign]`` key names something to vary."""
    return key[:2] in {f"c{q}" for q in QUOTES} or key.lower().startswith(("world.", "contact."))


def parse_parameter(key: str, text: str, line: int | None, files: ModelFiles, job_path: Path) -> Parameter:
    """A varied key of the ``[campaign]`` section, checked against the model ``files``."""
    texts = tuple(split_list(text))
    if not texts or not all(texts):
        raise ModelError(f"'{key}' needs values separated by commas (e.g. 0.1, 0.2)", job_path, line)
    for item in texts:
        if ";" in item or _SEVERAL.search(item):
            raise ModelError(f"'{key}': '{item}' reads as several values; separate values by commas only "
                             "(e.g. 0.2, 0.4)", job_path, line)
    if len(set(texts)) != len(texts):
        raise ModelError(f"'{key}' lists a value twice", job_path, line)
    sep = files.separator
    if key.lower().startswith("world."):
        name = _field(WorldSettings, key[len("world."):], "world file [main]", key, job_path, line)
        values = tuple(_parse(WorldSettings, name, t, job_path, line, sep) for t in texts)
        for value, item in zip(values, texts):
            _check_world_value(files, name, value, f"'{key}' value '{item}'", job_path, line)
        return Parameter(key, WORLD, "", name, values, texts, line)
    if key.lower().startswith("contact."):
        section, _, law_key = key[len("contact."):].rpartition(".")
        temperature = _section(files.contacts, section, key, job_path, line).law.initial_temperature
        name = _field(ContactLaw, law_key, "contact law", key, job_path, line)
        values = tuple(_parse(ContactLaw, name, t, job_path, line, sep) for t in texts)
        for value, item in zip(values, texts):
            if name == "initial_temperature":
                continue
            with _at(f"'{key}' value '{item}'", job_path, line):
                from mbds.model.checks import check_law_value  # sympy: imported only when a law is varied

                check_law_value(name, value, files, temperature, job_path)
        return Parameter(key, CONTACT, section, name, values, texts, line)
    name = key[2:].strip()
    if name not in files.constants.values:
        raise ModelError(f"constant c'{name} is not in the model's constants file", job_path, line)
    values = tuple(parse_number(t, job_path, line) for t in texts)
    return Parameter(key, CONSTANT, "", name, values, texts, line)


def axes(parameters: tuple[Parameter, ...], links: tuple[tuple[int, ...], ...] = ()) -> list[tuple[int, ...]]:
    """The independent axes of the variants: each linked group of parameter indices (they take
    their k-th values together), and each other parameter alone; in the order of their first key."""
    linked = {i for group in links for i in group}
    found = [tuple(group) for group in links] + [(i,) for i in range(len(parameters)) if i not in linked]
    return sorted(found, key=min)


def variant_count(parameters: tuple[Parameter, ...], links: tuple[tuple[int, ...], ...] = ()) -> int:
    """How many variants :func:`product` makes, counted without making them."""
    return math.prod(len(parameters[axis[0]].values) for axis in axes(parameters, links))


def product(parameters: tuple[Parameter, ...], links: tuple[tuple[int, ...], ...] = ()) -> list[Variant]:
    """Every combination of the parameters' values, the last key varying fastest; the keys of
    a linked group (``links``, groups of parameter indices) take their k-th values together. One
    variant (with nothing changed) when there are no parameters."""
    order = axes(parameters, links)
    combos = list(itertools.product(*(range(len(parameters[axis[0]].values)) for axis in order)))
    width = max(2, len(str(len(combos) - 1)))
    variants = []
    for index, combo in enumerate(combos):
        picks = [0] * len(parameters)
        for axis, k in zip(order, combo):
            for i in axis:
                picks[i] = k
        variants.append(Variant(f"v{index:0{width}d}", index, parameters, tuple(picks)))
    return variants


def variant_files(files: ModelFiles, variant: Variant) -> tuple[ModelFiles, dict[str, str]]:
    """The model ``files`` with the variant's values in, and the texts of the files that
    changed, by path relative to the world file's folder."""
    world, constants, contacts = files.world, files.constants, files.contacts
    for p, pick in zip(variant.parameters, variant.picks):
        value = p.values[pick]
        if p.kind == CONSTANT:
            constants = dataclasses.replace(constants, values={**constants.values, p.name: value})
        elif p.kind == WORLD:
            world = dataclasses.replace(world, settings=dataclasses.replace(world.settings, **{p.name: value}))
        else:
            contacts = _with_law(contacts, p, value)
    changed = dataclasses.replace(files, world=world, constants=constants, contacts=contacts)
    base, sep = files.world.path.parent, files.separator
    texts = {}
    if world != files.world:
        texts[world.path.name] = format_world(world)
    if constants != files.constants:
        texts[_relative(world, world.settings.constants_file, base)] = format_constants(constants, sep)
    if contacts != files.contacts:
        texts[_relative(world, world.settings.contact_properties_file, base)] = format_contacts(contacts, sep)
    return changed, texts


def check_world_combinations(files: ModelFiles, parameters: tuple[Parameter, ...], job_path: Path,
                             links: tuple[tuple[int, ...], ...] = ()) -> None:
    """Every combination of the varied world keys that a variant has passes the world file's
    checks (minimumTimestep <= maximumTimestep, ...); see :func:`check_world`."""
    for variant in kind_product(parameters, links, WORLD):
        check_world(files, variant, job_path)


def kind_product(parameters: tuple[Parameter, ...], links: tuple[tuple[int, ...], ...], kind: str) -> list[Variant]:
    """The combinations of the values of the parameters of ``kind`` alone that variants have
    (linked keys of that kind taken together); none when no parameter is of ``kind``."""
    chosen = [i for i, p in enumerate(parameters) if p.kind == kind]
    local = {i: k for k, i in enumerate(chosen)}
    chosen_links = tuple(g for g in (tuple(local[i] for i in group if i in local) for group in links) if len(g) > 1)
    return product(tuple(parameters[i] for i in chosen), chosen_links) if chosen else []


def check_world(files: ModelFiles, variant: Variant, job_path: Path) -> None:
    """The world settings of ``variant`` pass the world file's checks (minimumTimestep <=
    maximumTimestep, ...); ModelError at the line of its first world key otherwise."""
    world = [p for p in variant.parameters if p.kind == WORLD]
    if not world:
        return
    world_file = variant_files(files, variant)[0].world
    try:
        parse_world(format_world(world_file), world_file.path)
    except ModelError as exc:
        values = ", ".join(f"{k} = {v}" for k, v in variant.values.items())
        raise ModelError(f"variant {variant.id} ({values}): {exc.message}", job_path, world[0].line) from None


def _field(cls, key: str, what: str, full_key: str, job_path: Path, line: int | None) -> str:
    """The settings field of ``cls`` read from ``key`` (any letter case), if a variant may
    change it."""
    for f in dataclasses.fields(cls):
        names = [f.metadata["key"], *f.metadata["aliases"]]
        if key.lower() in (n.lower() for n in names):
            if f.metadata["kind"] not in _VARIED_KINDS:
                raise ModelError(f"'{full_key}': {key} cannot be varied (only numbers, flags and expressions)",
                                 job_path, line)
            return f.name
    raise ModelError(f"'{full_key}': '{key}' is not a {what} key", job_path, line)


def _parse(cls, name: str, text: str, job_path: Path, line: int | None, separator: str):
    """``text`` read as the value of field ``name`` of the settings class ``cls``; an
    expression gets the model's decimal ``separator``."""
    f = cls.__dataclass_fields__[name]
    section = Section("campaign", line or 0, [Entry(f.metadata["key"], text, line or 0)])
    value = getattr(read_settings(cls, section, job_path), name)
    if isinstance(value, Located) and separator == ",":
        return Located(value.text.replace(".", ","), line)
    return value


def _section(contacts: ContactsFile, title: str, key: str, job_path: Path, line: int | None) -> ContactSection:
    """The ``.cop`` file's section ``[title]``; ModelError when there is none."""
    for s in contacts.sections:
        if s.title == title:
            return s
    known = ", ".join(f"[{s.title}]" for s in contacts.sections) or "none"
    raise ModelError(f"'{key}': the contact properties file has no section [{title}] (it has {known})",
                     job_path, line)


@contextlib.contextmanager
def _at(what: str, job_path: Path, line: int | None):
    """ModelErrors of the block moved to the job file's ``line``, prefixed with ``what``."""
    try:
        yield
    except ModelError as exc:
        raise ModelError(f"{what}: {exc.message}", job_path, line) from None


def _check_world_value(files: ModelFiles, name: str, value, what: str, job_path: Path, line: int | None) -> None:
    """One varied world value in its range (``breakTime``: a positive time)."""
    with _at(what, job_path, line):
        if name == "break_time":
            from mbds.model.load import break_time  # sympy: imported only when breakTime is varied

            world = dataclasses.replace(files.world, settings=dataclasses.replace(files.world.settings, break_time=value))
            break_time(dataclasses.replace(files, world=world), job_path)
        elif name in WORLD_RULES:
            settings = dataclasses.replace(files.world.settings, **{name: value})
            check_rules(settings, {name: WORLD_RULES[name]}, None, job_path)


def _with_law(contacts: ContactsFile, p: Parameter, value) -> ContactsFile:
    """``contacts`` with ``p``'s key of its section set to ``value``."""
    key = ContactLaw.__dataclass_fields__[p.name].metadata["key"].lower()
    sections = [
        dataclasses.replace(s, law=dataclasses.replace(s.law, **{p.name: value}),
                            keys=None if s.keys is None else s.keys | {key})
        if s.title == p.section else s
        for s in contacts.sections
    ]
    return dataclasses.replace(contacts, sections=sections)


def _relative(world, name: str, base: Path) -> str:
    """The path of model file ``name`` relative to the world file's folder."""
    return world.resolve(name).relative_to(base).as_posix()
