"""Reading and writing a whole model: the world file and every file it names."""

from __future__ import annotations

import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.body import BodyFile, format_body, parse_body
from mbds.io.constants import ConstantsFile, format_constants, parse_constants
from mbds.io.contacts import ContactsFile, format_contacts, parse_contacts
from mbds.io.coordinates import (
    CoordinatesFile,
    DependentCoordinatesFile,
    format_coordinates,
    format_dependent_coordinates,
    parse_coordinates,
    parse_dependent_coordinates,
)
from mbds.io.equations import (
    ExpressionsFile,
    MatrixFile,
    format_expressions,
    format_matrix,
    parse_energy,
    parse_expressions,
    parse_matrix,
)
from mbds.io.shape import ShapeFile, format_shape, parse_shape
from mbds.io.text import read_text, write_atomic
from mbds.io.watches import WatchesFile, format_watches, parse_watches
from mbds.io.world import WorldFile, WorldSettings, format_world, parse_world


@dataclass
class ModelFiles:
    """Everything a world file names, as read (no cross-file checks yet)."""

    world: WorldFile
    bodies: list[BodyFile]
    shapes: list[ShapeFile]
    coordinates: CoordinatesFile
    dependent: DependentCoordinatesFile
    constants: ConstantsFile
    mass_matrix: MatrixFile
    h_vector: ExpressionsFile
    energy: ExpressionsFile
    contacts: ContactsFile
    watches: WatchesFile
    missing: list[str] = field(default_factory=list, compare=False)

    @property
    def separator(self) -> str:
        return self.world.settings.decimal_separator

    def paths(self) -> list[Path]:
        """The files read, world file first (absent optional files left out)."""
        files = [self.world, *self.bodies, *self.shapes, self.coordinates, self.dependent, self.constants,
                 self.mass_matrix, self.h_vector, self.energy, self.contacts, self.watches]
        return [f.path for f in files if f.path is not None]


def find_world(path: str | Path) -> Path:
    """The world file of ``path``: the file itself, or the one ``.wld`` file of a folder."""
    path = Path(path)
    if path.is_dir():
        worlds = sorted(path.glob("*.wld"))
        named = path / f"{path.name}.wld"
        if named in worlds:
            return named
        if len(worlds) == 1:
            return worlds[0]
        if not worlds:
            raise ModelError("no .wld world file in this folder", path)
        raise ModelError(f"several world files ({', '.join(w.name for w in worlds)}): name one", path)
    if not path.exists():
        raise ModelError("no such file or folder", path)
    if path.suffix.lower() != ".wld":
        raise ModelError("expected a model folder or a .wld world file", path)
    return path


def read_model_files(path: str | Path) -> ModelFiles:
    """Read a model from a folder or a ``.wld`` file; optional files may be absent.

    Optional: ``.dc`` (no dependent coordinates), ``.cns`` (no constants), ``.me`` (energy not
    tracked), ``.cop`` (no contacts), ``.wtc`` (no watches), when they have their default names
    (``current.dc``, ...); a file named otherwise, or a required one, that is missing is an error
    at the world file's line that names it.
    """
    world_path = find_world(path)
    world = parse_world(read_text(world_path), world_path)
    sep = world.settings.decimal_separator
    missing: list[str] = []

    def load(name: str, parser, empty, **kwargs):
        """The file of world key ``name`` parsed; ``empty`` when it is optional, absent and
        has its default name (``current.dc``, ...): a file named otherwise must be there."""
        value = getattr(world.settings, name)
        file = world.resolve(value)
        default = WorldSettings.__dataclass_fields__[name].default
        if empty is not None and not file.exists() and value.strip().lower() == default.lower():
            missing.append(file.name)
            return empty
        return parser(referred_text(file, world_path, world.line(name)), file, **kwargs)

    bodies, shapes = [], []
    for entry in world.bodies:
        body_path = world.directory / entry.text
        body = parse_body(referred_text(body_path, world_path, entry.line, "body file"), body_path, sep)
        if not body.main.shape_file:
            raise ModelError("no shapeFile given", body_path, body.name_line)
        shape_path = body_path.parent / body.main.shape_file
        shape_line = body.lines.get("shapefile", body.name_line)
        bodies.append(body)
        shapes.append(parse_shape(referred_text(shape_path, body_path, shape_line, "shape file"), shape_path, sep))
    n = world.settings.number_of_coordinates
    return ModelFiles(
        world=world,
        bodies=bodies,
        shapes=shapes,
        coordinates=load("coordinates_file", lambda t, p: parse_coordinates(t, p), None),
        dependent=load("dependent_coordinates_file", parse_dependent_coordinates, DependentCoordinatesFile()),
        constants=load("constants_file", parse_constants, ConstantsFile(), separator=sep),
        mass_matrix=load("mass_matrix_file", parse_matrix, None, size=n),
        h_vector=load("h_vector_file", parse_expressions, None, count=n),
        energy=load("mechanical_energy_file", parse_energy, ExpressionsFile()),
        contacts=load("contact_properties_file", parse_contacts, ContactsFile(), separator=sep),
        watches=load("watches_file", parse_watches, WatchesFile(), separator=sep),
        missing=missing,
    )


def referred_text(path: Path, referrer: Path, line: int | None, what: str = "file") -> str:
    """The text of ``path``, which line ``line`` of ``referrer`` names; a missing file or a
    folder is a ModelError at that line, naming ``path``."""
    if path.is_dir():
        raise ModelError(f"{what} '{path}' is a folder, expected a file", referrer, line)
    if not path.exists():
        raise ModelError(f"{what} '{path}' not found", referrer, line)
    return read_text(path)


def write_model_files(files: ModelFiles, folder: str | Path, world_name: str | None = None) -> Path:
    """Write a complete model into ``folder`` (each file atomically); returns the world path.

    Body and shape files keep their names; the other files get the world's ``current`` names.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    world = files.world
    stem = world_name or (world.path.stem if world.path else "model")
    sep = files.separator
    target = WorldFile(world.settings, world.bodies, folder / f"{stem}.wld")
    write_atomic(target.path, format_world(target))
    s = world.settings
    for body, shape, entry in zip(files.bodies, files.shapes, world.bodies):
        body_path = target.directory / entry.text
        body_path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(body_path, format_body(body, sep))
        write_atomic(body_path.parent / body.main.shape_file, format_shape(shape, sep))
    outputs = [
        (s.coordinates_file, format_coordinates(files.coordinates)),
        (s.dependent_coordinates_file, format_dependent_coordinates(files.dependent)),
        (s.constants_file, format_constants(files.constants, sep)),
        (s.mass_matrix_file, format_matrix(files.mass_matrix)),
        (s.h_vector_file, format_expressions(files.h_vector)),
        (s.mechanical_energy_file, format_expressions(files.energy)),
        (s.contact_properties_file, format_contacts(files.contacts, sep)),
        (s.watches_file, format_watches(files.watches, sep)),
    ]
    for name, text in outputs:
        write_atomic(target.resolve(name), text)
    return target.path


_VERSION = re.compile(r"\d{3}")
_REPLICATE = re.compile(r"r\d+")


def version_name(number: int) -> str:
    """``000`` for 0: three digits."""
    if not 0 <= number <= 999:
        raise ModelError(f"version {number} is not between 000 and 999")
    return f"{number:03d}"


def version_number(folder: str | Path) -> int | None:
    """The number of a version folder's name (``001`` -> 1), None for other names."""
    name = Path(folder).name
    return int(name) if _VERSION.fullmatch(name) else None


def replicate_name(index: int) -> str:
    """``r0``, ``r1``, ...: the folder of one replicate run inside a version folder (campaigns
    in ensemble mode)."""
    return f"r{index}"


def run_number(folder: str | Path) -> int | None:
    """The version a run folder belongs to: a version folder (``003`` -> 3) or a replicate
    folder inside one (``003/r1`` -> 3); None for other folders."""
    folder = Path(folder)
    if _REPLICATE.fullmatch(folder.name):
        return version_number(folder.parent)
    return version_number(folder)


def copy_model_files(files: ModelFiles, target: str | Path) -> None:
    """Copy every file of the model, byte for byte (comments and layout kept), into ``target``,
    at the same places relative to the world file's folder."""
    source = files.world.path.parent.resolve()
    for path in files.paths():
        path = Path(path).resolve()
        if not path.is_relative_to(source):
            raise ModelError("a model file outside the world file's folder cannot be copied (workingDirectory?)", path)
        destination = Path(target) / path.relative_to(source)
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, destination)
