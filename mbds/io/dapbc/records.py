"""The elements of a DAP_BC model folder, with the field names and defaults of the DAP_BC
manual's Tables B.1-B.8.

Every record keeps the manual's field names as attribute names (``m``, ``J``, ``r``,
``sPlocal``, ``iPindex``, ``L0``, ``iFunct``, ...).  Two-vectors are numpy arrays of shape
(2,).  Indices are 1-based as in the in-files; 0 means the ground (bodies) or "none"
(points, unit vectors, functions).  Units are whatever the model's in-files use; with the
default gravitational constant 9.81 the manual assumes SI (m, kg, s, rad, N).

Each element remembers where it was made (``source``) and where each of its fields was
last assigned (``field_sources``), so that checks further down can say ``file:line``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class SourcePos:
    """A place in an in-file: file path and 1-based line."""

    file: str
    line: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}"


def _vec(x: float, y: float):
    return field(default_factory=lambda: np.array([x, y], dtype=float))


@dataclass(eq=False)
class Element:
    """Common part of every record: where it was made and where each field was set."""

    source: SourcePos | None = field(default=None, repr=False, kw_only=True)
    field_sources: dict[str, SourcePos] = field(default_factory=dict, repr=False, kw_only=True)

    @classmethod
    def field_names(cls) -> tuple[str, ...]:
        """The manual's fields of this record (not the bookkeeping ones)."""
        return tuple(f.name for f in dataclasses.fields(cls) if f.name not in ("source", "field_sources"))

    def where(self, name: str | None = None) -> SourcePos | None:
        """Where field ``name`` was set (else where the element was made)."""
        if name is not None and name in self.field_sources:
            return self.field_sources[name]
        return self.source

    def copy(self):
        """A deep copy (arrays and source maps are not shared)."""
        values = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        values = {k: (v.copy() if isinstance(v, (np.ndarray, dict)) else v) for k, v in values.items()}
        return type(self)(**values)


@dataclass(eq=False)
class Body(Element):
    """Table B.1 (mass, inertia, initial coordinates and velocities) and B.7 (animation shape)."""

    m: float = 1.0  # mass
    J: float = 1.0  # moment of inertia about the mass centre
    r: np.ndarray = _vec(0.0, 0.0)  # x and y coordinates of the mass centre
    p: float = 0.0  # angle phi (rad)
    r_d: np.ndarray = _vec(0.0, 0.0)  # time derivative of x and y
    p_d: float = 0.0  # time derivative of phi
    shape: str = " "  # 'circle', 'rect', 'line' (blank: none)
    R: float = 1.0  # radius of the circle
    W: float = 0.0  # width of the rectangle (or length of a line along xi)
    H: float = 0.0  # height of the rectangle (or length of a line along eta)
    color: str = "k"  # MATLAB colour abbreviation


@dataclass(eq=False)
class Point(Element):
    """Table B.2: a body-fixed point."""

    Bindex: int = 0  # body index (0: ground)
    sPlocal: np.ndarray = _vec(0.0, 0.0)  # body-fixed (local) coordinates


@dataclass(eq=False)
class Uvector(Element):
    """Table B.3: a body-fixed unit vector."""

    Bindex: int = 0  # body index (0: ground)
    ulocal: np.ndarray = _vec(1.0, 0.0)  # body-fixed (local) components


@dataclass(eq=False)
class Force(Element):
    """Table B.4: a force element (``ptp``, ``rot-sda``, ``weight``, ``flocal``, ``f``, ``T``, ``user``)."""

    type: str = "ptp"  # element type
    iPindex: int = 0  # index of the point on body (i)
    jPindex: int = 0  # index of the point on body (j)
    iBindex: int = 0  # index of body (i)
    jBindex: int = 0  # index of body (j)
    k: float = 0.0  # spring stiffness
    L0: float = 0.0  # undeformed length
    theta0: float = 0.0  # undeformed angle
    dc: float = 0.0  # damping coefficient
    f_a: float = 0.0  # constant actuator force
    T_a: float = 0.0  # constant actuator torque
    gravity: float = 9.81  # gravitational constant
    wgt: np.ndarray = _vec(0.0, -1.0)  # gravitational direction
    flocal: np.ndarray = _vec(0.0, 0.0)  # constant force in the body-fixed frame
    f: np.ndarray = _vec(0.0, 0.0)  # constant force in the x-y frame
    T: float = 0.0  # constant torque
    iFunct: int = 0  # analytical function index


@dataclass(eq=False)
class Joint(Element):
    """Table B.5: a kinematic joint or driver (``rev``, ``tran``, ``rev-rev``, ``rev-tran``,
    ``rigid``, ``disc``, ``rel-rot``, ``rel-tran``)."""

    type: str = "rev"  # joint type
    iBindex: int = 0  # body index i
    jBindex: int = 0  # body index j
    iPindex: int = 0  # point Pi index
    jPindex: int = 0  # point Pj index
    iUindex: int = 0  # unit vector u_i index
    jUindex: int = 0  # unit vector u_j index
    iFunct: int = 0  # function index
    L: float = 0.0  # constant length
    R: float = 1.0  # constant radius
    x0: float = 0.0  # initial condition for a disc
    p0: float = 0.0  # initial condition for a disc or rigid


@dataclass(eq=False)
class Funct(Element):
    """Table B.6: an analytical function f(t) of type ``a`` (Eq. 8.1), ``b`` (8.2) or ``c`` (8.3)."""

    type: str = "a"  # function type a, b or c
    t_start: float = 0.0  # required for functions b, c
    f_start: float = 0.0  # required for functions b, c
    t_end: float = 1.0  # required for functions b, c
    f_end: float = 1.0  # required for function b
    dfdt_end: float = 1.0  # required for function c
    ncoeff: int = 3  # number of coefficients
    coeff: np.ndarray = field(default_factory=lambda: np.zeros(0))  # required for function a


#: The constructor name of each record in the in-files (``B1 = Body_struct;``).
CONSTRUCTORS: dict[str, type[Element]] = {
    "Body_struct": Body,
    "Point_struct": Point,
    "Unit_struct": Uvector,
    "Force_struct": Force,
    "Joint_struct": Joint,
    "Funct_struct": Funct,
}


@dataclass(frozen=True)
class PlotWindow:
    """inAnimate's axis limits of the animation window (model length units; None: not set)."""

    xmin: float | None = None
    xmax: float | None = None
    ymin: float | None = None
    ymax: float | None = None


@dataclass(eq=False)
class DapbcModel:
    """A DAP_BC model folder as read: the element lists in file order (list position i holds
    the element of 1-based index i+1), the animation data, and where everything came from."""

    folder: Path
    bodies: list[Body] = field(default_factory=list)
    points: list[Point] = field(default_factory=list)
    uvectors: list[Uvector] = field(default_factory=list)
    forces: list[Force] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    functs: list[Funct] = field(default_factory=list)
    points_anim: list[Point] = field(default_factory=list)  # inAnimate's extra drawing points
    window: PlotWindow = field(default_factory=PlotWindow)
    files: dict[str, Path] = field(default_factory=dict)  # in-file role ('inBodies', ...) -> path
    user_force_file: Path | None = None  # user_force.m, when the folder has one
    user_force_py: Path | None = None  # user_force.py, when the folder has one

    @property
    def nB(self) -> int:
        """Number of moving bodies."""
        return len(self.bodies)

    def where(self, kind: str, index: int, name: str | None = None) -> SourcePos | None:
        """Where element ``index`` (1-based) of list ``kind`` ('bodies', 'points', ...) was made,
        or where its field ``name`` was set."""
        return getattr(self, kind)[index - 1].where(name)
