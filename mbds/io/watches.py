"""Watches and reshaping files (``.wtc``): which contact points are watched, and how the
next version of the model is reshaped and its constants updated."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.ini import find_section, format_settings, parse_ini, read_settings, setting

FIXED_SECTIONS = ("common", "constantsupdate", "changeconstants", "reshapewindow", "bodybalancedupdate")


@dataclass(frozen=True)
class WatchItem:
    """One item of ``contactWatch``.

    ``first``/``last`` are 0-based point numbers (None for ``all``); ``combined`` sums the
    points into one watch (``1:3``, ``all:``), otherwise each point is its own watch (``1-3``);
    ``absolute`` reports impulses in the x-y frame instead of normal-tangential (``[...]``).
    """

    first: int | None
    last: int | None
    combined: bool = False
    absolute: bool = False

    def __str__(self) -> str:
        if self.first is None:
            text = "all:" if self.combined else "all"
        elif self.first == self.last and not self.combined:
            text = str(self.first)
        else:
            text = f"{self.first}{':' if self.combined else '-'}{self.last}"
        return f"[{text}]" if self.absolute else text

    def groups(self, count: int) -> list[list[int]]:
        """Point-number groups for a shape of ``count`` distinct points: one group per watch."""
        first, last = (0, count - 1) if self.first is None else (self.first, self.last)
        points = list(range(first, last + 1))
        return [points] if self.combined else [[p] for p in points]


_ITEM = re.compile(r"(all)(:?)|(\d+)(?:\s*([-:])\s*(\d+))?", re.IGNORECASE)


def parse_contact_watch(text: str, file=None, line=None) -> list[WatchItem]:
    """Items of a ``contactWatch`` value: ``1,2,5-10``, ``all``, ``1:3``, ``all:``, ``[1:3]``."""
    items = []
    for raw in _split_top_level(text, file, line):
        absolute = raw.startswith("[")
        inner = raw[1:-1].strip() if absolute else raw
        if absolute and not raw.endswith("]"):
            raise ModelError(f"unclosed '[' in contactWatch item '{raw}'", file, line)
        for part in _split_top_level(inner, file, line) if absolute else [inner]:
            m = _ITEM.fullmatch(part)
            if not m:
                raise ModelError(f"'{part}' is not a point, range (1-3), combination (1:3) or all", file, line)
            if m.group(1):
                items.append(WatchItem(None, None, bool(m.group(2)), absolute))
                continue
            first = int(m.group(3))
            last = int(m.group(5)) if m.group(5) else first
            if last < first:
                raise ModelError(f"range '{part}' runs backwards", file, line)
            items.append(WatchItem(first, last, m.group(4) == ":", absolute))
    if not items:
        raise ModelError("contactWatch lists no points", file, line)
    return items


def _split_top_level(text: str, file, line) -> list[str]:
    parts, depth, current = [], 0, ""
    for ch in text:
        depth += (ch == "[") - (ch == "]")
        if depth < 0 or depth > 1:
            raise ModelError(f"unbalanced brackets in '{text}'", file, line)
        if ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    if depth:
        raise ModelError(f"unbalanced brackets in '{text}'", file, line)
    parts.append(current.strip())
    if any(not p for p in parts):
        raise ModelError(f"empty item in '{text}'", file, line)
    return parts


@dataclass
class CommonOptions:
    """``[common]``: watch output options (``timeConstant`` in s)."""

    time_constant: float = setting("timeConstant", "number", 0.0)
    reshaping_cycles: int = setting("reshapingCycles", "integer", 1)
    smooth_work_left_right: int = setting("smoothWorkLeftRight", "integer", 0)
    convert_impulse_to_force: bool = setting("convertImpulseToForce", "flag", False)
    cumulative_work: bool = setting("cummulativeWork", "flag", False, "cumulativeWork")
    write_averaged_t_div_n: bool = setting("writeAveragedTDivN", "flag", False)
    absolute_angle_instead_of_work: bool = setting("absoluteAngleInsteadOfWork", "flag", False)


@dataclass
class ConstantsUpdate:
    """``[constantsUpdate]``: constants moved in proportion to each body's total lost work."""

    bodies: list = setting("body", "list", [])
    constants: list = setting("constant", "list", [])
    max_change: float = setting("maxChange", "number", 0.0)


@dataclass
class ChangeConstants:
    """``[changeConstants]``: constants incremented by fixed amounts in each new version."""

    constants: list = setting("constant", "list", [])
    changes: list = setting("change", "numbers", [])


@dataclass
class ReshapeWindow:
    """``[reshapeWindow]``: ``cutHiLowValues`` in percent; ``standardDeviationRange`` in sigmas."""

    cut_hi_low_values: float = setting("cutHiLowValues", "number", 0.0)
    standard_deviation_range: tuple = setting("standardDeviationRange", "pair", (-100.0, 100.0))


@dataclass
class BodyBalancedUpdate:
    """``[bodyBalancedUpdate]``: statistics and maximum taken over all listed bodies (m)."""

    bodies: list = setting("body", "list", [])
    max_change: float = setting("maxChange", "number", 0.0)


@dataclass
class BodyWatchOptions:
    """Keys of a ``[body]`` or ``[body:k]`` section (directions in body axes; maxChange in m)."""

    contact_watch: str = setting("contactWatch", "text", "")
    direction_x: float = setting("directionX", "number", 0.0)
    direction_y: float = setting("directionY", "number", 0.0)
    direction_inside: int = setting("directionInside", "integer", 0)
    max_change: list = setting("maxChange", "numbers", [0.0])


@dataclass
class BodyWatch:
    """A ``[body]`` section (``cycle`` None) or ``[body:k]`` section (used when version mod
    ``reshapingCycles`` == k); ``items`` is the parsed ``contactWatch``."""

    body: str
    cycle: int | None
    options: BodyWatchOptions
    items: list[WatchItem] = field(default_factory=list)
    line: int | None = field(default=None, compare=False)

    @property
    def title(self) -> str:
        return self.body if self.cycle is None else f"{self.body}:{self.cycle}"


@dataclass
class WatchesFile:
    common: CommonOptions = field(default_factory=CommonOptions)
    constants_update: ConstantsUpdate | None = None
    change_constants: ChangeConstants | None = None
    reshape_window: ReshapeWindow = field(default_factory=ReshapeWindow)
    body_balanced_update: BodyBalancedUpdate | None = None
    bodies: list[BodyWatch] = field(default_factory=list)
    path: Path | None = field(default=None, compare=False)

    def section_for(self, body: str, version: int) -> BodyWatch | None:
        """The section that applies to ``body`` in ``version``: ``[body:k]``, else ``[body]``."""
        cycle = version % max(self.common.reshaping_cycles, 1)
        found = [w for w in self.bodies if w.body == body and w.cycle == cycle]
        found = found or [w for w in self.bodies if w.body == body and w.cycle is None]
        return found[-1] if found else None


def parse_watches(text: str, path: str | Path | None = None, separator: str = ".") -> WatchesFile:
    sections = parse_ini(text, path)
    optional = {
        "constantsupdate": ConstantsUpdate,
        "changeconstants": ChangeConstants,
        "bodybalancedupdate": BodyBalancedUpdate,
    }
    parsed = {}
    for key, cls in optional.items():
        section = find_section(sections, key)
        parsed[key] = read_settings(cls, section, path, separator) if section else None
    common = read_settings(CommonOptions, find_section(sections, "common"), path, separator)
    window = read_settings(ReshapeWindow, find_section(sections, "reshapeWindow"), path, separator)
    _check_options(common, window, parsed, path, sections)
    bodies = []
    for s in sections:
        if s.name.lower() in FIXED_SECTIONS:
            continue
        if not s.name:
            raise ModelError("entries before the first section", path, s.entries[0].line)
        body, _, cycle_text = s.name.partition(":")
        cycle = None
        if cycle_text:
            if not cycle_text.strip().isdigit():
                raise ModelError(f"section [{s.name}]: the cycle after ':' must be a whole number", path, s.line)
            cycle = int(cycle_text)
            if cycle >= common.reshaping_cycles:
                warn(f"[{s.name}] is never used: reshapingCycles is {common.reshaping_cycles}", path, s.line)
        options = read_settings(BodyWatchOptions, s, path, separator)
        watch_line = next((e.line for e in s.entries if e.key.lower() == "contactwatch"), s.line)
        items = parse_contact_watch(options.contact_watch, path, watch_line) if options.contact_watch else []
        if options.direction_inside not in (-1, 0, 1):
            raise ModelError("directionInside must be 1 (inside), -1 (outside) or 0", path, s.line)
        if len(options.max_change) not in (1, 2):
            raise ModelError("maxChange must be one value or a range 'a,b'", path, s.line)
        bodies.append(BodyWatch(body.strip(), cycle, options, items, s.line))
    return WatchesFile(
        common,
        parsed["constantsupdate"],
        parsed["changeconstants"],
        window,
        parsed["bodybalancedupdate"],
        bodies,
        Path(path) if path else None,
    )


def _check_options(common, window, parsed, path, sections) -> None:
    def line_of(name):
        section = find_section(sections, name)
        return section.line if section else None

    if common.reshaping_cycles < 1:
        raise ModelError("reshapingCycles must be at least 1", path, line_of("common"))
    if common.time_constant < 0 or common.smooth_work_left_right < 0:
        raise ModelError("timeConstant and smoothWorkLeftRight must not be negative", path, line_of("common"))
    if not 0 <= window.cut_hi_low_values < 50:
        raise ModelError("cutHiLowValues is a percentage from 0 to below 50", path, line_of("reshapeWindow"))
    low, high = window.standard_deviation_range
    if low > high:
        raise ModelError("standardDeviationRange must be 'low,high' with low <= high", path, line_of("reshapeWindow"))
    update = parsed["constantsupdate"]
    if update is not None and len(update.bodies) != len(update.constants):
        raise ModelError("[constantsUpdate] needs one constant per body", path, line_of("constantsUpdate"))
    change = parsed["changeconstants"]
    if change is not None and len(change.constants) != len(change.changes):
        raise ModelError("[changeConstants] needs one change per constant", path, line_of("changeConstants"))


def format_watches(wtc: WatchesFile, separator: str = ".") -> str:
    lines = ["[common]", *format_settings(wtc.common, separator)]
    for title, value in (
        ("constantsUpdate", wtc.constants_update),
        ("changeConstants", wtc.change_constants),
        ("reshapeWindow", wtc.reshape_window),
        ("bodyBalancedUpdate", wtc.body_balanced_update),
    ):
        if value is not None:
            lines += [f"[{title}]", *format_settings(value, separator)]
    for w in wtc.bodies:
        options = w.options
        lines += [f"[{w.title}]", *format_settings(options, separator)]
    return "\n".join(lines) + "\n"
