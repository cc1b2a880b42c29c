"""Numeric values of the in-file evaluator: MATLAB matrices as 2-D float numpy arrays, with
MATLAB's operator rules and the functions the in-files may call."""

from __future__ import annotations

import math

import numpy as np

from mbds.errors import ModelError


def is_whole(x) -> bool:
    """True for a finite number with no fraction (an index or a size)."""
    return math.isfinite(x) and x == int(x)


def scalar(x: float) -> np.ndarray:
    """A 1x1 matrix."""
    return np.array([[float(x)]])


def shape_text(v) -> str:
    """How an error message names a value's kind and size."""
    if isinstance(v, str):
        return f"text '{v}'"
    if isinstance(v, np.ndarray):
        return "a number" if v.shape == (1, 1) else f"a {v.shape[0]}x{v.shape[1]} matrix"
    if isinstance(v, list):
        return f"an array of {len(v)} structs"
    return f"a {type(v).__name__} struct"


def _numeric(v, what: str, where) -> np.ndarray:
    if isinstance(v, np.ndarray):
        return v
    if isinstance(v, str) and len(v) == 1:
        return scalar(ord(v))
    raise ModelError(f"{what} needs numbers, not {shape_text(v)}", *where)


def _broadcast_ok(a: np.ndarray, b: np.ndarray) -> bool:
    return all(x == y or x == 1 or y == 1 for x, y in zip(a.shape, b.shape))


def binary(op: str, a, b, where) -> np.ndarray:
    """``a op b`` with MATLAB's meaning (``*`` a matrix product unless a side is 1x1)."""
    if op in ("==", "~=") and isinstance(a, str) and isinstance(b, str):
        same = a == b
        return scalar(same if op == "==" else not same)
    a = _numeric(a, f"'{op}'", where)
    b = _numeric(b, f"'{op}'", where)
    if op == "*" and a.size != 1 and b.size != 1:
        if a.shape[1] != b.shape[0]:
            raise ModelError(f"'*' of {shape_text(a)} and {shape_text(b)}: inner sizes differ", *where)
        return a @ b
    if op == "/" and b.size != 1:
        raise ModelError(f"'/' by {shape_text(b)} is outside the subset (divide by a number)", *where)
    if op == "^" and (a.size != 1 or b.size != 1):
        raise ModelError("'^' of matrices is outside the subset; use '.^' for element powers", *where)
    if not _broadcast_ok(a, b):
        raise ModelError(f"'{op}' of {shape_text(a)} and {shape_text(b)}: sizes do not match", *where)
    with np.errstate(all="ignore"):
        if op in ("+", "-"):
            return a + b if op == "+" else a - b
        if op in ("*", ".*"):
            return a * b
        if op in ("/", "./"):
            return a / b
        if op in ("^", ".^"):
            return np.power(a, b)  # a negative base to a fractional power gives NaN
        compare = {"==": np.equal, "~=": np.not_equal, "<": np.less, "<=": np.less_equal,
                   ">": np.greater, ">=": np.greater_equal, "&": np.logical_and, "|": np.logical_or}
        return compare[op](a, b).astype(float)


def truth(v, where) -> bool:
    """MATLAB's truth of a condition: all elements nonzero (and not empty)."""
    v = _numeric(v, "a condition", where)
    return bool(v.size) and bool(np.all(v != 0))


def _minmax(reduce_fn, pair_fn):
    def apply(*args):
        if len(args) == 1:
            a = args[0]
            if a.size == 0:
                return np.zeros((0, 0))
            return scalar(reduce_fn(a)) if 1 in a.shape else reduce_fn(a, axis=0, keepdims=True)
        return pair_fn(args[0], args[1])
    return apply


def _deg2rad(a):
    return a * (math.pi / 180.0)


def _rad2deg(a):
    return a * (180.0 / math.pi)


def _norm(a):
    return scalar(np.linalg.norm(a, 2))


def _filled(value: float):
    def make(*sizes):
        shape = tuple(int(s.item()) for s in sizes)
        return np.full({0: (1, 1), 1: shape * 2}.get(len(shape), shape), value)
    return make


def _matlab_round(a):
    return np.sign(a) * np.floor(np.abs(a) + 0.5)


#: name -> (least, most arguments, implementation on 2-D arrays)
FUNCTIONS = {
    "sin": (1, 1, np.sin), "cos": (1, 1, np.cos), "tan": (1, 1, np.tan),
    "asin": (1, 1, np.arcsin), "acos": (1, 1, np.arccos), "atan": (1, 1, np.arctan),
    "atan2": (2, 2, np.arctan2), "sinh": (1, 1, np.sinh), "cosh": (1, 1, np.cosh),
    "tanh": (1, 1, np.tanh), "sind": (1, 1, lambda a: np.sin(_deg2rad(a))),
    "cosd": (1, 1, lambda a: np.cos(_deg2rad(a))), "tand": (1, 1, lambda a: np.tan(_deg2rad(a))),
    "sqrt": (1, 1, np.sqrt), "abs": (1, 1, np.abs), "exp": (1, 1, np.exp),
    "log": (1, 1, np.log), "log10": (1, 1, np.log10), "sign": (1, 1, np.sign),
    "floor": (1, 1, np.floor), "ceil": (1, 1, np.ceil), "round": (1, 1, _matlab_round),
    "fix": (1, 1, np.trunc), "mod": (2, 2, lambda a, b: a - np.floor(a / b) * b),
    "rem": (2, 2, lambda a, b: a - np.trunc(a / b) * b), "hypot": (2, 2, np.hypot),
    "min": (1, 2, _minmax(np.min, np.minimum)), "max": (1, 2, _minmax(np.max, np.maximum)),
    "norm": (1, 1, _norm), "deg2rad": (1, 1, _deg2rad), "rad2deg": (1, 1, _rad2deg),
    "zeros": (0, 2, _filled(0.0)), "ones": (0, 2, _filled(1.0)),
}

#: names with a fixed value
CONSTANTS = {"pi": math.pi, "Inf": math.inf, "inf": math.inf, "NaN": math.nan, "nan": math.nan,
             "eps": float(np.finfo(float).eps), "true": 1.0, "false": 0.0}


def call(name: str, args: list, where) -> np.ndarray:
    """Call function ``name`` of FUNCTIONS on evaluated arguments."""
    least, most, fn = FUNCTIONS[name]
    if not least <= len(args) <= most:
        count = f"{least}" if least == most else f"{least} to {most}"
        raise ModelError(f"{name} takes {count} argument(s), got {len(args)}", *where)
    nums = [_numeric(a, name, where) for a in args]
    if name in ("zeros", "ones") and any(a.size != 1 or a.item() < 0 or not is_whole(a.item()) for a in nums):
        raise ModelError(f"{name} needs whole-number sizes", *where)
    if len(nums) == 2 and not _broadcast_ok(nums[0], nums[1]):
        raise ModelError(f"{name} of {shape_text(nums[0])} and {shape_text(nums[1])}: sizes do not match", *where)
    with np.errstate(all="ignore"):
        out = fn(*nums)
    return np.asarray(out, dtype=float).reshape(np.shape(out) if np.ndim(out) == 2 else (1, 1))
