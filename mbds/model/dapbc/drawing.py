"""What a drawing of a DAP_BC run needs, as plain arrays for the variables and attributes of its history: inAnimate's
shapes, colours, extra points and window, and where the points, joints and forces sit
(docs/dapbc.md, "Drawing"). ``mbds.plot`` draws the bodies from these and the run's r, p, rP."""

from __future__ import annotations

import numpy as np

from mbds.io.dapbc.fields import COLORS
from mbds.io.dapbc.records import DapbcModel, Point

ENDS = ("i", "j")
WINDOW = ("xmin", "xmax", "ymin", "ymax")


def _points(dim: str, points: list[Point], what: str) -> dict:
    body, local = f"{dim}_body", f"{dim}_local"
    return {
        body: ((dim,), np.array([p.Bindex for p in points], dtype=np.int32),
               {"long_name": f"body of the {what} (Bindex; 0: the ground)"}),
        local: ((dim, "axis"), np.array([p.sPlocal for p in points], dtype=float).reshape(-1, 2),
                {"long_name": f"body-frame coordinates of the {what} (sPlocal)", "units": "m"}),
    }


def _pairs(dim: str, elements, what: str) -> dict:
    return {
        f"{dim}_type": ((dim,), np.array([e.type for e in elements], dtype=object), {"long_name": f"{what} type"}),
        f"{dim}_points": ((dim, "end"), np.array([[e.iPindex, e.jPindex] for e in elements], dtype=np.int32).reshape(-1, 2),
                          {"long_name": f"points of the {what} (iPindex, jPindex; 0: none)"}),
    }


def drawing_variables(model: DapbcModel) -> tuple[dict, dict, dict]:
    """(data variables, coordinates, attributes) describing ``model`` for drawing: per body its
    inAnimate shape (``rect``, ``circle``, ``line`` or ``none``), width, height and radius (m)
    and colour (RGB hex); every point's body and body-frame position, the same for inAnimate's
    ``Points_anim`` (dimension ``anim_point``); each joint's and force's type and points; and the
    window ``animation_xmin`` ... ``animation_ymax`` (m) where inAnimate sets it."""
    bodies = model.bodies
    data = {
        "body_shape": (("body",), np.array([b.shape.strip() or "none" for b in bodies], dtype=object),
                       {"long_name": "inAnimate shape of the body (rect, circle, line or none)"}),
        "body_width": (("body",), np.array([b.W for b in bodies], dtype=float),
                       {"long_name": "width of the rectangle, or length of a line along xi (W)", "units": "m"}),
        "body_height": (("body",), np.array([b.H for b in bodies], dtype=float),
                        {"long_name": "height of the rectangle, or length of a line along eta (H)", "units": "m"}),
        "body_radius": (("body",), np.array([b.R for b in bodies], dtype=float),
                        {"long_name": "radius of the circle (R)", "units": "m"}),
        "body_color": (("body",), np.array([COLORS[b.color] for b in bodies], dtype=object),
                       {"long_name": "colour of the body's lines (RGB hex code of inAnimate's color)"}),
        **_points("point", model.points, "point"),
        **_points("anim_point", model.points_anim, "inAnimate point (Points_anim)"),
        **_pairs("joint", model.joints, "joint"),
        **_pairs("force", model.forces, "force element"),
    }
    coords = {
        "anim_point": ("anim_point", np.arange(1, len(model.points_anim) + 1, dtype=np.int32),
                       {"long_name": "index of the inAnimate point (Points_anim)"}),
        "joint": ("joint", np.arange(1, len(model.joints) + 1, dtype=np.int32), {"long_name": "joint index (inJoints)"}),
        "force": ("force", np.arange(1, len(model.forces) + 1, dtype=np.int32), {"long_name": "force index (inForces)"}),
        "end": ("end", np.array(ENDS, dtype=object), {"long_name": "end of a joint or force element (body i or j)"}),
    }
    window = {f"animation_{k}": getattr(model.window, k) for k in WINDOW if getattr(model.window, k) is not None}
    return data, coords, window
