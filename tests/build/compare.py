"""Comparing two model folders file by file: expressions numerically at random states, the
other files by their parsed contents."""

from __future__ import annotations

import importlib.util
import warnings
from pathlib import Path

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from mbds.expr.parse import parse_expression
from mbds.io.folder import ModelFiles, read_model_files

CAMPAIGNS = Path(__file__).resolve().parents[2] / "campaigns"
TOLERANCE = 1e-12
"""Largest relative difference of two expressions at a random state."""


def load_script(path: Path):
    """The module of a build script under campaigns/."""
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def read_quietly(folder: Path) -> ModelFiles:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_model_files(folder)


def expressions(files: ModelFiles) -> dict[str, str]:
    """Every expression of the .mmx, .hv, .me and .dc files, by a name saying where it is."""
    found = {}
    for i, row in enumerate(files.mass_matrix.rows):
        found.update({f"mmx[{i}][{k}]": e.text for k, e in enumerate(row)})
    found.update({f"hv[{i}]": e.text for i, e in enumerate(files.h_vector.expressions)})
    found.update({f"me[{i}]": e.text for i, e in enumerate(files.energy.expressions)})
    for c in files.dependent.coordinates:
        for label, e in zip(("position", "velocity", "acceleration"), c.definition):
            found[f"dc {c.coordinate} {label}"] = e.text
        found.update({f"dc {c.coordinate} J[{k}]": e.text for k, e in enumerate(c.jacobian or [])})
        if c.jacobian_scalar is not None:
            found[f"dc {c.coordinate} j"] = c.jacobian_scalar.text
    return found


def largest_difference(a: str, b: str, states: int = 3, seed: int = 7) -> float:
    """Largest relative difference of two expression texts at random states: every coordinate,
    derivative, constant and mass property drawn from [0.3, 1.1], with 30 digits."""
    ea, eb = parse_expression(a), parse_expression(b)
    atoms = set()
    for e in (ea, eb):
        atoms |= e.atoms(sympy.Derivative) | e.atoms(AppliedUndef) | e.free_symbols
    atoms = sorted(atoms, key=str)
    rng = np.random.default_rng(seed)
    worst = 0.0
    for _ in range(states):
        point = {x: sympy.Float(rng.uniform(0.3, 1.1), 30) for x in atoms}
        va, vb = (float(e.xreplace(point).evalf(30)) for e in (ea, eb))
        worst = max(worst, abs(va - vb) / max(1.0, abs(va), abs(vb)))
    return worst


def expression_differences(built: ModelFiles, written: ModelFiles) -> dict[str, float]:
    """Expressions whose values differ by more than :data:`TOLERANCE`, with the difference;
    an expression missing on one side counts as infinitely different."""
    ours, theirs = expressions(built), expressions(written)
    differences = {}
    for name in ours.keys() | theirs.keys():
        if name not in ours or name not in theirs:
            differences[name] = np.inf
            continue
        difference = largest_difference(ours[name], theirs[name])
        if difference > TOLERANCE:
            differences[name] = difference
    return differences
