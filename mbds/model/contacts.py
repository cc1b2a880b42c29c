"""Contact pairs of an assembled model, from the ``.cop`` sections.

A pair of bodies is checked for contact when a ``[a-b]`` or ``[a:all]`` section names it. Its
properties start from the defaults, take the keys of every ``[a:all]`` and ``[b:all]`` section
(in file order), and then those set by the ``[a-b]`` section. Pairs that can never touch are
left out: a body and its own virtual bodies, two virtual bodies of one carrier, and two bodies
that both never move.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from mbds.errors import ModelError
from mbds.io.contacts import ContactLaw
from mbds.io.folder import ModelFiles
from mbds.model.bodies import FIXED, Body


@dataclass
class ContactPair:
    """Bodies ``first`` and ``second`` (indices); ``law`` indexes the model's contact laws;
    ``resisting`` says whether first and second resist penetration (T:F -> (True, False))."""

    first: int
    second: int
    law: int
    resisting: tuple[bool, bool]
    initial_temperature: float
    sections: tuple[str, ...]
    heat_capacity: float = 0.0  # J/°C of each point's share of the heat; 0: no temperature model
    cooling_time: float = 0.0  # s; 0: the points do not cool

    @property
    def heated(self) -> bool:
        return self.heat_capacity > 0.0


def law_key(law: ContactLaw) -> tuple[str, str, str, str]:
    return tuple(x.text for x in (law.friction, law.restitution_normal, law.restitution_tangent, law.parameter_ni))


def assemble_contacts(files: ModelFiles, bodies: list[Body]) -> tuple[list[ContactPair], list[ContactLaw]]:
    """The contact pairs and the distinct merged laws they refer to."""
    index = {b.name: i for i, b in enumerate(bodies)}
    cop = files.contacts
    for s in cop.sections:
        for name in (s.first, s.second):
            if name is not None and name not in index:
                raise ModelError(f"[{s.title}] names no body '{name}' (bodies: {', '.join(index)})", cop.path, s.line)
    pairs, laws, keys = [], [], []
    for a in range(len(bodies)):
        for b in range(a + 1, len(bodies)):
            if not _can_touch(bodies, a, b):
                continue
            names = (bodies[a].name, bodies[b].name)
            applying = [s for s in cop.sections if s.second is None and s.first in names]
            applying += [s for s in cop.sections if s.second is not None and {s.first, s.second} == set(names)]
            if not applying:
                continue
            law, resisting = ContactLaw(), (True, True)
            for s in applying:
                for f in fields(ContactLaw):
                    if s.keys is None or f.metadata["key"].lower() in s.keys:
                        setattr(law, f.name, getattr(s.law, f.name))
                flags = tuple(part == "T" for part in s.law.resisting_penetration.split(":"))
                if s.keys is None or "resistingpenetration" in s.keys:
                    resisting = flags if s.first == names[0] else flags[::-1]
            if not any(resisting):
                continue
            if law_key(law) not in keys:
                keys.append(law_key(law))
                laws.append(law)
            titles = tuple(s.title for s in applying)
            for value, key in ((law.heat_capacity, "heatCapacity"), (law.cooling_time, "coolingTime")):
                if not value >= 0.0:
                    raise ModelError(f"{key} = {value:g} of {names[0]}-{names[1]}: must be 0 or more", cop.path,
                                     applying[-1].line)
            pairs.append(ContactPair(a, b, keys.index(law_key(law)), resisting, law.initial_temperature, titles,
                                     law.heat_capacity, law.cooling_time))
    _check_heat_models(pairs, bodies, cop)
    return pairs, laws


def _check_heat_models(pairs: list[ContactPair], bodies: list[Body], cop) -> None:
    """A body's points have one temperature: every heated pair of a body must give it the same
    heatCapacity, coolingTime and initialTemperature."""
    seen: dict[int, ContactPair] = {}
    for pair in (p for p in pairs if p.heated):
        model = (pair.heat_capacity, pair.cooling_time, pair.initial_temperature)
        for body in (pair.first, pair.second):
            other = seen.setdefault(body, pair)
            if (other.heat_capacity, other.cooling_time, other.initial_temperature) != model:
                line = next((s.line for s in cop.sections if s.title == pair.sections[-1]), None)
                raise ModelError(
                    f"body '{bodies[body].name}' has two temperature models: [{other.sections[-1]}] and "
                    f"[{pair.sections[-1]}] give heatCapacity, coolingTime or initialTemperature differently",
                    cop.path, line)


def _can_touch(bodies: list[Body], a: int, b: int) -> bool:
    carrier_a = bodies[a].carrier if bodies[a].virtual else a
    carrier_b = bodies[b].carrier if bodies[b].virtual else b
    if carrier_a == carrier_b:
        return False
    return not (_never_moves(bodies[carrier_a]) and _never_moves(bodies[carrier_b]))


def _never_moves(body: Body) -> bool:
    return all(kind == FIXED for kind in body.binding)
