"""The bodies of a DAP_BC run drawn as DAP_BC's ``anim`` draws them, from the history alone:
inAnimate's shapes (rect, circle, line) in the bodies' colours, the mass centres, lines from
each centre to the points on its body, every point (inPoints and inAnimate's Points_anim), the
joints' points, point-to-point force elements dashed and massless links (rev-rev, rev-tran), in
inAnimate's axis limits (docs/results.md)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import xarray as xr
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.patches import Circle, Polygon

from mbds.errors import ModelError
from mbds.plot.bodies import frame_axes

DRAWING = ("body_shape", "body_width", "body_height", "body_radius", "body_color", "point_body",
           "anim_point_body", "anim_point_local", "joint_type", "joint_points", "force_type", "force_points")
"""The variables of a dap_bc history that describe its drawing (mbds/model/dapbc/drawing.py)."""
WINDOW = ("xmin", "xmax", "ymin", "ymax")
LINKS = ("rev-rev", "rev-tran")
SPRINGS = ("ptp",)
SHAPE_STYLE = {"fill": False, "linewidth": 1.5}
SPRING_STYLE = {"colors": "m", "linestyles": "--", "linewidths": 1.0}
LINK_STYLE = {"colors": "c", "linewidths": 1.5}


class Pose(NamedTuple):
    """Where everything is at one sample (or, with a leading frame axis, at several)."""

    centres: np.ndarray  # (body, 2) mass centres r (m)
    angles: np.ndarray  # (body,) angles p (rad)
    points: np.ndarray  # (point + anim_point, 2): inPoints (rP), then Points_anim (m)

    def at(self, frame: int) -> Pose:
        """The pose of one frame of a pose over several."""
        return Pose(*(a[frame] for a in self))


def on_bodies(body: np.ndarray, local: np.ndarray, centres: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """World coordinates (m; (..., n, 2)) of body-frame points ``local`` (n, 2) on the 1-based
    bodies ``body`` (n,; 0: the ground, whose frame is the x-y frame)."""
    k = np.maximum(body - 1, 0)
    c, s = np.cos(angles[..., k]), np.sin(angles[..., k])
    world = np.stack([centres[..., k, 0] + c * local[:, 0] - s * local[:, 1],
                      centres[..., k, 1] + s * local[:, 0] + c * local[:, 1]], -1)
    return np.where((body > 0)[:, None], world, local)


class DapbcBodies:
    """The drawing of a dap_bc run: ``draw`` puts it on an axes at a pose and ``update`` moves
    it to another one."""

    def __init__(self, ds: xr.Dataset):
        missing = [n for n in DRAWING if n not in ds]
        if missing:
            raise ModelError("the history does not describe its drawing (no " + ", ".join(missing)
                             + "); it was written by an older mbds: run the model again")
        self.ds = ds
        self.shapes = [str(s) for s in ds["body_shape"].values]
        self.size = np.column_stack([ds[n].values for n in ("body_width", "body_height", "body_radius")])
        self.colors = [str(c) for c in ds["body_color"].values]
        self.anim_body = ds["anim_point_body"].values
        self.anim_local = ds["anim_point_local"].values.reshape(-1, 2)
        owners = np.concatenate([ds["point_body"].values, self.anim_body]).astype(int)
        self.spokes = [(b - 1, k) for k, b in enumerate(owners) if b > 0]
        joints = ds["joint_points"].values.reshape(-1, 2)
        self.springs = _pairs(ds["force_points"].values, ds["force_type"].values, SPRINGS)
        self.links = _pairs(joints, ds["joint_type"].values, LINKS)
        self.joint_points = np.unique(joints[joints > 0]) - 1
        self.window = tuple(ds.attrs.get(f"animation_{k}") for k in WINDOW)
        self.artists: dict[str, Artist] = {}

    def poses(self, index) -> Pose:
        """The pose at sample ``index`` (an int), or at each of the samples ``index`` (an array)."""
        centres, angles = self.ds["r"].isel(time=index).values, self.ds["p"].isel(time=index).values
        points = self.ds["rP"].isel(time=index).values
        anim = on_bodies(self.anim_body, self.anim_local, centres, angles)
        return Pose(centres, angles, np.concatenate([points, anim], axis=-2))

    def outline(self, body: int, pose: Pose) -> np.ndarray:
        """The world outline (m) of a rect (closed, 5 corners) or a line (2 ends) of ``body``
        (0-based): the shape's centre is the mass centre; a line runs from -(W, H)/2 to (W, H)/2
        (along xi when only W is given, along eta when only H is)."""
        w, h = self.size[body, :2] / 2
        corners = np.array([[-w, -h], [w, -h], [w, h], [-w, h], [-w, -h]] if self.shapes[body] == "rect" else [[-w, -h], [w, h]])
        return on_bodies(np.full(len(corners), body + 1), corners, pose.centres, pose.angles)

    def extent(self, pose: Pose) -> np.ndarray:
        """Points (m) that bound everything drawn at ``pose`` (one or several frames)."""
        parts = [pose.centres.reshape(-1, 2), pose.points.reshape(-1, 2)]
        for b, shape in enumerate(self.shapes):
            if shape == "circle":
                centres = pose.centres[..., b, :].reshape(-1, 2)
                parts += [centres - self.size[b, 2], centres + self.size[b, 2]]
            elif shape in ("rect", "line"):
                parts.append(self.outline(b, pose))
        return np.concatenate([p.reshape(-1, 2) for p in parts])

    def draw(self, ax: Axes, pose: Pose, limits: tuple[float, float, float, float] | None = None,
             extent: np.ndarray | None = None) -> list[Artist]:
        """Draw at ``pose`` on ``ax`` in ``limits`` (xmin, xmax, ymin, ymax; m), by default
        inAnimate's, around ``extent`` (default: the pose) where it sets none. The shapes are
        ``ax.patches`` (label ``body N``, gid the shape); the lines from the centres to their
        points (gid ``spokes``), the springs (``springs``) and the links (``links``) are line
        collections, the centres (``centres``) a scatter; the points (``points``) and the
        joints' points (``joints``) are ``ax.lines``; the labels ``(N)`` are texts."""
        for b, shape in enumerate(self.shapes):
            style = dict(SHAPE_STYLE, edgecolor=self.colors[b], label=f"body {b + 1}", gid=shape)
            if shape == "circle":
                self.artists[f"shape{b}"] = ax.add_patch(Circle(pose.centres[b], self.size[b, 2], **style))
            elif shape in ("rect", "line"):
                self.artists[f"shape{b}"] = ax.add_patch(Polygon(self.outline(b, pose), closed=shape == "rect", **style))
        spoke_colors = [self.colors[b] for b, _ in self.spokes]
        self.artists["spokes"] = ax.add_collection(LineCollection([], colors=spoke_colors, linewidths=1.0, gid="spokes"))
        self.artists["springs"] = ax.add_collection(LineCollection([], gid="springs", zorder=2.5, **SPRING_STYLE))
        self.artists["links"] = ax.add_collection(LineCollection([], gid="links", **LINK_STYLE))
        self.artists["points"] = ax.plot([], [], "o", color="k", markersize=2, gid="points", zorder=3)[0]
        self.artists["joints"] = ax.plot([], [], "o", color="k", markersize=5, gid="joints", zorder=3)[0]
        self.artists["centres"] = ax.scatter(*pose.centres.T, s=30, c=self.colors, edgecolors="k", gid="centres", zorder=4)
        for b in range(len(self.shapes)):
            self.artists[f"label{b}"] = ax.text(*pose.centres[b], f"  ({b + 1})", va="center", fontsize="small")
        frame_axes(ax, [self.extent(pose) if extent is None else extent], limits=limits)
        if limits is None:
            ax.set_xlim(*self.window[:2])
            ax.set_ylim(*self.window[2:])
        ax.grid(True, linewidth=0.5, alpha=0.5)
        return self.update(pose)

    def update(self, pose: Pose) -> list[Artist]:
        """Move the drawing to ``pose``; the artists moved."""
        points = pose.points
        for b, shape in enumerate(self.shapes):
            if shape == "circle":
                self.artists[f"shape{b}"].set_center(pose.centres[b])
            elif shape in ("rect", "line"):
                self.artists[f"shape{b}"].set_xy(self.outline(b, pose))
            self.artists[f"label{b}"].set_position(pose.centres[b])
        self.artists["spokes"].set_segments([[pose.centres[b], points[k]] for b, k in self.spokes])
        self.artists["springs"].set_segments([points[[i, j]] for i, j in self.springs])
        self.artists["links"].set_segments([points[[i, j]] for i, j in self.links])
        self.artists["points"].set_data(points[:, 0], points[:, 1])
        self.artists["joints"].set_data(points[self.joint_points, 0], points[self.joint_points, 1])
        self.artists["centres"].set_offsets(pose.centres)
        return list(self.artists.values())


def _pairs(points: np.ndarray, types: np.ndarray, kinds: tuple[str, ...]) -> list[tuple[int, int]]:
    """0-based (i, j) point pairs of the elements of one of ``kinds`` with both points."""
    return [(int(i) - 1, int(j) - 1) for (i, j), t in zip(points.reshape(-1, 2), types) if str(t) in kinds and i > 0 and j > 0]
