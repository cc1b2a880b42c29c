"""The options of one run of a version, light to import (campaign plans hold one per run task)."""

from __future__ import annotations

from dataclasses import dataclass

from mbds.io.job import JobSettings


@dataclass
class RunOptions:
    """``duration``: length of the run (s), default the world's ``breakTime``; ``seed`` of the
    lexicographic tolerance draws (a continued run keeps the random state it starts from);
    ``start_from``: the version whose end state the run starts from (None: the model's start);
    ``job``: the job settings that apply (``lexicoRandomizationRange``, ``maxLinesInLog``; None:
    those of the model folder's job file)."""

    duration: float | None = None
    seed: int = 0
    start_from: int | None = None
    job: JobSettings | None = None
