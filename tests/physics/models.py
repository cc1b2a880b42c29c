"""Small MBDS model folders for the physics tests, written as plain model files.

Every model here has one structure: a free rigid body ``body`` (generalized x, y, Rz) above
a fixed floor ``floor`` whose top face is the line y = 0 (x from -FLOOR_HALF_WIDTH to
+FLOOR_HALF_WIDTH). Gravity is the vector (c'gx, c'gy) (m/s²), the contact has friction c'mu
and normal restitution c'e. Shapes, masses, start states and world settings are data, not
code, so every model of this module shares one compiled stepper: tests vary them freely.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mbds.data.run_result import RunResult
from mbds.model.load import load_model
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import simulate

CAMPAIGNS = Path(__file__).resolve().parents[2] / "campaigns"
"""The example models."""

FLOOR_HALF_WIDTH = 5.0
"""Half-width (m) of the floor's top face."""

FLOOR_DEPTH = 0.1
"""Thickness (m) of the floor block below y = 0."""


def regular_polygon(sides: int, radius: float) -> np.ndarray:
    """Counter-clockwise regular polygon (sides, 2) of circumradius ``radius`` (m) about the
    origin, with a vertex straight below the centre."""
    angles = -0.5 * np.pi + 2.0 * np.pi * np.arange(sides) / sides
    return radius * np.column_stack([np.cos(angles), np.sin(angles)])


def rectangle(width: float, height: float) -> np.ndarray:
    """Counter-clockwise rectangle (4, 2) of the given sizes (m) centred on the origin."""
    w, h = 0.5 * width, 0.5 * height
    return np.array([[-w, -h], [w, -h], [w, h], [-w, h]])


@dataclass
class BodyOnFloor:
    """A body over the floor: shape (k, 2) in the body frame (m, origin at the centroid), mass
    (kg), centroidal inertia (kg m²), start pose (x, y, Rz) and velocity (m, rad; m/s, rad/s),
    gravity (gx, gy) (m/s²), friction coefficient and normal restitution; world settings: time
    steps (s), maximum penetration (m), history interval (in maximum steps), break time (s) and
    ``maximumDisplacementFactor`` (the world file's default); ``force_x``: an expression (N) in
    time ``t`` added to the x row of the h-vector, a force through the centroid."""

    shape: np.ndarray
    mass: float
    inertia: float
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    gravity: tuple[float, float] = (0.0, -9.81)
    friction: float = 0.0
    restitution: float = 0.0
    dt_min: float = 1e-10
    dt_max: float = 1e-4
    max_penetration: float = 1e-7
    history_every: int = 1
    history_each_step: bool = False
    break_time: float = 1.0
    displacement_factor: float = 0.5
    extra: dict[str, str] = field(default_factory=dict)
    force_x: str = ""

    def write(self, folder: Path) -> Path:
        """Write the model files into ``folder`` (created); return the folder."""
        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        files = {
            "model.wld": _ini({
                "main": {
                    "numberOfGeneralizedCoordinates": "3",
                    "minimumTimestep": _num(self.dt_min),
                    "maximumTimestep": _num(self.dt_max),
                    "maximumPenetration": _num(self.max_penetration),
                    "writeToHistoryMultipleOfMaximumTimestep": str(self.history_every),
                    "writeToHistoryEachTimeStep": "1" if self.history_each_step else "0",
                    "breakTime": _num(self.break_time),
                    "maximumDisplacementFactor": _num(self.displacement_factor),
                    **self.extra,
                },
                "bodies": {"body1": "body.bdy", "body2": "floor.bdy"},
            }),
            "body.bdy": _body("body", self.position, self.velocity, {"mass": self.mass, "InertiaZZ": self.inertia}),
            "body.exs": _shape(self.shape),
            "floor.bdy": _body("floor", (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), {"mass": 1.0, "InertiaZZ": 1.0}),
            "floor.exs": _shape(np.array([[FLOOR_HALF_WIDTH, 0.0], [-FLOOR_HALF_WIDTH, 0.0],
                                          [-FLOOR_HALF_WIDTH, -FLOOR_DEPTH], [FLOOR_HALF_WIDTH, -FLOOR_DEPTH]])),
            "model.gc": "b'body'x[t]\nb'body'y[t]\nb'body'Rz[t]\n",
            "model.mmx": "b'body'm\t0\t0\n0\tb'body'm\t0\n0\t0\tb'body'Jzz\n",
            "model.hv": f"b'body'm*c'gx{'+' + self.force_x if self.force_x else ''}\nb'body'm*c'gy\n0\n",
            "model.me": (
                "(b'body'm*(Derivative[1][b'body'x][t]^2+Derivative[1][b'body'y][t]^2)"
                "+b'body'Jzz*Derivative[1][b'body'Rz][t]^2)/2"
                "-b'body'm*(c'gx*b'body'x[t]+c'gy*b'body'y[t])\n"
            ),
            "model.cns": (
                f"c'gx = {_num(self.gravity[0])}\nc'gy = {_num(self.gravity[1])}\n"
                f"c'mu = {_num(self.friction)}\nc'e = {_num(self.restitution)}\n"
            ),
            "model.cop": _ini({"body-floor": {
                "friction": "c'mu", "restitutionNormal": "c'e", "restitutionTangent": "0", "parameterNi": "0",
            }}),
            "model.wtc": _ini({"body": {"contactWatch": "all"}}),
        }
        for name, text in files.items():
            (folder / name).write_text(text)
        return folder


def _num(value: float) -> str:
    return repr(float(value))


def _ini(sections: dict[str, dict[str, str]]) -> str:
    lines = []
    for name, entries in sections.items():
        lines.append(f"[{name}]")
        lines.extend(f"{key} = {value}" for key, value in entries.items())
    return "\n".join(lines) + "\n"


def _body(name: str, position, velocity, mass_properties: dict[str, float]) -> str:
    axes = ("x", "y", "Rz")
    return _ini({
        "main": {"name": name, "shapeType": "extrusionSolid", "shapeFile": f"{name}.exs", "correctOrigin": "0"},
        "Mass properties": {key: _num(value) for key, value in mass_properties.items()},
        "startPosition": {axis: _num(value) for axis, value in zip(axes, position)},
        "startVelocity": {axis: _num(value) for axis, value in zip(axes, velocity)},
    })


def _shape(points: np.ndarray) -> str:
    closed = np.vstack([points, points[:1]])
    rows = "\n".join(f"{x!r} {y!r}" for x, y in closed.tolist())
    return f"points = {len(closed)}\n%%data\n{rows}\n%%enddata\n"


def run_folder(folder: Path, break_time: float | None = None, **settings) -> RunResult:
    """Load the model in ``folder`` and run it to ``break_time`` (s; default: the model's);
    ``settings`` go to :class:`RunSettings` (seed, lexico_range)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # model warnings (an origin off the centroid) are not tested here
        model = load_model(folder)
    return simulate(model, RunSettings(break_time=break_time or model.break_time, **settings))


def energy_residual(result: RunResult) -> np.ndarray:
    """E_me(0) - E_me(t) - lost(t) + drive(t) at every sample (J): zero when the mechanical
    energy, the lost work and the work of rheonomic drivers balance."""
    return result.energy[0] - result.energy - result.lost + result.drive


def add_fixed_body(folder: Path, name: str, shape: np.ndarray) -> None:
    """Add a body that never moves (no coordinates), of ``shape`` (k, 2) in world coordinates
    (m), to the model in ``folder``; its pairs are the model's ``.cop`` sections that name it."""
    (folder / f"{name}.bdy").write_text(_body(name, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), {"mass": 1.0, "InertiaZZ": 1.0}))
    (folder / f"{name}.exs").write_text(_shape(shape))
    world = folder / "model.wld"
    count = world.read_text().count(".bdy")
    world.write_text(world.read_text().rstrip("\n") + f"\nbody{count + 1} = {name}.bdy\n")


@dataclass
class FreeBody:
    """A free rigid body (generalized x, y, Rz): name, shape (k, 2) in the body frame (m, origin
    at the centroid), mass (kg), centroidal inertia (kg m²), start pose and velocity."""

    name: str
    shape: np.ndarray
    mass: float
    inertia: float
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)


def write_free_bodies(folder: Path, bodies: list[FreeBody], pairs: list[tuple[str, str]], *, floor: bool,
                      gravity: float, friction: float, restitution: float, dt_max: float, max_penetration: float,
                      break_time: float, world: dict[str, str] | None = None) -> Path:
    """Write a model of free bodies under gravity (0, -gravity) (m/s²), with the fixed floor
    (named ``floor``) when asked; the contact pairs (body names) have friction c'mu and normal
    restitution c'e; history every 10 maximum steps; ``world``: more keys of the world file's
    [main]. Models with the same bodies, pairs and floor share one compiled stepper."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names = [body.name for body in bodies]
    n = 3 * len(names)
    files = {}
    if floor:
        files["floor.bdy"] = _body("floor", (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), {"mass": 1.0, "InertiaZZ": 1.0})
        files["floor.exs"] = _shape(np.array([[FLOOR_HALF_WIDTH, 0.0], [-FLOOR_HALF_WIDTH, 0.0],
                                              [-FLOOR_HALF_WIDTH, -FLOOR_DEPTH], [FLOOR_HALF_WIDTH, -FLOOR_DEPTH]]))
    diagonal, hv, kinetic, potential = [], [], [], []
    for body in bodies:
        files[f"{body.name}.bdy"] = _body(body.name, body.position, body.velocity,
                                          {"mass": body.mass, "InertiaZZ": body.inertia})
        files[f"{body.name}.exs"] = _shape(body.shape)
        b = f"b'{body.name}'"
        diagonal += [f"{b}m", f"{b}m", f"{b}Jzz"]
        hv += ["0", f"-{b}m*c'g", "0"]
        kinetic.append(f"{b}m*(Derivative[1][{b}x][t]^2+Derivative[1][{b}y][t]^2)"
                       f"+{b}Jzz*Derivative[1][{b}Rz][t]^2")
        potential.append(f"{b}m*c'g*{b}y[t]")
    contact = {"friction": "c'mu", "restitutionNormal": "c'e", "restitutionTangent": "0", "parameterNi": "0"}
    files.update({
        "model.wld": _ini({
            "main": {
                "numberOfGeneralizedCoordinates": str(n), "minimumTimestep": "1e-10",
                "maximumTimestep": _num(dt_max), "maximumPenetration": _num(max_penetration),
                "writeToHistoryMultipleOfMaximumTimestep": "10", "breakTime": _num(break_time),
                **(world or {}),
            },
            "bodies": {f"body{k + 1}": f"{name}.bdy" for k, name in enumerate(names + ["floor"] * floor)},
        }),
        "model.gc": "".join(f"b'{name}'{c}[t]\n" for name in names for c in ("x", "y", "Rz")),
        "model.mmx": "".join("\t".join(d if i == j else "0" for j in range(n)) + "\n"
                             for i, d in enumerate(diagonal)),
        "model.hv": "\n".join(hv) + "\n",
        "model.me": "(" + "+".join(kinetic) + ")/2+" + "+".join(potential) + "\n",
        "model.cns": f"c'g = {_num(gravity)}\nc'mu = {_num(friction)}\nc'e = {_num(restitution)}\n",
        "model.cop": _ini({f"{a}-{b}": contact for a, b in pairs}),
        "model.wtc": _ini({name: {"contactWatch": "all"} for name in names}),
    })
    for name, text in files.items():
        (folder / name).write_text(text)
    return folder


@dataclass
class BoxStack:
    """Boxes (width, height (m), mass (kg)) stacked on the floor, each resting centred on the one
    below, the first on the floor; friction c'mu and restitution c'e at every contact; world
    settings as in :class:`BodyOnFloor`. Every stack of the same number of boxes shares one
    compiled model."""

    boxes: list[tuple[float, float, float]]
    friction: float = 0.5
    restitution: float = 0.0
    dt_max: float = 1e-4
    max_penetration: float = 1e-8
    break_time: float = 1.0

    def write(self, folder: Path) -> Path:
        """Write the model files into ``folder`` (created); return the folder."""
        bodies, base = [], 0.0
        for k, (width, height, mass) in enumerate(self.boxes):
            bodies.append(FreeBody(f"box{k}", rectangle(width, height), mass, mass * (width**2 + height**2) / 12.0,
                                   position=(0.0, base + 0.5 * height, 0.0)))
            base += height
        names = [body.name for body in bodies]
        pairs = [(names[0], "floor")] + list(zip(names[1:], names[:-1]))
        return write_free_bodies(folder, bodies, pairs, floor=True, gravity=9.81, friction=self.friction,
                                 restitution=self.restitution, dt_max=self.dt_max,
                                 max_penetration=self.max_penetration, break_time=self.break_time)
