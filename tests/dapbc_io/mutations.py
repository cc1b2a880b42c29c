"""Random edits of a source text, for the fuzz tests of the DAP_BC reader and compiler."""

from __future__ import annotations

from hypothesis import strategies as st


def mutate(draw, text: str, pieces: list[str], swap_lines: bool = False) -> str:
    """One to three edits of ``text``: insert a piece or a few random characters, delete a few
    characters, replace some by a piece, or (``swap_lines``) swap two lines."""
    kinds = ["insert", "delete", "replace"] + (["swap"] if swap_lines else [])
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(kinds))
        i = draw(st.integers(0, len(text)))
        if kind == "insert":
            text = text[:i] + draw(st.sampled_from(pieces) | st.text(max_size=3)) + text[i:]
        elif kind == "delete":
            text = text[:i] + text[i + draw(st.integers(1, 8)):]
        elif kind == "replace":
            text = text[:i] + draw(st.sampled_from(pieces)) + text[i + draw(st.integers(1, 4)):]
        else:
            lines = text.split("\n")
            a, b = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
            lines[a], lines[b] = lines[b], lines[a]
            text = "\n".join(lines)
    return text
