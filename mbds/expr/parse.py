"""Parse MBDS mathematical expressions (manual section 3.2) into sympy.

The grammar, loosest binding first (Mathematica's precedences)::

    sum      := product (("+" | "-") product)*
    product  := unary (("*" | "/" | juxtaposition) unary)*
    unary    := ("+" | "-") unary | power
    power    := postfix ("^" unary)?              right-associative: 2^3^2 = 2^9
    postfix  := primary "!"*                      factorial binds tighter than ^
    primary  := number | reference | name | call | Derivative[n][f][t] | "(" sum ")"

Juxtaposition (``2 c'a``, ``2(x+1)``, ``c'a Sin[x]``) multiplies. A ``-`` or ``+`` after an
operand is always binary, as in Mathematica (``2 -3`` is -1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import sympy

from mbds.errors import ModelError
from mbds.expr import symbols
from mbds.expr.functions import FUNCTIONS, factorial, power

CONTEXT_QUOTES = "`'‘’´"
"""Characters accepted as context quotes (and, after a coordinate name, as primes)."""
_MINUS = "-−"
_PUNCTUATION = "()[]{}+*/^!,;:=<>|\\\"" + _MINUS + CONTEXT_QUOTES
_MAX_NESTING = 100
_MAX_DIGITS = 308  # integer literals must stay within float64 range
_MAX_ORDER = 2


def _is_digit(ch: str) -> bool:
    return len(ch) == 1 and ch in "0123456789"


@dataclass(frozen=True)
class _Token:
    kind: str  # number, name, ref, op, end
    text: str
    column: int  # 1-based
    value: object = None  # sympy number, or (object, primes) for a reference


def parse_expression(
    text: str,
    *,
    file: str | Path | None = None,
    line: int | None = None,
    decimal_separator: str = ".",
) -> sympy.Expr:
    """Parse one expression; raise :class:`ModelError` located at ``file:line`` if it is malformed.

    ``decimal_separator`` is ``"."`` (function arguments separated by ``,``) or ``","``
    (arguments separated by ``;``).
    """
    if decimal_separator not in (".", ","):
        raise ModelError(f"decimal separator must be '.' or ',', not {decimal_separator!r}", file, line)
    if not isinstance(text, str) or not text.strip():
        raise ModelError("empty expression", file, line)
    parser = _Parser(text, decimal_separator, file, line)
    try:
        result = parser.parse()
    except RecursionError:
        raise ModelError("expression nested too deeply", file, line) from None
    if result.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo):
        raise ModelError(f"expression has no finite value (division by zero?): {text.strip()}", file, line)
    if result.has(sympy.I):
        raise ModelError(f"expression has a complex value: {text.strip()}", file, line)
    if not all(_in_float_range(number) for number in result.atoms(sympy.Number)):
        raise ModelError(f"a number is out of range in: {text.strip()}", file, line)
    return result


def _in_float_range(number: sympy.Number) -> bool:
    try:
        return math.isfinite(float(number))
    except OverflowError:
        return False


class _Tokenizer:
    def __init__(self, text: str, decimal_separator: str, fail):
        self.text = text
        self.sep = decimal_separator
        self.fail = fail  # fail(message, column) raises
        self.i = 0

    def tokens(self) -> list[_Token]:
        out = []
        text = self.text
        while True:
            while self.i < len(text) and text[self.i].isspace():
                self.i += 1
            if self.i == len(text):
                out.append(_Token("end", "end of expression", self.i + 1))
                return out
            start, ch = self.i, text[self.i]
            if _is_digit(ch) or (ch == self.sep and _is_digit(self._peek(1))):
                out.append(self._number())
            elif ch.isalpha() or ch in "_$":
                out.append(self._word())
            elif ch in "+*/^!()[]" or ch in _MINUS:
                self.i += 1
                out.append(_Token("op", "-" if ch in _MINUS else ch, start + 1))
            elif ch == self._argument_separator():
                self.i += 1
                out.append(_Token("op", ",", start + 1))
            elif ch in CONTEXT_QUOTES:
                self.fail(f"unexpected quote {ch!r}", start + 1)
            else:
                hint = f" (the decimal separator is {self.sep!r})" if ch in ".," else ""
                self.fail(f"unexpected character {ch!r}{hint}", start + 1)

    def _argument_separator(self) -> str:
        return "," if self.sep == "." else ";"

    def _peek(self, offset: int = 0) -> str:
        """The character ``offset`` ahead, or NUL past the end (NUL belongs to no character class)."""
        j = self.i + offset
        return self.text[j] if j < len(self.text) else "\0"

    def _digits(self) -> str:
        start = self.i
        while _is_digit(self._peek()):
            self.i += 1
        return self.text[start : self.i]

    def _number(self) -> _Token:
        start = self.i
        mantissa = self._digits()
        is_float = False
        if self._peek() == self.sep:
            self.i += 1
            mantissa += "." + self._digits()
            is_float = True
        exponent = self._exponent()
        literal = self.text[start : self.i]
        shown = literal if len(literal) <= 24 else literal[:20] + "..."
        if self._peek() == self.sep:
            self.fail(f"malformed number {shown}{self._peek()}", start + 1)
        if exponent is None and not is_float:
            if len(mantissa.lstrip("0")) > _MAX_DIGITS:
                self.fail(f"number {shown} is out of range", start + 1)
            return _Token("number", literal, start + 1, sympy.Integer(int(mantissa)))
        value = float(mantissa + ("e" + exponent if exponent else ""))
        if not math.isfinite(value):
            self.fail(f"number {shown} is out of range", start + 1)
        return _Token("number", literal, start + 1, sympy.Float(value))

    def _exponent(self) -> str | None:
        """Read ``e-6``, ``E+3`` or Mathematica's ``*^-7`` after a mantissa, if one follows."""
        for marker in ("*^", "e", "E"):
            if self.text.startswith(marker, self.i):
                j = self.i + len(marker)
                sign = self.text[j] if j < len(self.text) and self.text[j] in "+-" else ""
                j += len(sign)
                if _is_digit(self.text[j : j + 1]):
                    self.i = j
                    return sign + self._digits()
        return None

    def _word(self) -> _Token:
        start = self.i
        while self._peek().isalnum() or self._peek() in "_$":
            self.i += 1
        word = self.text[start : self.i]
        if word in ("b", "c", "g") and self._peek() in CONTEXT_QUOTES:
            return self._reference(word, start)
        if self._peek() in CONTEXT_QUOTES:
            self.fail(f"unexpected quote after {word!r} (contexts are b, c and g)", self.i + 1)
        return _Token("name", word, start + 1)

    def _context_name(self, what: str) -> str:
        self.i += 1  # the quote
        start = self.i
        while not (self._peek().isspace() or self._peek() in _PUNCTUATION + "\0"):
            self.i += 1
        if start == self.i:
            self.fail(f"missing {what} after the quote", start + 1)
        return self.text[start : self.i]

    def _reference(self, context: str, start: int) -> _Token:
        first = self._context_name({"b": "body name", "c": "constant name", "g": "coordinate name"}[context])
        if context == "b":
            if self._peek() not in CONTEXT_QUOTES:
                self.fail(f"expected a quote and a coordinate or property after b'{first}", self.i + 1)
            second = self._context_name("coordinate or property")
            if second in symbols.COORDINATES:
                obj = symbols.body_coordinate(first, second)
            elif second in symbols.MASS_PROPERTIES:
                obj = symbols.mass_property(first, second)
            else:
                allowed = ", ".join(symbols.COORDINATES + symbols.MASS_PROPERTIES)
                message = f"unknown body coordinate or property {second!r} in b'{first}'{second} (allowed: {allowed})"
                self.fail(message, start + 1)
        elif context == "g":
            obj = symbols.generalized(first)
        else:
            obj = symbols.constant(first)
        primes = 0
        while self._peek() in CONTEXT_QUOTES + '"':
            primes += 2 if self._peek() == '"' else 1
            self.i += 1
        if primes and isinstance(obj, sympy.Symbol):
            self.fail(f"unexpected quote after {symbols.display(obj)}", self.i)
        return _Token("ref", self.text[start : self.i], start + 1, (obj, primes))


class _Parser:
    def __init__(self, text: str, decimal_separator: str, file, line):
        self.text = text
        self.file = file
        self.line = line
        self.tokens = _Tokenizer(text, decimal_separator, self._fail).tokens()
        self.pos = 0
        self.depth = 0

    # -- infrastructure -------------------------------------------------------------------

    def _fail(self, message: str, column: int):
        raise ModelError(f"{message} at column {column}", self.file, self.line)

    def _fail_at(self, message: str, token: _Token):
        self._fail(message, token.column)

    @property
    def _next(self) -> _Token:
        return self.tokens[self.pos]

    def _take(self) -> _Token:
        token = self.tokens[self.pos]
        self.pos += 1
        return token

    def _at(self, *texts: str) -> bool:
        return self._next.kind == "op" and self._next.text in texts

    def _expect(self, text: str, opener: _Token | None = None) -> _Token:
        if not self._at(text):
            found = self._next
            shown = found.text if found.kind == "end" else repr(found.text)
            why = f" to close {opener.text!r} at column {opener.column}" if opener else ""
            self._fail_at(f"expected {text!r}{why}, found {shown}", found)
        return self._take()

    def _build(self, token: _Token, function, *args) -> sympy.Expr:
        """Call a sympy constructor, turning its failures into located ModelErrors."""
        try:
            return function(*args)
        except (ArithmeticError, ValueError, TypeError, NotImplementedError) as error:
            self._fail_at(f"cannot evaluate the expression starting with {token.text!r}: {error}", token)

    # -- grammar ---------------------------------------------------------------------------

    def parse(self) -> sympy.Expr:
        result = self._sum()
        if self._next.kind != "end":
            self._fail_at(f"unexpected {self._next.text!r}", self._next)
        return result

    def _sum(self) -> sympy.Expr:
        first = self._next
        terms = [self._product()]
        while self._at("+", "-"):
            negate = self._take().text == "-"
            term = self._product()
            terms.append(-term if negate else term)
        return self._build(first, sympy.Add, *terms) if len(terms) > 1 else terms[0]

    def _starts_operand(self) -> bool:
        token = self._next
        return token.kind in ("number", "name", "ref") or (token.kind == "op" and token.text == "(")

    def _product(self) -> sympy.Expr:
        first = self._next
        factors = [self._unary()]
        while self._at("*", "/") or self._starts_operand():
            operator = self._take() if self._at("*", "/") else None
            token = self._next
            factor = self._unary()
            if operator is not None and operator.text == "/":
                factor = self._build(token, power, factor, sympy.Integer(-1))
            factors.append(factor)
        return self._build(first, sympy.Mul, *factors) if len(factors) > 1 else factors[0]

    def _unary(self) -> sympy.Expr:
        """Every nesting (parentheses, arguments, signs, exponents) passes here: depth is counted once."""
        self.depth += 1
        if self.depth > _MAX_NESTING:
            self._fail_at("expression nested too deeply", self._next)
        if self._at("+", "-"):
            negate = self._take().text == "-"
            operand = self._unary()
            result = -operand if negate else operand
        else:
            result = self._power()
        self.depth -= 1
        return result

    def _power(self) -> sympy.Expr:
        token = self._next
        base = self._postfix()
        if not self._at("^"):
            return base
        self._take()
        return self._build(token, power, base, self._unary())

    def _postfix(self) -> sympy.Expr:
        token = self._next
        value = self._primary()
        while self._at("!"):
            bang = self._take()
            if self._at("!"):
                self._fail_at("double factorial '!!' is not supported", bang)
            value = self._build(token, factorial, value)
        return value

    def _primary(self) -> sympy.Expr:
        token = self._take()
        if token.kind == "number":
            return token.value
        if token.kind == "ref":
            return self._coordinate(token)
        if token.kind == "name":
            return self._name(token)
        if token.kind == "op" and token.text == "(":
            inner = self._sum()
            self._expect(")", token)
            return inner
        if token.kind == "end":
            self._fail_at("unexpected end of expression", token)
        self._fail_at(f"unexpected {token.text!r}", token)

    def _coordinate(self, token: _Token, extra_order: int = 0, allow_t: bool = True) -> sympy.Expr:
        """A reference token, its primes, and the optional ``[t]`` of a coordinate."""
        obj, primes = token.value
        if isinstance(obj, sympy.Symbol):
            return obj
        if allow_t and self._at("["):
            self._time_argument()
        order = primes + extra_order
        if order > _MAX_ORDER:
            self._fail_at("derivatives above the second are not supported", token)
        return sympy.Derivative(obj, (symbols.T, order)) if order else obj

    def _time_argument(self) -> None:
        opener = self._expect("[")
        if self._next.kind != "name" or self._next.text != "t":
            self._fail_at("expected t in '[t]' after a coordinate", self._next)
        self._take()
        self._expect("]", opener)

    def _name(self, token: _Token) -> sympy.Expr:
        word = token.text
        lower = word.lower()
        if word == "t":
            return symbols.T
        if lower == "temp":
            return symbols.TEMP
        if lower == "vrel":
            return symbols.VREL
        if lower == "pi":
            return sympy.pi
        if word == "E":
            return sympy.E
        if lower == "derivative":
            return self._derivative(token)
        function = FUNCTIONS.get(lower)
        if function is None:
            what = "function" if self._at("[", "(") else "identifier"
            self._fail_at(f"unknown {what} {word!r}", token)
        if not self._at("[", "("):
            self._fail_at(f"function {word!r} needs its arguments in [ ] or ( )", token)
        arguments = self._arguments()
        if not function.accepts(len(arguments)):
            self._fail_at(f"{word} takes {function.arity_text()}, not {len(arguments)}", token)
        return self._build(token, function.build, *arguments)

    def _arguments(self) -> list[sympy.Expr]:
        opener = self._take()
        closer = "]" if opener.text == "[" else ")"
        arguments = [self._sum()]
        while self._at(","):
            self._take()
            arguments.append(self._sum())
        self._expect(closer, opener)
        return arguments

    def _derivative(self, token: _Token) -> sympy.Expr:
        """``Derivative[n][f][t]`` with f a coordinate written without ``[t]``; the final ``[t]`` is optional."""
        opener = self._expect("[")
        order = self._take()
        if order.kind != "number" or not order.value.is_Integer:
            self._fail_at("expected a whole number as the derivative order", order)
        self._expect("]", opener)
        opener = self._expect("[")
        target = self._take()
        if target.kind != "ref" or isinstance(target.value[0], sympy.Symbol):
            self._fail_at("expected a coordinate (b'body'x or g'name) to differentiate", target)
        result = self._coordinate(target, extra_order=int(order.value), allow_t=False)
        self._expect("]", opener)
        if self._at("["):
            self._time_argument()
        return result
