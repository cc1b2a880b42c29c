"""Compiling DAP_BC's user_force.m into Python source of a numba-compilable function.

The generated function has this fixed signature (all arrays float64, indices 0-based)::

    def user_force(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):

- ``t``: time (s); ``r``, ``r_d``: (nB, 2) body mass-centre positions (m) and velocities (m/s);
  ``p``, ``p_d``: (nB,) angles (rad) and rates (rad/s); ``A``: (nB, 2, 2) rotation matrices;
- ``rP``, ``rP_d``: (nP, 2) world positions and velocities of the points; ``sP``: (nP, 2) the
  rotated body-fixed vectors A s'P;
- ``fields``: (nF, FORCE_FIELD_COUNT) every Force's numeric fields, columns by FORCE_FIELDS
  (fill it with :func:`force_field_table`);
- ``state``: (n_state,) the Contact states, CONTACT_STATE_SLOTS per contact index, kept by the
  caller between evaluations (zeros at the start of a run);
- ``f``: (nB, 2) forces (N) and ``n``: (nB,) moments (N m) about the mass centres; the function
  changes them as the MATLAB code changes ``Bodies(i).f`` and ``Bodies(i).n``
  (``Bodies(i).f = Bodies(i).f + ...`` adds into them).

The caller runs it at the position of the ``user`` element in Forces (the elements before it
already added into f and n), at every evaluation of the equations of motion.  MATLAB's 1-based
``Bodies(2)``, ``Points(3)``, ``Forces(2)`` become rows 1, 2, 1.  The subset:
docs/dapbc-files.md.  A user force may instead be a Python function with the same signature
(``user_force.py`` in the folder, or :func:`from_function`).
"""

from __future__ import annotations

import ast as pyast
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mbds.errors import ModelError
from mbds.io.dapbc import parser as ast
from mbds.io.dapbc.fields import did_you_mean
from mbds.io.dapbc.reader import read_source
from mbds.io.dapbc.records import DapbcModel, Force
from mbds.io.dapbc.values import is_whole
from mbds.kernel.dapbc_library import CONTACT_STATE_SLOTS

SIGNATURE = ("t", "r", "p", "r_d", "p_d", "A", "rP", "rP_d", "sP", "fields", "state", "f", "n")

#: Force field -> its columns in ``fields`` (two for a 2-vector)
FORCE_FIELDS: dict[str, tuple[int, ...]] = {
    "k": (0,), "L0": (1,), "theta0": (2,), "dc": (3,), "f_a": (4,), "T_a": (5,), "gravity": (6,),
    "wgt": (7, 8), "flocal": (9, 10), "f": (11, 12), "T": (13,),
}
FORCE_FIELD_COUNT = 14

IMPORTS = ("import numpy as np\n"
           "from mbds.kernel.dapbc_library import (contact_flores, contact_ground,\n"
           "    contact_lankarani_nikravesh, friction_anderson, friction_brown_mcphee)\n")


def force_field_table(forces: list[Force]) -> np.ndarray:
    """The ``fields`` argument: (nF, FORCE_FIELD_COUNT) of the forces' numeric fields."""
    table = np.zeros((len(forces), FORCE_FIELD_COUNT))
    for row, force in enumerate(forces):
        for name, columns in FORCE_FIELDS.items():
            table[row, list(columns)] = getattr(force, name)
    return table


@dataclass(frozen=True)
class UserForceCode:
    """A model's user force: ``function_source`` (defines ``user_force``; needs ``imports``),
    the number of state slots it uses, and the file it came from."""

    function_source: str
    imports: str
    n_state: int
    file: Path | None

    @property
    def module_source(self) -> str:
        """A whole module whose ``user_force`` is numba-compiled."""
        return (self.imports + "from mbds.io.dapbc.user_force_hook import jitted as _jitted\n\n"
                + self.function_source + "\n\nuser_force = _jitted(user_force)\n")

    def load(self):
        """Run :attr:`module_source` and return its compiled ``user_force``."""
        namespace: dict = {"__name__": "mbds_dapbc_user_force"}
        exec(compile(self.module_source, str(self.file or "<user_force>"), "exec"), namespace)
        return namespace["user_force"]


def user_force_code(model: DapbcModel) -> UserForceCode | None:
    """The model's user force: user_force.py when the folder has one, else user_force.m
    compiled; None when it has neither."""
    if model.user_force_py is not None:
        return python_user_force(model.user_force_py)
    if model.user_force_file is not None:
        return compile_user_force(read_source(model.user_force_file), model, model.user_force_file)
    return None


def python_user_force(path: Path) -> UserForceCode:
    """A user_force.py: it must define ``user_force`` with the fixed signature; a module-level
    ``N_STATE = <int>`` gives its state slots (0 when absent)."""
    text = read_source(path)
    try:
        tree = pyast.parse(text, str(path))
    except SyntaxError as exc:
        raise ModelError(f"Python syntax error: {exc.msg}", path, exc.lineno) from None
    n_state = 0
    function = None
    for node in tree.body:
        if isinstance(node, pyast.FunctionDef) and node.name == "user_force":
            function = node
        elif isinstance(node, pyast.Assign) and any(isinstance(t, pyast.Name) and t.id == "N_STATE"
                                                    for t in node.targets):
            if not (isinstance(node.value, pyast.Constant) and isinstance(node.value.value, int)
                    and node.value.value >= 0):
                raise ModelError("N_STATE must be a whole number >= 0", path, node.lineno)
            n_state = node.value.value
    if function is None:
        raise ModelError("user_force.py must define 'def user_force(" + ", ".join(SIGNATURE) + "):'", path)
    params = tuple(a.arg for a in function.args.args)
    if params != SIGNATURE:
        raise ModelError(f"user_force must take ({', '.join(SIGNATURE)}), not ({', '.join(params)})",
                         path, function.lineno)
    return UserForceCode(text, "", n_state, path)


def from_function(function, n_state: int = 0) -> UserForceCode:
    """A user force given as a module-level Python function (of an importable module) with the
    fixed signature."""
    code = getattr(function, "__code__", None) or getattr(getattr(function, "py_func", None), "__code__", None)
    params = code.co_varnames[:code.co_argcount] if code is not None else ()
    if tuple(params) != SIGNATURE:
        raise ModelError(f"a user force function must take ({', '.join(SIGNATURE)})")
    source = f"from {function.__module__} import {function.__name__} as user_force\n"
    return UserForceCode(source, "", n_state, None)


# ---- compiling the MATLAB subset -------------------------------------------------------------
@dataclass(frozen=True)
class Value:
    """A compiled expression: its shape ('scalar', 'col', 'row', 'mat') and the Python text of
    each component (row-major for 'mat')."""

    shape: str
    parts: tuple[str, ...]


_SIZES = {"scalar": 1, "col": 2, "row": 2, "mat": 4}
_DESCRIBE = {"scalar": "a number", "col": "a 2x1 vector", "row": "a 1x2 vector", "mat": "a 2x2 matrix"}
_ELEMENTWISE = {"abs": "abs", "sqrt": "np.sqrt", "sin": "np.sin", "cos": "np.cos", "tan": "np.tan",
                "exp": "np.exp", "log": "np.log", "sign": "np.sign", "tanh": "np.tanh",
                "asin": "np.arcsin", "acos": "np.arccos", "atan": "np.arctan", "floor": "np.floor",
                "ceil": "np.ceil", "sinh": "np.sinh", "cosh": "np.cosh"}
_PAIRWISE = {"min": "min", "max": "max", "atan2": "np.arctan2", "hypot": "np.hypot", "power": "np.power"}
_BODY_READS = {"r": "col", "r_d": "col", "p": "scalar", "p_d": "scalar", "A": "mat", "f": "col", "n": "scalar"}
_POINT_READS = {"rP": "col", "rP_d": "col", "sP": "col", "sP_r": "col"}


def _scalar(text: str) -> Value:
    return Value("scalar", (text,))


def _num(x: float) -> str:
    return repr(float(x)) if math.isfinite(x) else f"np.{'inf' if x > 0 else 'nan'}"


class Compiler:
    """Translates one parsed user_force.m into the body of ``user_force``."""

    def __init__(self, program: ast.Program, model: DapbcModel):
        self.file = program.file
        self.program = program
        self.model = model
        self.shapes: dict[str, tuple[str, int]] = {}  # local -> (shape, line of first assignment)
        self.in_branch: set[str] = set()  # locals first set inside an if block (set to 0 on entry)
        self.lines: list[str] = []
        self.n_contacts = 0
        self.globals: set[str] = set()

    def error(self, message: str, line: int) -> ModelError:
        return ModelError(message, self.file, line)

    def compile(self) -> str:
        header = self.program.header
        if header is not None and (header.params or header.outputs):
            raise self.error("user_force takes no arguments and returns nothing (write 'function user_force')",
                             header.line)
        self.block(self.program.body, 1)
        init = [f"    {name} = 0.0" for local in sorted(self.in_branch)
                for name in self.names(local, self.shapes[local][0])]
        body = init + self.lines or ["    pass"]
        return f"def user_force({', '.join(SIGNATURE)}):\n" + "\n".join(body) + "\n"

    @staticmethod
    def names(local: str, shape: str) -> list[str]:
        """The Python variables holding MATLAB local ``local``."""
        if shape == "scalar":
            return [f"v_{local}"]
        return [f"v_{local}_{k}" for k in range(_SIZES[shape])]

    def emit(self, depth: int, text: str) -> None:
        self.lines.append("    " * depth + text)

    # -- statements --
    def block(self, statements, depth: int) -> None:
        start = len(self.lines)
        for s in statements:
            self.statement(s, depth)
        if len(self.lines) == start:
            self.emit(depth, "pass")

    def statement(self, s, depth: int) -> None:
        if isinstance(s, ast.Global):
            self.globals.update(s.names)
        elif isinstance(s, ast.If):
            for k, (condition, body) in enumerate(s.clauses):
                self.emit(depth, f"{'if' if k == 0 else 'elif'} {self.condition(condition, s.line)}:")
                self.block(body, depth + 1)
            if s.orelse:
                self.emit(depth, "else:")
                self.block(s.orelse, depth + 1)
        elif isinstance(s, ast.ExprStmt):
            self.call_statement(s, depth)
        else:
            self.assign(s, depth)

    def call_statement(self, s, depth: int) -> None:
        e = s.expr
        if isinstance(e, ast.Name) and e.id == "include_global":
            return
        if isinstance(e, ast.Apply) and isinstance(e.base, ast.Name) and e.base.id == "Contact":
            self.emit(depth, self.contact(e))
            return
        raise self.error("a statement without effect: only assignments, if blocks and Contact(...) "
                         "calls do something in user_force", s.line)

    def contact(self, e: ast.Apply) -> str:
        if len(e.args) != 6:
            raise self.error(f"Contact takes 6 arguments (Ci, Pi, Bi, k, e, Mi), got {len(e.args)}", e.line)
        ci = self.constant_index(e.args[0], "contact index Ci", None, e.line)
        pi = self.constant_index(e.args[1], "point index Pi", len(self.model.points), e.line)
        bi = self.constant_index(e.args[2], "body index Bi", self.model.nB, e.line)
        on = self.model.points[pi - 1].Bindex
        if on != bi:
            raise self.error(f"Contact: point {pi} is on body {on}, not on body {bi}", e.line)
        law = self.constant_index(e.args[5], "model index Mi", 2, e.line)
        k, restitution = (self.scalar_arg(a, "Contact") for a in e.args[3:5])
        self.n_contacts = max(self.n_contacts, ci)
        return (f"contact_ground(state, {(ci - 1) * CONTACT_STATE_SLOTS}, {pi - 1}, {bi - 1}, {k}, "
                f"{restitution}, {law}, rP, rP_d, sP, f, n)")

    def constant_index(self, e, what: str, count: int | None, line: int) -> int:
        value = self.constant(e)
        if value is None or not is_whole(value) or value < 1:
            raise self.error(f"{what} must be a constant whole number >= 1", line)
        if count is not None and value > count:
            raise self.error(f"{what} = {int(value)} is out of range (1..{count})", line)
        return int(value)

    def constant(self, e) -> float | None:
        """The value of a constant numeric expression, or None."""
        if isinstance(e, ast.Num):
            return e.value
        if isinstance(e, ast.Unary) and e.op in "+-":
            inner = self.constant(e.operand)
            return None if inner is None else (-inner if e.op == "-" else inner)
        if isinstance(e, ast.Binary) and e.op in ("+", "-", "*", "/"):
            a, b = self.constant(e.left), self.constant(e.right)
            if a is None or b is None or (e.op == "/" and b == 0):
                return None
            return {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b else 0.0}[e.op]
        return None

    def assign(self, s: ast.Assign, depth: int) -> None:
        value = self.value(s.value)
        target = s.target
        if isinstance(target, ast.Name):
            self.check_name(target.id, s.line)
            if target.id not in self.shapes and depth > 1:
                self.in_branch.add(target.id)
            shape, first = self.shapes.setdefault(target.id, (value.shape, s.line))
            if shape != value.shape:
                raise self.error(f"'{target.id}' is {_DESCRIBE[shape]} (line {first}); it cannot become "
                                 f"{_DESCRIBE[value.shape]}", s.line)
            self.emit(depth, f"{', '.join(self.names(target.id, shape))} = {', '.join(value.parts)}")
            return
        if isinstance(target, ast.Apply) and isinstance(target.base, ast.Name):  # fsd(2) = ...
            name = target.base.id
            if name not in self.shapes or self.shapes[name][0] == "scalar":
                raise self.error(f"'{name}' is not a vector set earlier in user_force", s.line)
            k = self.component(target.args, self.shapes[name][0], s.line)
            self.emit(depth, f"{self.names(name, self.shapes[name][0])[k]} = {self.expect_scalar(value, s.line)}")
            return
        component = None
        if isinstance(target, ast.Apply):  # Bodies(i).f(1) = ...
            component, target = target.args, target.base
        if not isinstance(target, ast.FieldRef):
            raise self.error("user_force may set only local variables, Bodies(i).f and Bodies(i).n", s.line)
        array, index = self.element(target.base, s.line)
        if array != "Bodies" or target.name not in ("f", "n"):
            raise self.error(f"user_force may change only Bodies(i).f and Bodies(i).n, not "
                             f"{array}({index + 1}).{target.name}", s.line)
        if target.name == "n":
            if component is not None:
                raise self.error("Bodies(i).n is a number; it cannot be indexed", s.line)
            self.emit(depth, f"n[{index}] = {self.expect_scalar(value, s.line)}")
        elif component is not None:
            k = self.component(component, "col", s.line)
            self.emit(depth, f"f[{index}, {k}] = {self.expect_scalar(value, s.line)}")
        else:
            if value.shape not in ("col", "scalar"):
                raise self.error(f"Bodies(i).f must be a 2x1 vector, not {_DESCRIBE[value.shape]}", s.line)
            parts = value.parts * 2 if value.shape == "scalar" else value.parts
            self.emit(depth, f"f[{index}, 0], f[{index}, 1] = {parts[0]}, {parts[1]}")

    def check_name(self, name: str, line: int) -> None:
        if name in ("Bodies", "Points", "Forces", "Uvectors", "Joints", "Functs"):
            raise self.error(f"'{name}' cannot be replaced in user_force", line)
        if name in self.globals:
            raise self.error(f"global '{name}': global variables other than the model's arrays are "
                             "outside the subset (Contact keeps its own state)", line)

    def component(self, args: tuple, shape: str, line: int) -> int:
        if len(args) != 1:
            raise self.error("expected one index", line)
        size = _SIZES[shape]
        k = self.constant(args[0])
        if k is None or not is_whole(k) or not 1 <= k <= size:
            raise self.error(f"an index must be a constant whole number 1..{size}", line)
        return int(k) - 1

    def element(self, e, line: int) -> tuple[str, int]:
        """``Bodies(i)``, ``Points(i)`` or ``Forces(i)``: the array name and the 0-based row."""
        if not (isinstance(e, ast.Apply) and isinstance(e.base, ast.Name)
                and e.base.id in ("Bodies", "Points", "Forces", "Uvectors", "Joints", "Functs")):
            raise self.error("expected Bodies(i), Points(i) or Forces(i) before the field", line)
        array = e.base.id
        counts = {"Bodies": self.model.nB, "Points": len(self.model.points), "Forces": len(self.model.forces)}
        if array not in counts:
            raise self.error(f"{array} is not available in user_force (Bodies, Points, Forces are)", line)
        if len(e.args) != 1:
            raise self.error(f"{array}(i) takes one index", line)
        return array, self.constant_index(e.args[0], f"the index of {array}", counts[array], line) - 1

    # -- expressions --
    def condition(self, e, line: int) -> str:
        value = self.value(e)
        return " and ".join(f"{part} != 0.0" for part in value.parts)

    def expect_scalar(self, value: Value, line: int) -> str:
        if value.shape != "scalar":
            raise self.error(f"expected a number, got {_DESCRIBE[value.shape]}", line)
        return value.parts[0]

    def scalar_arg(self, e, function: str) -> str:
        value = self.value(e)
        if value.shape != "scalar":
            raise self.error(f"{function} takes numbers, not {_DESCRIBE[value.shape]}", e.line)
        return value.parts[0]

    def value(self, e) -> Value:
        if isinstance(e, ast.Num):
            return _scalar(_num(e.value))
        if isinstance(e, ast.Name):
            return self.name(e)
        if isinstance(e, ast.Text):
            raise self.error("text is outside the user_force subset", e.line)
        if isinstance(e, ast.FieldRef):
            return self.field(e)
        if isinstance(e, ast.Apply):
            return self.apply(e)
        if isinstance(e, ast.Unary):
            operand = self.value(e.operand)
            if e.op == "-":
                return Value(operand.shape, tuple(f"(-{p})" for p in operand.parts))
            if e.op == "+":
                return operand
            return Value(operand.shape, tuple(f"(1.0 if {p} == 0.0 else 0.0)" for p in operand.parts))
        if isinstance(e, ast.Transpose):
            v = self.value(e.operand)
            flipped = {"col": "row", "row": "col"}.get(v.shape, v.shape)
            parts = (v.parts[0], v.parts[2], v.parts[1], v.parts[3]) if v.shape == "mat" else v.parts
            return Value(flipped, parts)
        if isinstance(e, ast.Matrix):
            return self.matrix(e)
        return self.binary(e)

    def name(self, e: ast.Name) -> Value:
        if e.id in self.shapes:
            shape = self.shapes[e.id][0]
            return Value(shape, tuple(self.names(e.id, shape)))
        if e.id == "pi":
            return _scalar(repr(math.pi))
        if e.id in ("Inf", "inf", "eps"):
            return _scalar("np.inf" if e.id != "eps" else repr(float(np.finfo(float).eps)))
        if e.id == "t":
            return _scalar("t")
        if e.id in self.globals:
            raise self.error(f"global '{e.id}': global variables other than the model's arrays are outside "
                             "the subset (Contact keeps its own state)", e.line)
        raise self.error(f"'{e.id}' is used before it is set", e.line)

    def field(self, e: ast.FieldRef) -> Value:
        array, i = self.element(e.base, e.line)
        reads = {"Bodies": _BODY_READS, "Points": _POINT_READS, "Forces": FORCE_FIELDS}[array]
        if e.name not in reads:
            raise self.error(f"{array}(i).{e.name} is not available in user_force"
                             f"{did_you_mean(e.name, reads, 'readable')}", e.line)
        if array == "Forces":
            columns = FORCE_FIELDS[e.name]
            return Value("scalar" if len(columns) == 1 else "col", tuple(f"fields[{i}, {c}]" for c in columns))
        if array == "Points":
            if e.name == "sP_r":
                return Value("col", (f"(-sP[{i}, 1])", f"sP[{i}, 0]"))
            return Value("col", (f"{e.name}[{i}, 0]", f"{e.name}[{i}, 1]"))
        shape = _BODY_READS[e.name]
        if shape == "scalar":
            return _scalar(f"{e.name}[{i}]")
        if shape == "mat":
            return Value("mat", tuple(f"A[{i}, {a}, {b}]" for a in range(2) for b in range(2)))
        return Value("col", (f"{e.name}[{i}, 0]", f"{e.name}[{i}, 1]"))

    def apply(self, e: ast.Apply) -> Value:
        if isinstance(e.base, ast.FieldRef) or (isinstance(e.base, ast.Name) and e.base.id in self.shapes):
            v = self.value(e.base)
            if v.shape == "scalar":
                raise self.error("a number cannot be indexed", e.line)
            if v.shape == "mat":
                if len(e.args) != 2:
                    raise self.error("a 2x2 matrix takes two indices (i, j)", e.line)
                a, b = (self.component((x,), "col", e.line) for x in e.args)
                return _scalar(v.parts[2 * a + b])
            return _scalar(v.parts[self.component(e.args, v.shape, e.line)])
        if not isinstance(e.base, ast.Name):
            raise self.error("this call is outside the user_force subset", e.line)
        name = e.base.id
        args = [self.value(a) for a in e.args]
        if name in _ELEMENTWISE and len(args) == 1:
            return Value(args[0].shape, tuple(f"{_ELEMENTWISE[name]}({p})" for p in args[0].parts))
        if name in ("min", "max") and len(args) == 1 and args[0].shape in ("col", "row"):
            return _scalar(f"{name}({args[0].parts[0]}, {args[0].parts[1]})")
        if name in _PAIRWISE and len(args) == 2:
            a, b = self.broadcast(args[0], args[1], name, e.line)
            return Value(a.shape, tuple(f"{_PAIRWISE[name]}({x}, {y})" for x, y in zip(a.parts, b.parts)))
        if name == "s_rot":
            if len(args) != 1 or args[0].shape != "col":
                raise self.error("s_rot takes one 2x1 vector", e.line)
            return Value("col", (f"(-{args[0].parts[1]})", args[0].parts[0]))
        if name in ("Friction_A", "Friction_B", "Contact_LN", "Contact_FM"):
            return self.library(name, e, args)
        if name == "Contact":
            raise self.error("Contact(...) is a statement of its own; it returns nothing", e.line)
        if name in _ELEMENTWISE or name in _PAIRWISE:
            raise self.error(f"{name} got {len(args)} argument(s)", e.line)
        if name in ("Bodies", "Points", "Forces"):
            raise self.error(f"{name}(i) needs a field, e.g. {name}(i).{next(iter(_BODY_READS))}", e.line)
        raise self.error(f"'{name}' is not a function of the user_force subset", e.line)

    def library(self, name: str, e: ast.Apply, args: list[Value]) -> Value:
        counts = {"Friction_A": (6, 7), "Friction_B": (7, 7), "Contact_LN": (5, 5), "Contact_FM": (5, 5)}
        least, most = counts[name]
        if not least <= len(args) <= most:
            raise self.error(f"{name} takes {least if least == most else f'{least} or {most}'} arguments, "
                             f"got {len(args)}", e.line)
        parts = [self.expect_scalar(a, e.line) for a in args]
        target = {"Friction_A": "friction_anderson", "Friction_B": "friction_brown_mcphee",
                  "Contact_LN": "contact_lankarani_nikravesh", "Contact_FM": "contact_flores"}[name]
        call = f"{target}({', '.join(parts[:6] if name == 'Friction_A' else parts)})"
        if name == "Friction_A" and len(parts) == 7:  # the variant with the normal force fN
            call = f"({parts[6]} * {call})"
        return _scalar(call)

    def broadcast(self, a: Value, b: Value, op: str, line: int) -> tuple[Value, Value]:
        if a.shape == b.shape:
            return a, b
        if a.shape == "scalar":
            return Value(b.shape, a.parts * len(b.parts)), b
        if b.shape == "scalar":
            return a, Value(a.shape, b.parts * len(a.parts))
        raise self.error(f"'{op}' of {_DESCRIBE[a.shape]} and {_DESCRIBE[b.shape]}: sizes do not match", line)

    def binary(self, e: ast.Binary) -> Value:
        a, b = self.value(e.left), self.value(e.right)
        op = e.op
        if op in ("&&", "||"):
            x, y = self.expect_scalar(a, e.line), self.expect_scalar(b, e.line)
            word = "and" if op == "&&" else "or"
            return _scalar(f"(1.0 if {x} != 0.0 {word} {y} != 0.0 else 0.0)")
        if op == "*" and a.shape != "scalar" and b.shape != "scalar":
            return self.product(a, b, e.line)
        if op == "/" and b.shape != "scalar":
            raise self.error("'/' by a vector or matrix is outside the subset (divide by a number)", e.line)
        if op == "^" and (a.shape != "scalar" or b.shape != "scalar"):
            raise self.error("'^' of vectors is outside the subset; use '.^'", e.line)
        a, b = self.broadcast(a, b, op, e.line)
        template = {"+": "({} + {})", "-": "({} - {})", "*": "({} * {})", ".*": "({} * {})",
                    "/": "({} / {})", "./": "({} / {})", "^": "np.power({}, {})", ".^": "np.power({}, {})",
                    "==": "(1.0 if {} == {} else 0.0)", "~=": "(1.0 if {} != {} else 0.0)",
                    "<": "(1.0 if {} < {} else 0.0)", "<=": "(1.0 if {} <= {} else 0.0)",
                    ">": "(1.0 if {} > {} else 0.0)", ">=": "(1.0 if {} >= {} else 0.0)",
                    "&": "(1.0 if {} != 0.0 and {} != 0.0 else 0.0)",
                    "|": "(1.0 if {} != 0.0 or {} != 0.0 else 0.0)"}[op]
        return Value(a.shape, tuple(template.format(x, y) for x, y in zip(a.parts, b.parts)))

    def product(self, a: Value, b: Value, line: int) -> Value:
        """Matrix product of 2-vectors and 2x2 matrices."""
        rows = {"row": [a.parts], "mat": [a.parts[:2], a.parts[2:]]}.get(a.shape)
        cols = {"col": [b.parts], "mat": [b.parts[0::2], b.parts[1::2]]}.get(b.shape)
        if a.shape == "col" and b.shape == "row":  # outer product
            return Value("mat", tuple(f"({x} * {y})" for x in a.parts for y in b.parts))
        if rows is None or cols is None:
            raise self.error(f"'*' of {_DESCRIBE[a.shape]} and {_DESCRIBE[b.shape]}: inner sizes differ", line)
        parts = tuple(f"({r[0]} * {c[0]} + {r[1]} * {c[1]})" for r in rows for c in cols)
        shape = {(1, 1): "scalar", (2, 1): "col", (1, 2): "row", (2, 2): "mat"}[(len(rows), len(cols))]
        return Value(shape, parts)

    def matrix(self, e: ast.Matrix) -> Value:
        rows = [[self.value(x) for x in row] for row in e.rows]
        if all(v.shape == "scalar" for row in rows for v in row):
            sizes = [len(row) for row in rows]
            flat = tuple(v.parts[0] for row in rows for v in row)
            if sizes == [1, 1]:
                return Value("col", flat)
            if sizes == [2]:
                return Value("row", flat)
            if sizes == [2, 2]:
                return Value("mat", flat)
            if sizes == [1]:
                return Value("scalar", flat)
        if len(rows) == 1 and len(rows[0]) == 1:
            return rows[0][0]
        if len(rows) == 1 and all(v.shape == "col" for v in rows[0]) and len(rows[0]) == 2:
            c1, c2 = rows[0]
            return Value("mat", (c1.parts[0], c2.parts[0], c1.parts[1], c2.parts[1]))
        if len(rows) == 2 and all(len(r) == 1 and r[0].shape == "row" for r in rows):
            return Value("mat", rows[0][0].parts + rows[1][0].parts)
        raise self.error("only 2x1, 1x2 and 2x2 matrices are in the user_force subset", e.line)


def compile_user_force(source: str, model: DapbcModel, file: str | Path = "user_force.m") -> UserForceCode:
    """Compile the text of a user_force.m for ``model`` (used to check its indices)."""
    program = ast.parse(source, str(file))
    compiler = Compiler(program, model)
    text = compiler.compile()
    return UserForceCode(text, IMPORTS, compiler.n_contacts * CONTACT_STATE_SLOTS, Path(file))
