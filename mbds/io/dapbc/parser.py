"""Syntax tree of the MATLAB subset of DAP_BC in-files and user_force.m.

Statements: assignments to a name, a field or an indexed field (``B1.r = [1; 0.2];``,
``Bodies(1).f(1) = ...``), calls (``include_global``, ``Contact(1, 1, 1, k, e, 1)``),
``global`` declarations, ``if``/``elseif``/``else``/``end`` and the ``function`` header.
Expressions: numbers, quoted text, names, ``.field``, ``(args)``, ``[rows; ...]``, the
operators ``+ - * / ^ .* ./ .^ ' .'``, comparisons and ``&& || & | ~``, with MATLAB's
precedence.  Anything else raises ModelError at its line."""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass, field

from mbds.errors import ModelError
from mbds.io.dapbc.lexer import Token, tokenize


# Expressions (every node carries its 1-based line).  Apply is ``base(args)``: a call or an
# index, told apart when evaluated.  Matrix rows are tuples of expressions.
Num = namedtuple("Num", "value line")
Text = namedtuple("Text", "value line")
Name = namedtuple("Name", "id line")
FieldRef = namedtuple("FieldRef", "base name line")
Apply = namedtuple("Apply", "base args line")
Unary = namedtuple("Unary", "op operand line")
Binary = namedtuple("Binary", "op left right line")
Transpose = namedtuple("Transpose", "operand line")
Matrix = namedtuple("Matrix", "rows line")

# Statements.  An If holds ((condition, body), ...) for its if and elseif branches and the
# body of its else (empty when none); an Assign's target is a Name, FieldRef or Apply.
Assign = namedtuple("Assign", "target value line")
ExprStmt = namedtuple("ExprStmt", "expr line")
Global = namedtuple("Global", "names line")
If = namedtuple("If", "clauses orelse line")
FunctionHeader = namedtuple("FunctionHeader", "name outputs params line")


@dataclass
class Program:
    """A parsed file: its function header (None for a script) and its statements."""

    file: str
    header: FunctionHeader | None
    body: list = field(default_factory=list)


_COMPARE = ("==", "~=", "!=", "<", "<=", ">", ">=")
_UNSUPPORTED_KW = {"for": "for loops", "while": "while loops", "switch": "switch blocks",
                   "try": "try blocks", "do": "do-until loops", "parfor": "parfor loops",
                   "classdef": "classes", "unwind_protect": "unwind_protect blocks"}


class Parser:
    """Recursive descent over the tokens of one file."""

    def __init__(self, source: str, file: str):
        self.file = file
        self.tokens = tokenize(source, file)
        self.pos = 0
        self.matrix = [False]  # inside [ ] (True) or ( ) (False), innermost last

    # -- token helpers --
    @property
    def tok(self) -> Token:
        return self.tokens[self.pos]

    def peek(self, k: int = 1) -> Token:
        return self.tokens[min(self.pos + k, len(self.tokens) - 1)]

    def advance(self) -> Token:
        t = self.tokens[self.pos]
        self.pos += 1
        return t

    def at(self, *texts: str) -> bool:
        return self.tok.kind in ("op", "kw") and self.tok.text in texts

    def error(self, message: str, line: int | None = None):
        return ModelError(message, self.file, self.tok.line if line is None else line)

    def expect(self, text: str, what: str) -> Token:
        if not self.at(text):
            raise self.error(f"expected '{text}' {what}, found {describe(self.tok)}")
        return self.advance()

    def skip_separators(self):
        while self.tok.kind == "nl" or self.at(";", ","):
            self.advance()

    # -- statements --
    def parse_program(self) -> Program:
        self.skip_separators()
        header = None
        if self.at("function"):
            header = self.function_header()
        body = self.block(until=("end", "function") if header else ("function",))
        if header is not None and self.at("end"):
            end_line = self.advance().line
            self.end_of_statement()
            self.skip_separators()
            if self.tok.kind != "eof" and not self.at("function"):
                raise self.error("this 'end' closes the function but statements follow it "
                                 "(an 'end' without 'if'?)", end_line)
        if self.at("function"):
            raise self.error("a second function in the file is outside the subset")
        if self.at("end"):
            raise self.error("'end' without a matching 'if'")
        if self.tok.kind != "eof":
            raise self.error(f"unexpected {describe(self.tok)}")
        return Program(self.file, header, body)

    def function_header(self) -> FunctionHeader:
        line = self.advance().line
        outputs: list[str] = []
        if self.at("["):
            outputs = self.name_list("]", "an output name")
            self.expect("=", "after the function's outputs")
        name = self.name_token("a function name").text
        if self.at("="):
            self.advance()
            outputs, name = [name], self.name_token("a function name").text
        params = self.name_list(")", "a parameter name") if self.at("(") else []
        self.end_of_statement()
        return FunctionHeader(name, tuple(outputs), tuple(params), line)

    def name_list(self, close: str, what: str) -> list[str]:
        """Names separated by commas, after the opening bracket, up to ``close``."""
        self.advance()
        names = []
        while not self.at(close):
            names.append(self.name_token(what).text)
            if self.at(","):
                self.advance()
            elif not self.at(close):
                raise self.error(f"expected ',' or '{close}', found {describe(self.tok)}")
        self.advance()
        return names

    def name_token(self, what: str) -> Token:
        if self.tok.kind != "name":
            raise self.error(f"expected {what}, found {describe(self.tok)}")
        return self.advance()

    def block(self, until: tuple[str, ...]) -> list:
        body = []
        self.skip_separators()
        while self.tok.kind != "eof" and not self.at(*until):
            body.append(self.statement())
            self.skip_separators()
        return body

    def end_of_statement(self):
        if self.tok.kind in ("nl", "eof") or self.at(";", ","):
            return
        raise self.error(f"expected the end of the statement, found {describe(self.tok)}")

    def statement(self):
        t = self.tok
        if t.kind == "kw":
            if t.text == "if":
                return self.if_statement()
            if t.text == "global":
                self.advance()
                names = []
                while self.tok.kind == "name":
                    names.append(self.advance().text)
                if not names:
                    raise self.error("'global' needs at least one name")
                self.end_of_statement()
                return Global(tuple(names), t.line)
            if t.text in _UNSUPPORTED_KW:
                raise self.error(f"{_UNSUPPORTED_KW[t.text]} are outside the subset mbds reads")
            raise self.error(f"unexpected '{t.text}'")
        if self.at("["):
            start = self.pos
            depth = 0
            while self.tok.kind not in ("nl", "eof"):  # [a, b] = f(...) is a multiple assignment
                if self.at("[", "("):
                    depth += 1
                elif self.at("]", ")"):
                    depth -= 1
                elif self.at("=") and depth == 0:
                    raise self.error("assignments to several outputs ([a, b] = ...) are outside the subset")
                self.advance()
            self.pos = start
        if t.kind == "name" and self.peek().kind in ("name", "num", "str") and self.peek().space_before \
                and not (self.peek().kind == "name" and self.peek().text in ("=",)):
            raise self.error(f"command syntax '{t.text} {self.peek().text}' is outside the subset")
        expr = self.expression()
        if self.at("="):
            if not isinstance(expr, (Name, FieldRef, Apply)) or not _assignable(expr):
                raise self.error("the left side of '=' must be a name, a field or an indexed element")
            self.advance()
            value = self.expression()
            self.end_of_statement()
            return Assign(expr, value, t.line)
        self.end_of_statement()
        return ExprStmt(expr, t.line)

    def if_statement(self) -> If:
        line = self.advance().line
        clauses = [(self.expression(), None)]
        body = self.block(until=("elseif", "else", "end"))
        clauses[-1] = (clauses[-1][0], tuple(body))
        orelse: tuple = ()
        while True:
            if self.tok.kind == "eof":
                raise self.error("this 'if' is never closed by 'end'", line)
            if self.at("elseif"):
                self.advance()
                cond = self.expression()
                clauses.append((cond, tuple(self.block(until=("elseif", "else", "end")))))
            elif self.at("else"):
                self.advance()
                orelse = tuple(self.block(until=("elseif", "else", "end")))
                if not self.at("end"):
                    if self.tok.kind == "eof":
                        raise self.error("this 'if' is never closed by 'end'", line)
                    raise self.error(f"'{self.tok.text}' after 'else'")
            else:
                self.advance()  # end
                self.end_of_statement()
                return If(tuple(clauses), orelse, line)

    # -- expressions, lowest precedence first --
    def expression(self):
        return self.binary_level(0)

    _LEVELS = (("||",), ("&&",), ("|",), ("&",), _COMPARE, ("+", "-"), ("*", "/", ".*", "./", "\\"))

    def binary_level(self, level: int):
        if level == len(self._LEVELS):
            return self.unary()
        left = self.binary_level(level + 1)
        ops = self._LEVELS[level]
        while self.tok.kind == "op" and self.tok.text in ops:
            if self.element_boundary():
                break
            op = self.advance()
            if op.text == "\\":
                raise self.error("left division '\\' is outside the subset", op.line)
            right = self.binary_level(level + 1)
            left = Binary("~=" if op.text == "!=" else op.text, left, right, op.line)
        if self.at(":"):
            raise self.error("ranges 'a:b' are outside the subset")
        return left

    def element_boundary(self) -> bool:
        """Inside [ ], '1 -2' is two elements: a spaced sign directly before its operand."""
        t = self.tok
        return (self.matrix[-1] and t.text in ("+", "-") and t.space_before
                and not self.peek().space_before and self.peek().kind != "nl")

    def unary(self):
        if self.at("-", "+", "~", "!"):
            op = self.advance()
            operand = self.unary()
            return Unary("~" if op.text == "!" else op.text, operand, op.line)
        return self.power()

    def power(self):
        base = self.postfix()
        while self.at("^", ".^"):
            op = self.advance()
            if self.at("-", "+", "~", "!"):  # 2^-1
                sign = self.advance()
                exponent = Unary("~" if sign.text == "!" else sign.text, self.postfix(), sign.line)
            else:
                exponent = self.postfix()
            base = Binary(op.text, base, exponent, op.line)
        return base

    def postfix(self):
        expr = self.primary()
        while True:
            t = self.tok
            if t.kind == "op" and t.text == "." and not t.space_before:
                self.advance()
                if self.tok.kind not in ("name", "kw"):
                    raise self.error(f"expected a field name after '.', found {describe(self.tok)}")
                expr = FieldRef(expr, self.advance().text, t.line)
            elif t.kind == "op" and t.text == "(" and not (self.matrix[-1] and t.space_before):
                self.advance()
                self.matrix.append(False)
                args = []
                while not self.at(")"):
                    if self.at(":"):
                        raise self.error("':' indexing is outside the subset")
                    args.append(self.expression())
                    if self.at(","):
                        self.advance()
                    elif not self.at(")"):
                        raise self.error(f"expected ',' or ')', found {describe(self.tok)}")
                self.matrix.pop()
                self.advance()
                expr = Apply(expr, tuple(args), t.line)
            elif t.kind == "op" and t.text in ("'", ".'"):
                self.advance()
                expr = Transpose(expr, t.line)
            elif t.kind == "op" and t.text == "{":
                raise self.error("cell arrays '{ }' are outside the subset")
            else:
                return expr

    def primary(self):
        t = self.tok
        if t.kind == "num":
            self.advance()
            return Num(float(t.text), t.line)
        if t.kind == "str":
            self.advance()
            return Text(t.text, t.line)
        if t.kind == "name":
            self.advance()
            return Name(t.text, t.line)
        if t.kind == "kw" and t.text == "end":
            raise self.error("'end' inside an expression is outside the subset")
        if self.at("("):
            self.advance()
            self.matrix.append(False)
            inner = self.expression()
            self.matrix.pop()
            self.expect(")", "to close '('")
            return inner
        if self.at("["):
            return self.matrix_literal()
        if self.at("@"):
            raise self.error("function handles '@' are outside the subset")
        if self.at("{"):
            raise self.error("cell arrays '{ }' are outside the subset")
        hint = " (continue a statement on the next line with '...')" if t.kind == "nl" else ""
        raise self.error(f"expected a value, found {describe(t)}{hint}")

    def matrix_literal(self) -> Matrix:
        line = self.advance().line
        self.matrix.append(True)
        rows: list[list] = [[]]
        while True:
            t = self.tok
            if t.kind == "eof":
                raise self.error(f"'[' at line {line} is never closed by ']'")
            if self.at("]"):
                self.advance()
                break
            if self.at("="):
                raise self.error(f"'[' at line {line} is never closed by ']'", line)
            if t.kind == "nl" or self.at(";"):
                self.advance()
                if rows[-1]:
                    rows.append([])
                continue
            if self.at(","):
                if not rows[-1]:
                    raise self.error("',' without a value before it")
                self.advance()
                continue
            rows[-1].append(self.expression())
            if not (self.at("]", ";", ",") or self.tok.kind in ("nl", "eof") or self.tok.space_before):
                raise self.error(f"expected ',', ';' or ']' in the brackets, found {describe(self.tok)}")
        self.matrix.pop()
        if not rows[-1]:
            rows.pop()
        return Matrix(tuple(tuple(r) for r in rows), line)


def _assignable(expr) -> bool:
    if isinstance(expr, Name):
        return True
    if isinstance(expr, FieldRef):
        return _assignable(expr.base)
    if isinstance(expr, Apply):
        return _assignable(expr.base)
    return False


def describe(t: Token) -> str:
    """A token as an error message names it."""
    if t.kind == "eof":
        return "the end of the file"
    if t.kind == "nl":
        return "the end of the line"
    if t.kind == "str":
        return f"text '{t.text}'"
    return f"'{t.text}'"


def parse(source: str, file: str) -> Program:
    """Parse one in-file or user_force.m; ModelError ``file:line: ...`` on anything outside the subset."""
    return Parser(source, file).parse_program()
