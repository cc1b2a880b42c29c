"""The bodies at one time (``shapes``) and the whole run as an animation (``animate``)."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes

from mbds.errors import ModelError
from mbds.plot.bodies import BodyOutlines, frame_axes
from mbds.plot.dapbc_bodies import DapbcBodies
from mbds.plot.figure import new_axes
from mbds.plot.source import run_kind, run_title


def sample_at(ds: xr.Dataset, time: float | None) -> int:
    """Index of the sample nearest ``time`` (s); the last sample when None."""
    times = ds["time"].values
    if time is None:
        return len(times) - 1
    if not times[0] - 1e-12 <= time <= times[-1] + 1e-12:
        raise ModelError(f"time {time} s is outside the run ({times[0]:g} to {times[-1]:g} s)")
    return int(np.abs(times - time).argmin())


def shapes(run: xr.Dataset, time: float | None = None, ax: Axes | None = None,
           limits: tuple[float, float, float, float] | None = None) -> Axes:
    """The bodies in their world pose at the sample nearest ``time`` (s; default: the run's end):
    moving bodies filled in their RGBColor, fixed bodies hatched, virtual bodies dashed. The
    polygons are ``ax.patches`` (label: body name, gid: kind). ``limits``: (xmin, xmax, ymin,
    ymax) in m; by default around the moving bodies. A dap_bc run is drawn as DAP_BC's anim
    draws it (:meth:`mbds.plot.dapbc_bodies.DapbcBodies.draw`), by default in inAnimate's
    limits. Returns the axes."""
    ax = ax or new_axes()
    index = sample_at(run, time)
    if run_kind(run) == "dap_bc":
        drawer = DapbcBodies(run)
        drawer.draw(ax, drawer.poses(index), limits)
    else:
        drawer = BodyOutlines(run)
        patches = drawer.draw(ax, drawer.poses(index))
        polygons = [p.get_xy() for p in patches]
        frame_axes(ax, polygons, around=drawer.moving(polygons), limits=limits)
    ax.set_title(f"{run_title(run)}, t = {float(run['time'][index]):.4g} s")
    return ax


def frame_samples(ds: xr.Dataset, fps: float, speed: float) -> np.ndarray:
    """Indices of the samples shown at ``fps`` frames per second of video when ``speed`` s of
    the run pass per second of video (the sample nearest each frame's time)."""
    if not fps > 0 or not speed > 0:
        raise ModelError("fps and speed must be positive")
    times = ds["time"].values
    wanted = np.arange(times[0], times[-1] + 1e-12, speed / fps)
    index = np.clip(np.searchsorted(times, wanted), 0, len(times) - 1)
    earlier = np.clip(index - 1, 0, None)
    closer = np.abs(times[earlier] - wanted) <= np.abs(times[index] - wanted)
    return np.unique(np.where(closer, earlier, index))


def animate(run: xr.Dataset, fps: float = 30, speed: float = 1.0, contacts: bool = True, ax: Axes | None = None,
            scale: float | None = None, limits: tuple[float, float, float, float] | None = None) -> FuncAnimation:
    """The run as a ``FuncAnimation``: frames at ``fps`` per second of video, ``speed`` s of the
    run per second of video, a time label, and (``contacts``) each watch's point marked and its
    impulse since the last frame drawn as an arrow (``scale`` m per N s; default: the largest
    arrow a fifth of the view); ``limits`` as for :func:`shapes`, by default around the moving
    bodies over the whole run (a dap_bc run: inAnimate's limits, as DAP_BC's anim). Save it with
    :func:`mbds.plot.save`."""
    ax = ax or new_axes()
    index = frame_samples(run, fps, speed)
    if run_kind(run) == "dap_bc":
        move = _dapbc_frames(ax, run, index, limits)
    else:
        move = _mbds_frames(ax, run, index, contacts, scale, limits)
    ax.set_title(run_title(run))
    clock = ax.text(0.02, 0.96, "", transform=ax.transAxes, va="top")
    times = run["time"].values[index]

    def update(frame: int):
        clock.set_text(f"t = {times[frame]:.3f} s")
        return move(frame) + [clock]

    update(0)
    ax.figure.draw_without_rendering()  # lay the figure out once, not at every frame
    ax.figure.set_layout_engine("none")
    return FuncAnimation(ax.figure, update, frames=len(index), interval=1000 / fps, blit=False)


def _mbds_frames(ax: Axes, run: xr.Dataset, index: np.ndarray, contacts: bool, scale: float | None,
                 limits: tuple[float, float, float, float] | None):
    """Draw an MBDS run's bodies (and watches) at the first of the samples ``index``; the
    function that moves them to a frame and returns the artists moved."""
    drawer = BodyOutlines(run)
    poses = drawer.poses(index)
    patches = drawer.draw(ax, poses[0])
    extent = [p for pose in poses[:: max(len(poses) // 50, 1)] for p in drawer.world(pose)] + drawer.world(poses[-1])
    frame_axes(ax, extent, around=drawer.moving(extent), limits=limits)
    arrows = _ContactArrows(ax, run, drawer, index, scale) if contacts and run.sizes.get("watch", 0) else None

    def move(frame: int) -> list:
        for patch, polygon in zip(patches, drawer.world(poses[frame])):
            patch.set_xy(polygon)
        return patches + (arrows.update(frame, poses[frame]) if arrows else [])

    return move


def _dapbc_frames(ax: Axes, run: xr.Dataset, index: np.ndarray, limits: tuple[float, float, float, float] | None):
    """Draw a dap_bc run at the first of the samples ``index`` (in inAnimate's limits, else
    around the whole run); the function that moves it to a frame."""
    drawer = DapbcBodies(run)
    poses = drawer.poses(index)
    drawer.draw(ax, poses.at(0), limits, extent=drawer.extent(poses))
    return lambda frame: drawer.update(poses.at(frame))


class _ContactArrows:
    """Watched points (markers) and their impulses (N s, x-y frame) summed over each frame's
    samples, drawn as arrows."""

    def __init__(self, ax: Axes, ds: xr.Dataset, drawer: BodyOutlines, index: np.ndarray, scale: float | None):
        bodies = [drawer.names.index(str(b)) for b in ds["watch_body"].values]
        first, last = ds["watch_first_point"].values, ds["watch_last_point"].values
        self.body = np.array(bodies)
        self.local = np.array([drawer.local[b][f : l + 1].mean(0) for b, f, l in zip(bodies, first, last)])
        edges = np.concatenate([[0], index[:-1] + 1])
        x, y = (np.add.reduceat(ds[n].values, edges, axis=0) for n in ("impulse_x", "impulse_y"))
        self.impulse = np.stack([x, y], -1)  # frames, watches, 2
        size = float(np.abs(ax.get_xlim()[1] - ax.get_xlim()[0]))
        largest = float(np.linalg.norm(self.impulse, axis=-1).max(initial=0))
        self.scale = scale if scale is not None else (0.2 * size / largest if largest > 0 else 0.0)
        self.points = ax.plot([], [], "o", color="red", markersize=3, label="watched points")[0]
        self.arrows = ax.quiver(np.zeros(len(bodies)), np.zeros(len(bodies)), np.zeros(len(bodies)),
                                np.zeros(len(bodies)), color="red", angles="xy", scale_units="xy", scale=1, width=0.004)

    def update(self, frame: int, pose: np.ndarray):
        x, y, angle = pose[self.body].T
        c, s = np.cos(angle), np.sin(angle)
        px = x + c * self.local[:, 0] - s * self.local[:, 1]
        py = y + s * self.local[:, 0] + c * self.local[:, 1]
        self.points.set_data(px, py)
        self.arrows.set_offsets(np.column_stack([px, py]))
        self.arrows.set_UVC(*(self.scale * self.impulse[frame].T))
        return [self.points, self.arrows]
