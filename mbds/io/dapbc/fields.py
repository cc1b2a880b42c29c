"""Assigning values to the fields of DAP_BC records, checked against the manual's tables."""

from __future__ import annotations

import difflib

import numpy as np

from mbds.errors import ModelError
from mbds.io.dapbc.records import Element, Force, Funct, Joint, SourcePos
from mbds.io.dapbc.values import is_whole, shape_text

FORCE_TYPES = ("ptp", "rot-sda", "weight", "flocal", "f", "T", "user")
JOINT_TYPES = ("rev", "tran", "rev-rev", "rev-tran", "rigid", "disc", "rel-rot", "rel-tran")
FUNCT_TYPES = ("a", "b", "c")
SHAPES = ("", " ", "circle", "rect", "line")
COLORS = {"y": "#ffff00", "m": "#ff00ff", "c": "#00ffff", "r": "#ff0000", "g": "#00ff00", "b": "#0000ff",
          "w": "#ffffff", "k": "#000000", "yellow": "#ffff00", "magenta": "#ff00ff", "cyan": "#00ffff",
          "red": "#ff0000", "green": "#00ff00", "blue": "#0000ff", "white": "#ffffff", "black": "#000000"}
"""MATLAB's eight predefined colours (short and long names) as RGB hex codes (MathWorks,
"ColorSpec (Color Specification)", MATLAB R2021a documentation): a body's ``color``."""
_CHOICES = {(Force, "type"): FORCE_TYPES, (Joint, "type"): JOINT_TYPES,
            (Funct, "type"): FUNCT_TYPES, ("Body", "shape"): SHAPES, ("Body", "color"): tuple(COLORS)}


def field_kind(record: Element, name: str) -> str:
    """'num', 'index', 'vec2', 'vector' or 'text', from the field's default value."""
    default = getattr(type(record)(), name)
    if isinstance(default, str):
        return "text"
    if isinstance(default, np.ndarray):
        return "vec2" if default.shape == (2,) else "vector"
    return "index" if isinstance(default, int) else "num"


def did_you_mean(name: str, names, listing: str = "fields") -> str:
    """``; did you mean 'x'?`` with the closest of ``names`` (case first), else the list of them."""
    names = list(names)
    close = [n for n in names if n.lower() == name.lower()] or difflib.get_close_matches(name, names, n=1)
    return f"; did you mean '{close[0]}'?" if close else f" ({listing}: {', '.join(names)})"


def unknown_field(record: Element, name: str) -> str:
    """The message for a field the record does not have (with the closest known name)."""
    return f"{type(record).__name__} has no field '{name}'{did_you_mean(name, record.field_names())}"


def set_field(record: Element, name: str, value, pos: SourcePos, component: int | None = None) -> None:
    """Store ``value`` (evaluator value) in ``record.name`` (or one 1-based component of a
    vector field), checking its kind; records where it was set."""
    where = (pos.file, pos.line)
    label = f"{type(record).__name__} field '{name}'"
    if name not in record.field_names():
        raise ModelError(unknown_field(record, name), *where)
    kind = field_kind(record, name)
    if component is not None:
        if kind not in ("vec2", "vector"):
            raise ModelError(f"{label} is not a vector; it cannot be indexed", *where)
        current = getattr(record, name)
        if not 1 <= component <= max(len(current), 2 if kind == "vec2" else component):
            raise ModelError(f"{label} has no component {component}", *where)
        number = _number(value, label, where)
        if kind == "vector" and component > len(current):
            current = np.concatenate([current, np.zeros(component - len(current))])
        current = current.copy()
        current[component - 1] = number
        setattr(record, name, current)
    elif kind == "text":
        if not isinstance(value, str):
            raise ModelError(f"{label} must be text in quotes, not {shape_text(value)}", *where)
        choices = _CHOICES.get((type(record), name)) or _CHOICES.get((type(record).__name__, name))
        if choices is not None and value not in choices:
            listed = ", ".join(f"'{c}'" for c in choices if c.strip())
            raise ModelError(f"{label}: unknown '{value}' (one of {listed})", *where)
        setattr(record, name, value)
    elif kind == "num":
        setattr(record, name, _number(value, label, where))
    elif kind == "index":
        number = _number(value, label, where)
        if number < 0 or not is_whole(number):
            raise ModelError(f"{label} must be a whole number >= 0, not {number:g}", *where)
        setattr(record, name, int(number))
    else:
        if not isinstance(value, np.ndarray) or (value.size and 1 not in value.shape):
            raise ModelError(f"{label} must be a vector, not {shape_text(value)}", *where)
        flat = value.reshape(-1).astype(float)
        if kind == "vec2" and flat.size != 2:
            raise ModelError(f"{label} must be a 2-vector like [0.2; -0.1], not {shape_text(value)}", *where)
        if not np.all(np.isfinite(flat)):
            raise ModelError(f"{label} is not finite: {flat.tolist()}", *where)
        setattr(record, name, flat)
    record.field_sources[name] = pos


def _number(value, label: str, where) -> float:
    if not isinstance(value, np.ndarray) or value.shape != (1, 1):
        raise ModelError(f"{label} must be a number, not {shape_text(value)}", *where)
    number = float(value[0, 0])
    if not np.isfinite(number):
        raise ModelError(f"{label} is not a finite number ({number})", *where)
    return number


def get_field(record: Element, name: str, where):
    """A field's value as the evaluator sees it (numbers as 1x1, vectors as columns)."""
    if name not in record.field_names():
        raise ModelError(unknown_field(record, name), *where)
    value = getattr(record, name)
    if isinstance(value, str):
        return value
    if isinstance(value, np.ndarray):
        return value.reshape(-1, 1).copy() if field_kind(record, name) == "vec2" else value.reshape(1, -1).copy()
    return np.array([[float(value)]])


def set_field_value(record: Element, name: str, value, pos: SourcePos) -> None:
    """Set a field from a plain Python value (a number, a sequence of numbers or text), with the
    checks of the in-files; for campaign variations such as ``force.1.k = 40000``."""
    if isinstance(value, str):
        set_field(record, name, value, pos)
        return
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"{type(record).__name__} field '{name}': not a number: {value!r}",
                         pos.file, pos.line) from None
    set_field(record, name, array.reshape(1, 1) if array.ndim == 0 else array.reshape(-1, 1), pos)
