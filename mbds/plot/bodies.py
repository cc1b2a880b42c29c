"""MBDS bodies drawn as matplotlib polygons in their world pose: moving bodies filled in their
RGBColor, fixed bodies hatched grey, virtual bodies as a dashed outline."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.patches import Polygon

STYLES = {
    "moving": {"alpha": 0.85, "edgecolor": "black", "linewidth": 0.8},
    "fixed": {"facecolor": "0.8", "edgecolor": "0.35", "hatch": "///", "linewidth": 0.8},
    "virtual": {"fill": False, "linestyle": "--", "linewidth": 1.2},
}


class BodyOutlines:
    """The bodies of a run: names, kinds, colours and body-frame polygons (closed, m), and their
    world polygons at a sample from ``body_x``, ``body_y``, ``body_angle``."""

    def __init__(self, ds: xr.Dataset):
        self.ds = ds
        self.names = [str(n) for n in ds["body"].values]
        self.kinds = [str(k) for k in ds["body_kind"].values]
        self.colors = ds["body_color"].values
        owner = ds["point_body"].values
        x, y = ds["shape_x"].values, ds["shape_y"].values
        self.local = []
        for index in range(len(self.names)):
            mine = owner == index
            points = np.column_stack([x[mine], y[mine]])
            self.local.append(np.vstack([points, points[:1]]))

    def poses(self, index) -> np.ndarray:
        """Poses (x, y, Rz) of every body at the samples ``index`` (an int or an array)."""
        return np.stack([self.ds[name].isel(time=index).values for name in ("body_x", "body_y", "body_angle")], -1)

    def world(self, pose: np.ndarray) -> list[np.ndarray]:
        """The closed world polygons (m) of every body at ``pose`` (bodies, 3)."""
        out = []
        for points, (x, y, angle) in zip(self.local, pose):
            c, s = np.cos(angle), np.sin(angle)
            out.append(np.column_stack([x + c * points[:, 0] - s * points[:, 1], y + s * points[:, 0] + c * points[:, 1]]))
        return out

    def moving(self, polygons: list[np.ndarray]) -> list[np.ndarray]:
        """Those of ``polygons`` (one per body, for one or more poses in turn) that belong to bodies
        that are not fixed."""
        return [p for i, p in enumerate(polygons) if self.kinds[i % len(self.kinds)] != "fixed"]

    def draw(self, ax: Axes, pose: np.ndarray) -> list[Polygon]:
        """One polygon patch per body on ``ax`` (label: the body's name, gid: its kind)."""
        patches = []
        for name, kind, color, polygon in zip(self.names, self.kinds, self.colors, self.world(pose)):
            style = dict(STYLES[kind])
            if kind == "moving":
                style["facecolor"] = color
            elif kind == "virtual":
                style["edgecolor"] = color
            patch = Polygon(polygon, closed=True, label=name, gid=kind, **style)
            ax.add_patch(patch)
            patches.append(patch)
        return patches


def frame_axes(ax: Axes, polygons: list[np.ndarray], margin: float = 0.05, around: list[np.ndarray] | None = None,
               limits: tuple[float, float, float, float] | None = None) -> None:
    """Equal scales, axis labels in m, and ``limits`` (xmin, xmax, ymin, ymax; m), by default
    around ``polygons``, cut to half the size of the polygons ``around`` (the moving bodies) on
    each side so that a long fixed body does not shrink them."""
    if limits is None:
        points = np.concatenate(polygons)
        low, high = points.min(0), points.max(0)
        if around:
            inner = np.concatenate(around)
            reach = 0.5 * max(float((inner.max(0) - inner.min(0)).max()), 1e-9)
            low, high = np.maximum(low, inner.min(0) - reach), np.minimum(high, inner.max(0) + reach)
        pad = margin * max(float((high - low).max()), 1e-9)
        limits = (low[0] - pad, high[0] + pad, low[1] - pad, high[1] + pad)
    ax.set_xlim(*limits[:2])
    ax.set_ylim(*limits[2:])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
