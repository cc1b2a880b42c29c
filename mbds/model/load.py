"""Loading a model: files -> checked, assembled :class:`Model` -> compiled functions."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mbds.errors import ModelError
from mbds.expr import symbols as S
from mbds.expr.codegen import CompiledModel, ModelExpressions, compile_model
from mbds.io.contacts import ContactLaw
from mbds.io.coordinates import CoordinateName, parse_coordinate_name
from mbds.io.folder import ModelFiles, read_model_files
from mbds.io.ini import Located, split_list
from mbds.io.watches import CommonOptions
from mbds.io.world import WorldSettings
from mbds.model.bodies import GENERALIZED, POSE, Body, assemble_bodies
from mbds.model.checks import check_laws, check_mass_matrix
from mbds.model.contacts import ContactPair, assemble_contacts
from mbds.model.equations import ExpressionReader, Parameters, gather_expressions
from mbds.model.system import StepSettings, SystemSource, WatchOptions
from mbds.model.watches import Watch, assemble_watches


@dataclass
class Model:
    """A checked model: bodies, coordinates, contacts, watches, expressions and parameters.

    ``q0``/``qd0`` are the start values of the generalized coordinates (m, rad; m/s, rad/s):
    a body coordinate starts at its ``.bdy`` start value, a free ``g'`` coordinate at 0.
    ``break_time`` is in s. ``source`` names the files it was read from, ``settings`` and
    ``watch_options`` are the world's and the watches file's settings (SI units): nothing
    below this front-end reads the files themselves. ``compiled`` holds the numba functions
    once :meth:`compile` ran.
    """

    source: SystemSource
    settings: StepSettings
    watch_options: WatchOptions
    version: int
    bodies: list[Body]
    coordinates: list[CoordinateName]
    dependent: list[CoordinateName]
    pairs: list[ContactPair]
    laws: list[ContactLaw]
    watches: list[Watch]
    expressions: ModelExpressions
    parameters: Parameters
    break_time: float
    q0: np.ndarray
    qd0: np.ndarray
    compiled: CompiledModel | None = field(default=None, repr=False)

    @property
    def world_path(self) -> Path:
        return self.source.path

    @property
    def name(self) -> str:
        return self.source.name

    def compile(self, cache_dir: str | Path | None = None) -> CompiledModel:
        """Compile (or load from the disk cache) the model's numba functions."""
        if self.compiled is None:
            self.compiled = compile_model(self.expressions, Path(cache_dir) if cache_dir else None)
        return self.compiled


def load_model(path: str | Path, *, version: int = 0, compile: bool = True, cache_dir=None) -> Model:
    """Read, check and assemble the model of a folder or ``.wld`` file; compile it unless told
    not to. ``version`` selects the ``[body:k]`` watch sections. Raises :class:`ModelError`."""
    files = read_model_files(path)
    model = assemble_model(files, version)
    check_mass_matrix(model.expressions, model.parameters, model.q0, files.mass_matrix.path)
    if compile:
        model.compile(cache_dir)
    return model


def assemble_model(files: ModelFiles, version: int = 0) -> Model:
    """A :class:`Model` from files already read."""
    bodies = assemble_bodies(files)
    pairs, laws = assemble_contacts(files, bodies)
    check_laws(laws, files)
    expressions, params = gather_expressions(files, bodies, laws)
    watches = assemble_watches(files, bodies, version)
    q0, qd0 = _start_state(files, bodies)
    duration = break_time(files, files.world.path, bodies)
    return Model(
        source=SystemSource(files.world.path.stem, files.world.path, tuple(files.paths()), tuple(files.missing)),
        settings=step_settings(files.world.settings),
        watch_options=watch_options(files.watches.common),
        version=version,
        bodies=bodies,
        coordinates=list(files.coordinates.coordinates),
        dependent=[c.coordinate for c in files.dependent.coordinates],
        pairs=pairs,
        laws=laws,
        watches=watches,
        expressions=expressions,
        parameters=params,
        break_time=duration,
        q0=q0,
        qd0=qd0,
    )


def step_settings(world: WorldSettings) -> StepSettings:
    """The stepper's settings from a world file's ``[main]``."""
    interval = world.history_multiple_of_maximum_timestep * world.maximum_timestep
    return _same_named(StepSettings, world, sample_interval=interval)


def watch_options(common: CommonOptions) -> WatchOptions:
    """The watch output options of a watches file's ``[common]``."""
    return _same_named(WatchOptions, common)


def _same_named(cls, record, **derived):
    """An instance of the dataclass ``cls`` from the fields of ``record`` of the same names, and
    the ``derived`` values."""
    names = [f.name for f in dataclasses.fields(cls) if f.name not in derived]
    return cls(**{name: getattr(record, name) for name in names}, **derived)


def _start_state(files: ModelFiles, bodies: list[Body]) -> tuple[np.ndarray, np.ndarray]:
    n = len(files.coordinates.coordinates)
    q0, qd0 = np.zeros(n), np.zeros(n)
    for body in bodies:
        for axis in range(len(POSE)):
            if body.binding[axis] == GENERALIZED:
                k = body.binding_index[axis]
                q0[k] = body.start_position[axis]
                qd0[k] = body.start_velocity[axis]
    _generalized_start(files, bodies, q0, qd0)
    return q0, qd0


def _generalized_start(files: ModelFiles, bodies: list[Body], q0: np.ndarray, qd0: np.ndarray) -> None:
    """Start values of free coordinates from the world's ``[generalizedStart]`` section."""
    world = files.world
    index = {c.name: k for k, c in enumerate(files.coordinates.coordinates) if c.kind == "g"}
    reader = ExpressionReader(files, bodies)
    values = {S.constant(name): v for name, v in files.constants.values.items()}
    for key, item in world.generalized_start:
        name = parse_coordinate_name(key, world.path, item.line)
        if name.kind != "g" or name.name not in index:
            raise ModelError(f"{key} is not a free coordinate g'name of the .gc file", world.path, item.line)
        parts = split_list(item.text, files.separator)
        if not 1 <= len(parts) <= 2 or not all(parts):
            raise ModelError(f"{key} needs 'position' or 'position, velocity'", world.path, item.line)
        numbers = []
        for part in parts:
            expr = reader.read(Located(part, item.line), world.path, constant_only=True)
            number = float(expr.subs(values).evalf())
            if not np.isfinite(number):
                raise ModelError(f"the start value '{part}' of {key} is not a finite number", world.path, item.line)
            numbers.append(number)
        q0[index[name.name]] = numbers[0]
        qd0[index[name.name]] = numbers[1] if len(numbers) > 1 else 0.0


def break_time(files: ModelFiles, path, bodies: list[Body] = ()) -> float:
    """The world's ``breakTime`` (s), a positive number; ModelError at its line of ``path``."""
    item = files.world.settings.break_time
    expr = ExpressionReader(files, list(bodies)).read(item, path, constant_only=True)
    values = {S.constant(name): v for name, v in files.constants.values.items()}
    try:
        value = float(expr.subs(values).evalf())
    except (TypeError, ValueError):
        value = float("nan")
    if not np.isfinite(value) or value <= 0:
        raise ModelError(f"breakTime must be a positive time, is {value}", path, item.line)
    return value
