"""Time series of a run: the watches (the Plot window), energies, coordinates and multipliers,
and the lost work per shape point as a coloured outline."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure

from mbds.errors import ModelError
from mbds.plot.bodies import frame_axes
from mbds.plot.figure import new_axes
from mbds.plot.source import label, run_kind, run_title

DAP_BC_ENERGIES = ("kinetic", "potential", "total")
"""Columns of a DAP_BC run's ``eng`` (time, energy) variable."""


def watches(run: xr.Dataset, watch: list[str] | None = None) -> Figure:
    """The Plot window: one panel each for the normal and the tangential impulse (or force) and
    the lost work accumulated since the run's start (J), one line per watch (``watch``: the
    labels to show; default all). Returns the figure (panels in ``figure.axes``)."""
    if not run.sizes.get("watch", 0):
        raise ModelError("the run has no watches (contactWatch in the .wtc file)")
    chosen = run["watch"].values if watch is None else watch
    missing = sorted(set(chosen) - set(run["watch"].values))
    if missing:
        raise ModelError(f"no watch {', '.join(missing)}; the watches are {', '.join(run['watch'].values)}")
    figure = Figure(figsize=(7, 7), layout="constrained")
    panels = figure.subplots(3, 1, sharex=True)
    time = run["time"]
    for ax, name in zip(panels[:2], ("impulse_normal", "impulse_tangential")):
        values = run[name].sel(watch=chosen)
        for column, text in zip(values.values.T, chosen):
            ax.plot(time.values, column, label=str(text), linewidth=0.8)
        what = "force" if run.attrs.get("watch_convert_impulse_to_force", 0) else "impulse"
        ax.set_ylabel(f"{name.split('_')[1]} {what} ({values.attrs.get('units', '')})")
    work = _accumulated_work(run).sel(watch=chosen)
    for column, text in zip(work.values.T, chosen):
        panels[2].plot(time.values, column, label=str(text))
    panels[2].set_ylabel("lost work since the run's start (J)")
    panels[2].set_xlabel(label(time))
    if len(chosen) <= 12:
        panels[0].legend(fontsize="small", ncols=min(len(chosen), 4))
    panels[0].set_title(run_title(run, "watches"))
    return figure


def _accumulated_work(run: xr.Dataset) -> xr.DataArray:
    """The lost work at each watch since the run's start (J)."""
    if "work" not in run:
        raise ModelError("the run wrote angles instead of work (absoluteAngleInsteadOfWork = 1)")
    work = run["work"]
    return work if run.attrs.get("watch_cumulative_work", 0) else work.cumsum("time")


def lost_work_outline(run: xr.Dataset, body: str, smoothed: bool = False, ax: Axes | None = None) -> Axes:
    """The outline of ``body`` (body frame, m) coloured by the lost work accumulated at each of
    its shape points in the run (J; ``smoothed``: after smoothWorkLeftRight), with a colour bar.
    The outline is ``ax.collections[0]``, one segment per point, centred on the point."""
    ax = ax or new_axes()
    names = [str(n) for n in run["body"].values]
    if body not in names:
        raise ModelError(f"no body {body!r}; the bodies are {', '.join(names)}")
    mine = run["point_body"].values == names.index(body)
    points = np.column_stack([run["shape_x"].values[mine], run["shape_y"].values[mine]])
    loss = run["point_lost_work_smoothed" if smoothed else "point_lost_work"].values[mine]
    before = (points + np.roll(points, 1, axis=0)) / 2
    after = (points + np.roll(points, -1, axis=0)) / 2
    segments = np.stack([before, points, after], axis=1)
    lines = LineCollection(segments, array=loss, cmap="inferno_r", linewidths=4)
    ax.add_collection(lines)
    ax.figure.colorbar(lines, ax=ax, label="lost work at the point (J)")
    frame_axes(ax, [points])
    ax.set_title(run_title(run, f"lost work along {body}"))
    return ax


def energy(run: xr.Dataset, ax: Axes | None = None) -> Axes:
    """Energies against time (J): for an MBDS run the mechanical energy, the lost and the driver
    work and the balance E + lost - driver; for a DAP_BC run its kinetic, potential and total
    energy (``eng``). One line per quantity (``ax.lines``). Returns the axes."""
    ax = ax or new_axes()
    time = run["time"].values
    if run_kind(run) == "dap_bc":
        for column, name in zip(run["eng"].values.T, DAP_BC_ENERGIES):
            ax.plot(time, column, label=f"{name} energy")
    else:
        mechanical, lost, driver = (run[n].values for n in ("mechanical_energy", "lost_work", "driver_work"))
        ax.plot(time, mechanical, label="mechanical energy")
        ax.plot(time, lost, label="lost work")
        ax.plot(time, driver, label="driver work")
        ax.plot(time, mechanical + lost - driver, "--", label="mechanical energy + lost - driver work")
    ax.set_xlabel(label(run["time"]))
    ax.set_ylabel("energy (J)")
    ax.legend(fontsize="small")
    ax.set_title(run_title(run, "energy"))
    return ax


def coordinates(run: xr.Dataset) -> Figure:
    """The coordinates against time, one panel per unit (m, rad, ...), one line per coordinate:
    q and the dependent coordinates of an MBDS run, r and p of a DAP_BC run."""
    series = _coordinate_series(run)
    units = list(dict.fromkeys(unit for _, unit, _ in series))
    figure = Figure(figsize=(9, 2.5 * len(units) + 1), layout="constrained")
    panels = np.atleast_1d(figure.subplots(len(units), 1, sharex=True))
    time = run["time"].values
    for name, unit, values in series:
        panels[units.index(unit)].plot(time, values, label=name)
    for ax, unit in zip(panels, units):
        ax.set_ylabel(f"coordinate ({unit})" if unit != "1" else "coordinate")
        ax.legend(fontsize="x-small", ncols=-(-len(ax.lines) // 6), loc="upper left", bbox_to_anchor=(1.01, 1))
    panels[-1].set_xlabel(label(run["time"]))
    panels[0].set_title(run_title(run, "coordinates"))
    return figure


def _coordinate_series(run: xr.Dataset) -> list[tuple[str, str, np.ndarray]]:
    """(name, unit, values) of every coordinate."""
    if run_kind(run) == "dap_bc":
        r, p = run["r"].values, run["p"].values
        bodies = range(r.shape[1])
        return ([(f"x{b + 1}", "m", r[:, b, 0]) for b in bodies] + [(f"y{b + 1}", "m", r[:, b, 1]) for b in bodies]
                + [(f"phi{b + 1}", "rad", p[:, b]) for b in bodies])
    out = [(str(n), str(u) or "1", c) for n, u, c in zip(run["coordinate"].values, run["coordinate_unit"].values, run["q"].values.T)]
    if run.sizes.get("dependent", 0):
        out += [(str(n), str(u) or "1", c) for n, u, c in
                zip(run["dependent"].values, run["dependent_unit"].values, run["dependent_q"].values.T)]
    return out


def multipliers(run: xr.Dataset, ax: Axes | None = None) -> Axes:
    """The Lagrange multipliers of a DAP_BC run (``Lam``, time x constraint) against time, one
    line per constraint. An MBDS run has none: its contact impulses are in :func:`watches`."""
    if run_kind(run) != "dap_bc":
        raise ModelError("an MBDS run has no Lagrange multipliers; its contact impulses are drawn by `watches`")
    ax = ax or new_axes()
    for k, column in enumerate(run["Lam"].values.T):
        ax.plot(run["time"].values, column, label=f"constraint {k + 1}")
    ax.set_xlabel(label(run["time"]))
    ax.set_ylabel(label(run["Lam"]))
    ax.legend(fontsize="small", ncols=2)
    ax.set_title(run_title(run, "Lagrange multipliers"))
    return ax
