"""Loading a model: files -> checked, assembled :class:`Model` -> compiled functions.

A model whose record the compile cache holds (:mod:`mbds.model.known`: one loaded before with
the same files but its shapes) is assembled from that record and loads its compiled module
straight from the cache, without sympy; any other is assembled from its expressions, compiled,
and its record kept. Importing this module does not import sympy."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mbds.errors import ModelError
from mbds.expr.compiled import CompiledModel, cached_module
from mbds.io.contacts import ContactLaw
from mbds.io.coordinates import CoordinateName, parse_coordinate_name
from mbds.io.folder import ModelFiles, read_model_files
from mbds.io.ini import Located, split_list
from mbds.io.watches import CommonOptions
from mbds.io.world import WorldSettings
from mbds.model import known
from mbds.model.bodies import GENERALIZED, POSE, Body, assemble_bodies
from mbds.model.checks import check_compiled_mass_matrix, check_laws, check_mass_matrix
from mbds.model.contacts import ContactPair, assemble_contacts
from mbds.model.system import Parameters, StepSettings, SystemSource, WatchOptions
from mbds.model.watches import Watch, assemble_watches

if TYPE_CHECKING:  # sympy's: a model assembled from the cache's record has no expressions
    from mbds.expr.codegen import ModelExpressions


@dataclass
class Model:
    """A checked model: bodies, coordinates, contacts, watches, expressions and parameters.

    ``q0``/``qd0`` are the start values of the generalized coordinates (m, rad; m/s, rad/s):
    a body coordinate starts at its ``.bdy`` start value, a free ``g'`` coordinate at 0.
    ``break_time`` is in s. ``source`` names the files it was read from, ``settings`` and
    ``watch_options`` are the world's and the watches file's settings (SI units): nothing
    below this front-end reads the files themselves. ``compiled`` holds the numba functions
    once :meth:`compile` ran. A model assembled from the cache's record (:mod:`mbds.model.known`)
    has no ``expressions`` and no parameter names; its ``structure`` names its compiled module.
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
    expressions: ModelExpressions | None
    parameters: Parameters
    break_time: float
    q0: np.ndarray
    qd0: np.ndarray
    compiled: CompiledModel | None = field(default=None, repr=False)
    structure: str | None = field(default=None, repr=False)

    @property
    def world_path(self) -> Path:
        return self.source.path

    @property
    def name(self) -> str:
        return self.source.name

    def compile(self, cache_dir: str | Path | None = None) -> CompiledModel:
        """Compile (or load from the disk cache) the model's numba functions (a model assembled
        from the cache's record comes with them)."""
        if self.compiled is None:
            from mbds.expr.codegen import compile_model

            self.compiled = compile_model(self.expressions, Path(cache_dir) if cache_dir else None)
            self.structure = self.compiled.source_hash
        return self.compiled


def load_model(path: str | Path, *, version: int = 0, compile: bool = True, cache_dir=None,
               from_record: bool = False) -> Model:
    """Read, check and assemble the model of a folder or ``.wld`` file; compile it unless told
    not to. ``version`` selects the ``[body:k]`` watch sections. Compiled into the default
    cache, its record is kept there (:mod:`mbds.model.known`); ``from_record``: assemble it from
    that record when the cache holds one, without sympy (the model then has no ``expressions``
    and no parameter names; what runs use). Raises :class:`ModelError`."""
    return load_files(read_model_files(path), version, compile=compile, cache_dir=cache_dir, from_record=from_record)


def load_files(files: ModelFiles, version: int = 0, *, compile: bool = True, cache_dir=None,
               from_record: bool = False) -> Model:
    """:func:`load_model` of model files already read."""
    if from_record and compile and cache_dir is None:
        model = remembered_model(files, version)
        if model is not None:
            return model
    noted: list[str] = []
    model = _assembled(files, version, noted)
    with known.noting(noted):
        check_mass_matrix(model.expressions, model.parameters, model.q0, files.mass_matrix.path)
    if compile:
        model.compile(cache_dir)
        if cache_dir is None:
            known.remember(files, record(model, files, noted))
    return model


def record(model: Model, files: ModelFiles, noted: list[str]) -> known.Record:
    """The record of ``model`` of ``files`` (its ``structure`` known) and the warnings its
    expressions gave (``noted``)."""
    lifted = model.parameters.values[len(known.base_parameters(files, model.bodies)):]
    return known.Record(model.structure, known.floats(lifted), known.floats(model.q0), known.floats(model.qd0),
                        float(model.break_time), tuple(noted))


def find_structure(files: ModelFiles) -> str:
    """The structure of the model of ``files`` (as read from its folder): the hash of its
    generated code, with sympy; the model's record is kept in the cache when it passes its checks."""
    from mbds.expr.cache import source_hash
    from mbds.expr.codegen import generate_source

    noted: list[str] = []
    model = _assembled(files, 0, noted)
    model.structure = source_hash(generate_source(model.expressions))
    try:
        with known.noting(noted):
            check_mass_matrix(model.expressions, model.parameters, model.q0, files.mass_matrix.path)
    except ModelError:  # the runs will say so
        return model.structure
    known.remember(files, record(model, files, noted))
    return model.structure


def check_model(files: ModelFiles, version: int = 0, texts: dict[str, str] | None = None) -> None:
    """ModelError for bad input in the model of ``files`` (``texts``: files written over the
    folder's, see :func:`mbds.model.known.model_digest`); without sympy when the cache holds
    the record of these files, which passed the checks of their expressions."""
    if known.remembered(files, texts) is None:
        assemble_model(files, version)
        return
    bodies = assemble_bodies(files)
    assemble_contacts(files, bodies)
    assemble_watches(files, bodies, version)


def model_break_time(path: str | Path) -> float:
    """The break time (s) of the model of a folder or ``.wld`` file: from the cache's record of
    its files when there is one, else from its world file (the model assembled and checked)."""
    files = read_model_files(path)
    remembered = known.remembered(files)
    return remembered.break_time if remembered is not None else load_files(files, compile=False).break_time


def remembered_model(files: ModelFiles, version: int = 0, texts: dict[str, str] | None = None) -> Model | None:
    """The model of ``files`` (``texts``: see :func:`check_model`), compiled, assembled from the
    cache's record of these files without sympy; None when the cache holds no record of them or
    not their compiled module."""
    remembered = known.remembered(files, texts)
    if remembered is None:
        return None
    compiled = cached_module(remembered.structure)
    if compiled is None:
        return None
    bodies = assemble_bodies(files)
    pairs, laws = assemble_contacts(files, bodies)
    values = np.array([*known.base_parameters(files, bodies), *remembered.law_numbers], dtype=float)
    if len(values) != compiled.n_parameters or len(remembered.q0) != compiled.n:
        return None
    known.issue(remembered.warnings)
    model = _model(files, version, bodies, pairs, laws, None, Parameters([], values, len(files.constants.values)),
                   (np.array(remembered.q0), np.array(remembered.qd0)), remembered.break_time)
    model.compiled, model.structure = compiled, remembered.structure
    check_compiled_mass_matrix(compiled, model.parameters.values, model.q0, files.mass_matrix.path)
    return model


def assemble_model(files: ModelFiles, version: int = 0) -> Model:
    """A :class:`Model` from files already read, assembled from its expressions (with sympy)."""
    return _assembled(files, version, [])


def _assembled(files: ModelFiles, version: int, noted: list[str]) -> Model:
    """:func:`assemble_model`; the texts of the warnings that its expressions gave go to ``noted``."""
    from mbds.model.equations import gather_expressions

    bodies = assemble_bodies(files)
    pairs, laws = assemble_contacts(files, bodies)
    with known.noting(noted):
        check_laws(laws, files)
        expressions, params = gather_expressions(files, bodies, laws)
        start = _start_state(files, bodies)
        duration = break_time(files, files.world.path, bodies)
    return _model(files, version, bodies, pairs, laws, expressions, params, start, duration)


def _model(files: ModelFiles, version: int, bodies: list[Body], pairs: list[ContactPair], laws: list[ContactLaw],
           expressions, parameters: Parameters, start: tuple[np.ndarray, np.ndarray], duration: float) -> Model:
    """The :class:`Model` of ``files`` from its parts (its watches assembled here)."""
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
        watches=assemble_watches(files, bodies, version),
        expressions=expressions,
        parameters=parameters,
        break_time=duration,
        q0=start[0],
        qd0=start[1],
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
    from mbds.expr import symbols as S
    from mbds.model.equations import ExpressionReader

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
    from mbds.expr import symbols as S
    from mbds.model.equations import ExpressionReader

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
