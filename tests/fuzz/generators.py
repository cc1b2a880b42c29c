"""Hypothesis generators of malformed input files, one entry per file type.

Each :class:`FileType` names the files it covers (their well-formed texts) and the pieces that
mutations insert: tokens of the file's own syntax, numbers at the edges of their ranges and
characters that break parsers. :func:`mutated` draws one file of a type and one to three edits
of it. A new file type (a DAP_BC in-file as it arrives, say) is one more entry of
:data:`FILE_TYPES`; the fuzz tests pick it up.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from hypothesis import strategies as st

from tests.dapbc_io.folders import SP
from tests.dapbc_io.mutations import mutate
from tests.examples import CAMPAIGNS

EDGE_NUMBERS = ["0", "-0", "-1", "1e-320", "1e308", "1e400", "-1e400", "nan", "NaN", "inf", "-inf", "1*^-7",
                "100000000000", "-100000000000", "1.5.2", "0x10", "1e", "+", "", "2**1000"]
HOSTILE = ["\x00", "\n", "\r", "\t", "\ufeff", "\u00e9", "\u2019", "$(id)", "`id`", "'", '"', "\\", "%", "%%",
           "__import__('os').system('id')", "/etc/passwd", "..", ".", "../../..", "~", "*", ";", ","]
INI = ["[", "]", "[main]", "[bodies]", "[campaign]", "=", "==", " = ", "[Mass properties]", "[startPosition]"]


@dataclass(frozen=True)
class FileType:
    """Files of one kind: ``texts`` (file name -> well-formed text) and the mutation ``pieces``."""

    name: str
    texts: dict[str, str]
    pieces: tuple[str, ...]


def _model_texts(model: str, suffixes: tuple[str, ...]) -> dict[str, str]:
    folder = CAMPAIGNS / model
    return {p.name: p.read_text() for p in sorted(folder.iterdir()) if p.suffix in suffixes}


MODEL_PIECES = (*EDGE_NUMBERS, *HOSTILE, *INI, "c'", "b'mass1'", "b'mass1'm", "g'", "b'nobody'x", "temp", "vRel",
                "Sin[", "]", "(", ")", "*", "/", "^", "-", "current.", "%%data", "%%J", "%%%new%%%", "all", "1:3",
                "T:T", "T:X", "mass1-mass2", "mass1:all", "MaxInt")
JOB_PIECES = (*EDGE_NUMBERS, *HOSTILE, *INI, "jobs = ", "000-002", "999-000", "000,000", "createNextVersionAtEnd",
              "worldFile = ", "folder = ", "replicates = ", "seed = ", "mode = ", "ensemble", "maxTasks = ",
              "c'gravity = ", "world.breakTime = ", "world.maximumTimestep = ", "contact.mass1-mass2.friction = ",
              "contact.nobody-x.friction = ", "0.1, 0.2", "0.2 0.4", "0.2; 0.4", "abc")
DAPBC_PIECES = ("[", "]", "(", ")", ";", ",", "'", "...", "%", "=", "==", ".", "end", "if", "else", "function",
                "global", "include_global", "Bodies", "Points(2)", "B1", ".r", ".type", "Body_struct",
                "Point_struct", "1e300", "1e400", "NaN", "Inf", "pi", "sin(", "~", "^", "*", "/", "\n", " ",
                "B1.m = ", ":", "{", "@", '"', "1/0", "[1 2; 3]", "\t", "\x00")

TWO_MASS_JOB = "[main]\njobs = 000-002\ncreateNextVersionAtEnd = 1\n"
CAMPAIGN_SECTION = ("[campaign]\nfolder = runs\nseed = 3\nreplicates = 2\nmode = chains\nc'gravity = 9.81, 5\n"
                    "contact.mass1-mass2.friction = 0.1, 0.3\nworld.breakTime = 0.2, 0.4\n")

FILE_TYPES = {
    "model": FileType("model", _model_texts("2mass", (".wld", ".bdy", ".exs", ".cns", ".cop", ".gc", ".dc", ".mmx",
                                                       ".hv", ".me", ".wtc")), MODEL_PIECES),
    "job": FileType("job", {"2mass.job": TWO_MASS_JOB}, JOB_PIECES),
    "campaign": FileType("campaign", {"2mass.job": TWO_MASS_JOB + CAMPAIGN_SECTION}, JOB_PIECES),
    "dapbc": FileType("dapbc", dict(SP), DAPBC_PIECES),
}


@st.composite
def mutated(draw, kind: str) -> tuple[str, str]:
    """(file name, mutated text) of one file of the file type ``kind``."""
    file_type = FILE_TYPES[kind]
    name = draw(st.sampled_from(sorted(file_type.texts)))
    return name, mutate(draw, file_type.texts[name], list(file_type.pieces), swap_lines=True)


def write(folder: Path, name: str, text: str) -> Path:
    """Write ``text`` as file ``name`` of ``folder`` (UTF-8, NUL bytes and all); its path."""
    path = folder / name
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    return path
