"""Figures drawn at once in forked processes (mbds.plot.batch): the same files as drawn one
after the other, and an error raised in the caller as if drawn there."""

import functools
import os

import numpy as np
import pytest
from matplotlib.figure import Figure

from mbds.errors import ModelError
from mbds.plot import save
from mbds.plot.batch import free_cores, save_figures


def curve(k: int) -> Figure:
    figure = Figure(figsize=(2, 2))
    ax = figure.add_subplot()
    ax.plot(np.linspace(0, 1, 50), np.sin(np.linspace(0, k, 50)))
    ax.set_title(f"curve {k}")
    return figure


def broken() -> Figure:
    raise ModelError("no body 'mass3'")


def test_figures_drawn_at_once_are_the_files_drawn_one_by_one(tmp_path):
    paths = [tmp_path / f"curve{k}.png" for k in range(3)]
    assert save_figures([(functools.partial(curve, k), p) for k, p in enumerate(paths)], dpi=50) == paths
    for k, path in enumerate(paths):
        assert path.read_bytes() == save(curve(k), tmp_path / f"again{k}.png", dpi=50).read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([*(p.name for p in paths),
                                                                  *(f"again{k}.png" for k in range(3))])


def test_an_error_in_a_drawing_is_raised_here_and_the_others_are_written(tmp_path, capfd):
    with pytest.raises(ModelError, match="no body 'mass3'"):
        save_figures([(functools.partial(curve, 1), tmp_path / "one.png"), (broken, tmp_path / "broken.png"),
                      (functools.partial(curve, 2), tmp_path / "two.png")], dpi=50)
    written = sorted(p.name for p in tmp_path.iterdir())
    if free_cores() > 1:  # at once: the others were drawn by their processes
        assert written == ["one.png", "two.png"]
    assert "Traceback" not in capfd.readouterr().err


def test_each_figure_is_drawn_by_a_process_of_its_own_where_cores_are_free(tmp_path):
    def marked(k: int) -> Figure:
        (tmp_path / f"pid{k}").write_text(str(os.getpid()))
        return curve(k)

    save_figures([(functools.partial(marked, k), tmp_path / f"curve{k}.png") for k in range(2)], dpi=50)
    pids = {int((tmp_path / f"pid{k}").read_text()) for k in range(2)}
    if free_cores() > 1:
        assert len(pids) == 2 and os.getpid() not in pids
    else:
        assert pids == {os.getpid()}
