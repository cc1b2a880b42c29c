"""Running one DAP_BC in-file: the statements of the subset evaluated on numbers, text and
the element records of :mod:`mbds.io.dapbc.records`."""

from __future__ import annotations

import numpy as np

from mbds.errors import ModelError
from mbds.io.dapbc import parser as ast
from mbds.io.dapbc.fields import get_field, set_field
from mbds.io.dapbc.records import CONSTRUCTORS, Element, SourcePos
from mbds.io.dapbc.values import CONSTANTS, FUNCTIONS, binary, call, is_whole, scalar, shape_text, truth

#: The names that DAP_BC's include_global makes shared between the in-files.
GLOBAL_NAMES = ("Bodies", "Points", "Uvectors", "Forces", "Joints", "Functs", "Points_anim",
                "xmin", "xmax", "ymin", "ymax")


def _copy(value):
    if isinstance(value, Element):
        return value.copy()
    if isinstance(value, list):
        return [e.copy() for e in value]
    if isinstance(value, np.ndarray):
        return value.copy()
    return value


class InFile:
    """Evaluates the statements of one parsed in-file.  ``shared`` holds the global names
    (shared with the other in-files); ``set_at`` records where each shared name was set."""

    def __init__(self, program: ast.Program, shared: dict, set_at: dict[str, SourcePos]):
        self.program = program
        self.file = program.file
        self.shared = shared
        self.set_at = set_at
        self.local: dict = {}
        self.global_names: set[str] = set()
        self.included = False

    def run(self) -> None:
        """Run the file's statements in order."""
        header = self.program.header
        if header is not None and (header.params or header.outputs):
            raise ModelError("in-files take no arguments and return nothing "
                             f"(write 'function {header.name}')", self.file, header.line)
        for statement in self.program.body:
            self.statement(statement)
        if not self.included:
            line = header.line if header is not None else 1
            raise ModelError("include_global is missing; the manual requires it in every in-file "
                             "(without it the file's arrays do not reach the program)", self.file, line)

    def where(self, line: int) -> tuple[str, int]:
        return self.file, line

    # -- statements --
    def statement(self, s) -> None:
        if isinstance(s, ast.Assign):
            self.assign(s.target, self.value(s.value), s.line)
        elif isinstance(s, ast.ExprStmt):
            if isinstance(s.expr, ast.Name) and s.expr.id == "include_global":
                self.included = True
                self.global_names.update(GLOBAL_NAMES)
            else:
                self.value(s.expr)
        elif isinstance(s, ast.Global):
            self.global_names.update(s.names)
        elif isinstance(s, ast.If):
            for condition, body in s.clauses:
                if truth(self.value(condition), self.where(s.line)):
                    for inner in body:
                        self.statement(inner)
                    return
            for inner in s.orelse:
                self.statement(inner)

    def scope(self, name: str) -> dict:
        return self.shared if name in self.global_names else self.local

    def lookup(self, name: str, line: int):
        scope = self.scope(name)
        if name in scope:
            return scope[name]
        if name in GLOBAL_NAMES and name not in self.global_names and name in self.shared:
            raise ModelError(f"'{name}' is not visible here: include_global must come first", self.file, line)
        raise KeyError(name)

    def assign(self, target, value, line: int) -> None:
        pos = SourcePos(self.file, line)
        if isinstance(target, ast.Name):
            self.scope(target.id)[target.id] = _copy(value)
            if target.id in self.global_names:
                self.set_at[target.id] = pos
            return
        if isinstance(target, ast.FieldRef):
            record = self.record_for(target.base, line)
            set_field(record, target.name, value, pos)
            return
        # Apply: X.f(k) = v  (component of a vector field), X(i) = struct
        if isinstance(target.base, ast.FieldRef):
            record = self.record_for(target.base.base, line)
            set_field(record, target.base.name, value, pos, component=self.one_index(target.args, line))
            return
        container = self.lookup_for_write(target.base, line)
        index = self.one_index(target.args, line)
        if not isinstance(container, list):
            raise ModelError("indexed assignment is only for arrays of structs "
                             f"(not {shape_text(container)})", self.file, line)
        if not 1 <= index <= len(container):
            raise ModelError(f"index {index} is out of range: the array has {len(container)} elements",
                             self.file, line)
        if not isinstance(value, Element) or type(value) is not type(container[index - 1]):
            raise ModelError(f"an element of this array must be a {type(container[index - 1]).__name__} "
                             f"struct, not {shape_text(value)}", self.file, line)
        container[index - 1] = value.copy()

    def lookup_for_write(self, expr, line: int):
        if not isinstance(expr, ast.Name):
            raise ModelError("nested indexing on the left of '=' is outside the subset", self.file, line)
        try:
            return self.lookup(expr.id, line)
        except KeyError:
            raise ModelError(f"'{expr.id}' is not defined", self.file, line) from None

    def record_for(self, expr, line: int) -> Element:
        """The record that ``expr`` (``B1`` or ``Bodies(2)``) names, for a field assignment."""
        if isinstance(expr, ast.Name):
            try:
                record = self.lookup(expr.id, line)
            except KeyError:
                raise ModelError(f"'{expr.id}' is not defined; create it first, e.g. "
                                 f"'{expr.id} = Body_struct;'", self.file, line) from None
            if isinstance(record, list) and len(record) == 1:
                return record[0]
            if not isinstance(record, Element):
                raise ModelError(f"'{expr.id}' is {shape_text(record)}, not a struct", self.file, line)
            return record
        if isinstance(expr, ast.Apply):
            container = self.lookup_for_write(expr.base, line)
            if not isinstance(container, list):
                raise ModelError(f"'{expr.base.id}' is {shape_text(container)}, not an array of structs",
                                 self.file, line)
            index = self.one_index(expr.args, line)
            if not 1 <= index <= len(container):
                raise ModelError(f"{expr.base.id}({index}) does not exist: "
                                 f"{expr.base.id} has {len(container)} elements", self.file, line)
            return container[index - 1]
        raise ModelError("the left side of '=' is outside the subset", self.file, line)

    def one_index(self, args: tuple, line: int) -> int:
        if len(args) != 1:
            raise ModelError(f"expected one index, got {len(args)}", self.file, line)
        value = self.value(args[0])
        if not isinstance(value, np.ndarray) or value.shape != (1, 1) or not is_whole(value[0, 0]) \
                or value[0, 0] < 1:
            raise ModelError(f"an index must be a whole number >= 1, not {shape_text(value)}"
                             + (f" {value[0, 0]:g}" if isinstance(value, np.ndarray) and value.size == 1 else ""),
                             self.file, line)
        return int(value[0, 0])

    # -- expressions --
    def value(self, e):
        where = self.where(getattr(e, "line", 0))
        if isinstance(e, ast.Num):
            return scalar(e.value)
        if isinstance(e, ast.Text):
            return e.value
        if isinstance(e, ast.Name):
            return self.name_value(e)
        if isinstance(e, ast.FieldRef):
            base = self.value(e.base)
            if isinstance(base, list) and len(base) == 1:
                base = base[0]
            if not isinstance(base, Element):
                raise ModelError(f"'.{e.name}' of {shape_text(base)}: only structs have fields", *where)
            return get_field(base, e.name, where)
        if isinstance(e, ast.Apply):
            return self.apply(e)
        if isinstance(e, ast.Unary):
            operand = self.value(e.operand)
            if not isinstance(operand, np.ndarray):
                raise ModelError(f"'{e.op}' of {shape_text(operand)}", *where)
            return -operand if e.op == "-" else (operand if e.op == "+" else (operand == 0).astype(float))
        if isinstance(e, ast.Binary):
            if e.op in ("&&", "||"):
                left = truth(self.value(e.left), where)
                if (e.op == "&&" and not left) or (e.op == "||" and left):
                    return scalar(left)
                return scalar(truth(self.value(e.right), where))
            return binary(e.op, self.value(e.left), self.value(e.right), where)
        if isinstance(e, ast.Transpose):
            operand = self.value(e.operand)
            if not isinstance(operand, np.ndarray):
                raise ModelError(f"transpose of {shape_text(operand)}", *where)
            return operand.T.copy()
        if isinstance(e, ast.Matrix):
            return self.matrix(e)
        raise ModelError("expression outside the subset", *where)

    def name_value(self, e: ast.Name):
        try:
            return self.lookup(e.id, e.line)
        except KeyError:
            pass
        if e.id in CONSTANTS:
            return scalar(CONSTANTS[e.id])
        if e.id in CONSTRUCTORS:
            record = CONSTRUCTORS[e.id](source=SourcePos(self.file, e.line))
            return record
        if e.id in FUNCTIONS:
            return call(e.id, [], self.where(e.line))
        if e.id == "include_global":
            raise ModelError("include_global must be a statement of its own", self.file, e.line)
        raise ModelError(f"'{e.id}' is not defined", self.file, e.line)

    def apply(self, e: ast.Apply):
        where = self.where(e.line)
        if isinstance(e.base, ast.Name):
            try:
                container = self.lookup(e.base.id, e.line)
            except KeyError:
                container = None
                if e.base.id in FUNCTIONS:
                    return call(e.base.id, [self.value(a) for a in e.args], where)
                if e.base.id in CONSTRUCTORS:
                    raise ModelError(f"{e.base.id} takes no arguments", *where)
                raise ModelError(f"'{e.base.id}' is neither a variable nor a known function", *where) from None
        else:
            container = self.value(e.base)
        if isinstance(container, Element):
            container = [container]
        if isinstance(container, list):
            index = self.one_index(e.args, e.line)
            if not 1 <= index <= len(container):
                raise ModelError(f"index {index} is out of range: the array has {len(container)} elements", *where)
            return container[index - 1]
        if isinstance(container, str):
            raise ModelError("indexing into text is outside the subset", *where)
        indices = [self.value(a) for a in e.args]
        if not 1 <= len(indices) <= 2:
            raise ModelError(f"expected one or two indices, got {len(indices)}", *where)
        ints = []
        for index, size in zip(indices, (container.size,) if len(indices) == 1 else container.shape):
            if not isinstance(index, np.ndarray) or index.shape != (1, 1) or not is_whole(index[0, 0]):
                raise ModelError(f"an index must be a whole number, not {shape_text(index)}", *where)
            k = int(index[0, 0])
            if not 1 <= k <= size:
                raise ModelError(f"index {k} is out of range 1..{size}", *where)
            ints.append(k - 1)
        item = container.reshape(-1, order="F")[ints[0]] if len(ints) == 1 else container[ints[0], ints[1]]
        return scalar(item)

    def matrix(self, e: ast.Matrix):
        where = self.where(e.line)
        rows = [[self.value(x) for x in row] for row in e.rows]
        items = [v for row in rows for v in row]
        if any(isinstance(v, (Element, list)) for v in items):
            records: list[Element] = []
            for v in items:
                if isinstance(v, Element):
                    records.append(v.copy())
                elif isinstance(v, list):
                    records.extend(x.copy() for x in v)
                elif not (isinstance(v, np.ndarray) and v.size == 0):
                    raise ModelError(f"an array of structs cannot hold {shape_text(v)}", *where)
            kinds = {type(r).__name__ for r in records}
            if len(kinds) > 1:
                raise ModelError(f"an array of structs mixes {' and '.join(sorted(kinds))} structs", *where)
            return records
        if any(isinstance(v, str) for v in items):
            if len(rows) == 1 and all(isinstance(v, str) for v in items):
                return "".join(items)
            raise ModelError("text mixed with numbers in brackets is outside the subset", *where)
        blocks = []
        for row in rows:
            row = [v for v in row if v.size]
            if not row:
                continue
            if len({v.shape[0] for v in row}) > 1:
                raise ModelError("elements of a row in brackets have different numbers of rows", *where)
            blocks.append(np.hstack(row))
        if not blocks:
            return np.zeros((0, 0))
        if len({b.shape[1] for b in blocks}) > 1:
            raise ModelError("rows in brackets have different lengths", *where)
        return np.vstack(blocks)
