"""Worn shapes across versions (the manual's Figures 2.10/2.11) and the campaign summary."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from mbds.errors import ModelError
from mbds.plot.source import history_paths, open_history

SHAPE_VARIABLES = ("shape_x", "shape_y", "point_body", "body")
LINE_STYLES = ("-", "--", ":", "-.")
VERSION_COLORS = ListedColormap(colormaps["Blues"](np.linspace(0.35, 1.0, 256)))
"""Light (first version) to dark (last)."""


def wear(source, body: str, versions: list[int] | None = None, replicate: int = 0) -> Figure:
    """The outline of ``body`` (body frame, m) at each version, overlaid from light (first) to
    dark (last). ``source`` is a model folder (its versions with a run), a list of history
    datasets, or a collected campaign (``mbds.open_campaign``): then one panel per variant (the
    chains of ``replicate`` when every replicate has its own shapes). ``versions``: which ones
    (default all). Each panel holds one line per version (``ax.lines``, label ``version NNN``)."""
    table, title = _shape_table(source, replicate)
    names = [str(n) for n in table["body"].values]
    if body not in names:
        raise ModelError(f"no body {body!r}; the bodies are {', '.join(names)}")
    shown = [int(v) for v in table["version"].values] if versions is None else list(versions)
    missing = sorted(set(shown) - {int(v) for v in table["version"].values})
    if missing:
        raise ModelError(f"no version {', '.join(f'{v:03d}' for v in missing)} with a run")
    mine = np.flatnonzero(table["point_body"].values == names.index(body))
    x = table["shape_x"].sel(version=shown).isel(point=mine).values
    y = table["shape_y"].sel(version=shown).isel(point=mine).values
    panels = table["panel"].values
    columns = min(len(panels), max(4, int(np.ceil(np.sqrt(len(panels))))))
    rows = -(-len(panels) // columns)
    # fixed margins in inches: a constrained layout of 64 panels takes seconds to compute
    side = 3.2 if columns <= 4 else 2.2  # inches per panel
    width, height = side * columns + 1.6, side * rows + 0.9
    margins = {"left": 0.8 / width, "right": 1.0 - 1.2 / width, "bottom": 0.5 / height, "top": 1.0 - 0.6 / height,
               "wspace": 0.3, "hspace": 0.35}
    figure = Figure(figsize=(width, height))
    grid = figure.add_gridspec(rows, columns, **margins)
    # the panels do not share their axes (matplotlib would compare every panel's limits with all
    # the others' each time one is read): they get the same limits, as shared ones would
    axes = [figure.add_subplot(grid[k // columns, k % columns]) for k in range(rows * columns)]
    limits = [_limits(values) for values in (x, y)]
    shades = VERSION_COLORS(np.linspace(0.0, 1.0, len(shown)))
    for k, (ax, panel) in enumerate(zip(axes, panels)):
        # one call for the panel's outlines (one line each), closed by their first point
        lines = ax.plot(np.vstack([x[k].T, x[k, :, :1].T]), np.vstack([y[k].T, y[k, :, :1].T]), linewidth=1.0)
        for line, shade, version in zip(lines, shades, shown):
            line.set_color(shade)
            line.set_label(f"version {version:03d}")
        ax.set(xlim=limits[0], ylim=limits[1], aspect="equal")
        ax.xaxis.set_major_locator(MaxNLocator(4))  # fewer ticks, each made and drawn per panel
        ax.yaxis.set_major_locator(MaxNLocator(4))
        # a title at a fixed height: matplotlib otherwise measures every panel's tick labels to
        # place it (a third of the drawing time of 64 panels)
        ax.set_title(str(panel), fontsize="medium", y=1.0, pad=4.0)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.label_outer()  # the same limits everywhere: labels on the outer panels only, and inner panels
        spec = ax.get_subplotspec()  # without tick marks (most of the drawing time is ticks)
        ax.xaxis.set_visible(spec.is_last_row() or k + columns >= len(panels))
        ax.yaxis.set_visible(spec.is_first_col())
    for ax in axes[len(panels):]:
        ax.set_visible(False)
    bar = ScalarMappable(Normalize(shown[0], shown[-1] if len(shown) > 1 else shown[0] + 1), VERSION_COLORS)
    figure.colorbar(bar, cax=figure.add_axes((1.0 - 0.9 / width, margins["bottom"], 0.15 / width,
                                             margins["top"] - margins["bottom"])), label="version")
    figure.suptitle(f"{body} worn: {title}", y=1.0 - 0.3 / height, va="center")
    return figure


def _limits(values: np.ndarray) -> tuple[float, float] | None:
    """The axis limits that hold ``values`` (m) with matplotlib's margins (None: all NaN)."""
    low, high = np.nanmin(values, initial=np.inf), np.nanmax(values, initial=-np.inf)
    if not np.isfinite(low):
        return None
    pad = 0.05 * (high - low) if high > low else 0.05 * max(abs(low), 1.0)
    return low - pad, high + pad


def _shape_table(source, replicate: int) -> tuple[xr.Dataset, str]:
    """Shapes with dimensions (panel, version, point), the bodies and a title."""
    if isinstance(source, xr.DataTree):
        root = source.ds
        table = root[list(SHAPE_VARIABLES)]
        if "replicate" in table["shape_x"].dims:
            table = table.isel(replicate=replicate)
        return table.rename(variant="panel"), root.attrs.get("title", "campaign")
    datasets = [_shapes_of(p) for p in history_paths(source)] if isinstance(source, (str, Path)) else list(source)
    if not datasets:
        raise ModelError("no runs to draw")
    model = datasets[0].attrs.get("model", "?")
    versions = [int(ds.attrs["version"]) for ds in datasets]
    rows = [ds[list(SHAPE_VARIABLES)].expand_dims(version=[v]) for ds, v in zip(datasets, versions)]
    table = xr.concat(rows, "version", data_vars="minimal", coords="minimal", compat="override")
    return table.expand_dims(panel=[f"model {model}"]), f"model {model}"


def _shapes_of(path: Path) -> xr.Dataset:
    """The shape variables of one history, read (the file is closed again)."""
    with open_history(path) as ds:
        return ds[list(SHAPE_VARIABLES)].load()


def campaign_summary(campaign: xr.DataTree) -> Figure:
    """Three panels against version: the mechanical energy lost in each run (J), the mechanical
    energy at the run's end (J) and the largest reshaping (m, the largest displacement of a
    shape point from the previous version's shape); one line per variant (the mean over
    replicates), coloured by the first varied key and dashed by the second. Reads only the campaign's summary."""
    root = campaign.ds
    versions = root["version"].values
    lost, final = root["run_lost_work"], root["end_energy"]
    if "replicate" in lost.dims:
        lost, final = lost.mean("replicate"), final.mean("replicate")
    shift = _largest_reshaping(root)
    figure = Figure(figsize=(7, 8), layout="constrained")
    panels = figure.subplots(3, 1, sharex=True)
    colors, styles, legend = _variant_styles(root)
    rows = [values.transpose("variant", "version").values for values in (lost, final, shift)]  # read once
    for k in range(root.sizes["variant"]):
        for ax, values in zip(panels, rows):
            ax.plot(versions, values[k], marker="o", linestyle=styles[k], color=colors[k], label=legend[k],
                    markersize=3)
    panels[2].xaxis.set_major_locator(MaxNLocator(integer=True))
    panels[0].set_ylabel("lost work in the run (J)")
    panels[1].set_ylabel("mechanical energy at the end (J)")
    panels[2].set_ylabel("largest reshaping (m)")
    panels[2].set_xlabel("version")
    if len(legend) <= 16:
        figure.legend(*panels[0].get_legend_handles_labels(), loc="outside lower center", fontsize="small")
    panels[0].set_title(root.attrs.get("title", "campaign"))
    return figure


def _largest_reshaping(root: xr.Dataset) -> xr.DataArray:
    """Per variant and version, the largest distance (m) of a shape point from where it was in
    the previous version (NaN for the first); the mean over replicates when each has a shape."""
    dx, dy = (root[n].diff("version", label="upper") for n in ("shape_x", "shape_y"))
    shift = np.hypot(dx, dy).max("point")
    if "replicate" in shift.dims:
        shift = shift.mean("replicate")
    return shift.reindex(version=root["version"])


def _variant_styles(root: xr.Dataset) -> tuple[list, list[str], list[str]]:
    """A colour, a line style and a legend text per variant, from the varied keys that take
    more than one value: colour by the first numeric one, line style by the next one."""
    count = root.sizes["variant"]
    keys = [n for n, c in root.coords.items()
            if "key" in c.attrs and c.dims == ("variant",) and len(np.unique(c.values)) > 1]
    legend = [", ".join(f"{root[k].attrs['key']} = {root[k].values[i]}" for k in keys) or str(root["variant"].values[i])
              for i in range(count)]
    numeric = [k for k in keys if root[k].dtype.kind in "fiu"]
    if numeric:
        values = root[numeric[0]].values.astype(float)
        span = Normalize(values.min(), values.max())
        colors = [colormaps["viridis"](0.85 * span(v)) for v in values]
    else:
        colors = [colormaps["tab10"](i % 10) for i in range(count)]
    rest = [k for k in keys if not numeric or k != numeric[0]]
    styles = ["-"] * count
    if rest:
        levels = list(np.unique(root[rest[0]].values))
        styles = [LINE_STYLES[levels.index(v) % len(LINE_STYLES)] for v in root[rest[0]].values]
    return colors, styles, legend
