"""Tokens of the MATLAB subset that DAP_BC in-files and user_force.m are written in.

Handles ``%`` comments (and ``%{ ... %}`` blocks), ``...`` line continuation, single-quoted
character arrays (``''`` for a quote) and the transpose quote.  Every token carries its
1-based line and whether white space came before it (inside ``[ ]`` white space separates
elements)."""

from __future__ import annotations

import re
from dataclasses import dataclass

from mbds.errors import ModelError

KEYWORDS = {"if", "elseif", "else", "end", "function", "global", "for", "while", "switch",
            "case", "otherwise", "break", "continue", "return", "try", "catch", "do", "until",
            "parfor", "classdef", "unwind_protect"}
OPERATORS = (".*", "./", ".^", ".'", "==", "~=", "!=", "<=", ">=", "&&", "||",
             "+", "-", "*", "/", "\\", "^", "<", ">", "&", "|", "~", "!", "=", "(", ")",
             "[", "]", "{", "}", ";", ",", ".", ":", "'", "@")
_NUMBER = re.compile(r"(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


@dataclass(frozen=True)
class Token:
    """One token: kind ('num', 'str', 'name', 'kw', 'op', 'nl', 'eof'), its text, line, and
    whether white space preceded it on the same line."""

    kind: str
    text: str
    line: int
    space_before: bool = False


def tokenize(source: str, file: str) -> list[Token]:
    """Split ``source`` into tokens; a character outside the subset raises ModelError at its line."""
    tokens: list[Token] = []
    line, i, n = 1, 0, len(source)
    depth = 0  # nesting of [ ] and { }, where a quote after a space starts text
    space = False
    while i < n:
        c = source[i]
        if c in " \t\r":
            i += 1
            space = True
            continue
        if c == "\n":
            tokens.append(Token("nl", "\n", line, space))
            line += 1
            i += 1
            space = False
            continue
        if c == "%" or c == "#":
            eol = source.find("\n", i)
            this_line = source[source.rfind("\n", 0, i) + 1:n if eol < 0 else eol]
            if this_line.strip() in ("%{", "#{"):
                end = re.compile(r"^[ \t]*[%#]\}[ \t]*$", re.M).search(source, i)
                if end is None:
                    raise ModelError("block comment %{ is never closed by %}", file, line)
                line += source.count("\n", i, end.end())
                i = end.end()
                continue
            while i < n and source[i] != "\n":
                i += 1
            continue
        if source.startswith("...", i):
            while i < n and source[i] != "\n":
                i += 1
            if i < n:
                line += 1
                i += 1
            space = True
            continue
        prev = tokens[-1] if tokens else None
        if c == "'":
            transpose = prev is not None and (
                prev.kind in ("name", "num") or prev.text in (")", "]", "}", "'", ".'") or
                (prev.kind == "kw" and prev.text == "end"))
            if transpose and not (space and depth > 0):
                tokens.append(Token("op", "'", line, space))
                i += 1
                space = False
                continue
            j = i + 1
            text = []
            while True:
                if j >= n or source[j] == "\n":
                    raise ModelError("text in quotes is not closed on this line", file, line)
                if source[j] == "'":
                    if j + 1 < n and source[j + 1] == "'":
                        text.append("'")
                        j += 2
                        continue
                    break
                text.append(source[j])
                j += 1
            tokens.append(Token("str", "".join(text), line, space))
            i = j + 1
            space = False
            continue
        if c == '"':
            raise ModelError('double-quoted strings are outside the subset; use single quotes', file, line)
        m = _NUMBER.match(source, i)
        if m and (c.isdigit() or (c == "." and m.end() > i + 1)):
            text = m.group(0).replace("d", "e").replace("D", "e")
            if m.end() < n and (source[m.end()].isalpha() or source[m.end()] == "_"):
                raise ModelError(f"malformed number '{source[i:m.end() + 1]}'", file, line)
            tokens.append(Token("num", text, line, space))
            i = m.end()
            space = False
            continue
        m = _NAME.match(source, i)
        if m:
            word = m.group(0)
            word = "end" if word in ("endif", "endfunction") else word  # Octave's spellings
            tokens.append(Token("kw" if word in KEYWORDS else "name", word, line, space))
            i = m.end()
            space = False
            continue
        for op in OPERATORS:
            if source.startswith(op, i):
                if op in ("[", "{"):
                    depth += 1
                elif op in ("]", "}"):
                    depth = max(depth - 1, 0)
                tokens.append(Token("op", op, line, space))
                i += len(op)
                space = False
                break
        else:
            raise ModelError(f"unexpected character {c!r}", file, line)
    tokens.append(Token("nl", "\n", line, space))
    tokens.append(Token("eof", "", line, False))
    return tokens
