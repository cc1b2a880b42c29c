"""World files (``.wld``): simulation settings, file names and the list of bodies.

mbds extension: a ``[generalizedStart]`` section gives free coordinates their start values,
``g'name = position[, velocity]`` (m or rad; m/s or rad/s; expressions of constants). Without
it, or for a free coordinate it does not list, the coordinate starts at 0 with velocity 0, as
in the original program.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mbds.errors import ModelError, warn
from mbds.io.ini import (
    NOT_NEGATIVE,
    OPEN_FRACTION,
    POSITIVE,
    Located,
    Section,
    check_rules,
    key_line,
    find_section,
    format_settings,
    parse_ini,
    read_settings,
    setting,
)
from mbds.io.text import significant_lines

GENERALIZED_START = "generalizedStart"


@dataclass
class WorldSettings:
    """The ``[main]`` section of a world file, with the manual's defaults (units: s, m)."""

    decimal_separator: str = setting("decimalSeparator", "text", ".")
    working_directory: str = setting("workingDirectory", "text", "current")
    # written in the manual's own spelling, the one the original program reads
    number_of_coordinates: int = setting(
        "numberOfGeneralizedCoodinates", "integer", 1, "numberOfGeneralizedCoordinates"
    )
    lcp_pivot_tolerance_min: float = setting("LCPPivotToleranceMin", "number", 1e-14)
    lcp_pivot_tolerance_max: float = setting("LCPPivotToleranceMax", "number", 1e-10)
    lcp_lexico_zero_tolerance: float = setting("LCPLexicoZeroTolerance", "number", 1e-8)
    log_lcp_unbounded_ray: bool = setting("logLCPUnboundedRay", "flag", False)
    log_lcp_max_iterations: bool = setting("logLCPMaxNumberOfIterations", "flag", False)
    zero_velocity_tolerance: float = setting("ZeroVelocityTolerance", "number", 1e-18)
    try_to_solve_by_going_back: bool = setting("TryToSolveByGoingBack", "flag", False)
    minimum_timestep: float = setting("minimumTimestep", "number", 1e-12)
    maximum_timestep: float = setting("maximumTimestep", "number", 1e-5)
    maximum_penetration: float = setting("maximumPenetration", "number", 1e-6)
    maximum_displacement_factor: float = setting("maximumDisplacementFactor", "number", 0.5)
    history_multiple_of_maximum_timestep: float = setting(
        "writeToHistoryMultipleOfMaximumTimestep", "number", 1.0
    )
    history_at_collision: bool = setting("writeToHistoryAtCollision", "flag", False)
    history_each_timestep: bool = setting("writeToHistoryEachTimeStep", "flag", False)
    constants_file: str = setting("constantListFile", "text", "current.cns")
    coordinates_file: str = setting("generalizedCoordinatesFile", "text", "current.gc")
    dependent_coordinates_file: str = setting("dependentCoordinatesFile", "text", "current.dc")
    mass_matrix_file: str = setting("massMatrixFile", "text", "current.mmx")
    h_vector_file: str = setting("hVectorFile", "text", "current.hv")
    mechanical_energy_file: str = setting("mechanicalEnergyFile", "text", "current.me")
    contact_properties_file: str = setting("contactPropertiesFile", "text", "current.cop")
    watches_file: str = setting("watchesFile", "text", "current.wtc")
    break_time: Located = setting("breakTime", "expression", Located("1"))


RULES = {
    "number_of_coordinates": NOT_NEGATIVE,
    "lcp_pivot_tolerance_min": OPEN_FRACTION,
    "lcp_pivot_tolerance_max": OPEN_FRACTION,
    "lcp_lexico_zero_tolerance": OPEN_FRACTION,
    "zero_velocity_tolerance": NOT_NEGATIVE,
    "minimum_timestep": POSITIVE,
    "maximum_timestep": POSITIVE,
    "maximum_penetration": POSITIVE,
    "maximum_displacement_factor": POSITIVE,
    "history_multiple_of_maximum_timestep": POSITIVE,
}
"""The range of each numeric ``[main]`` key (the LCP solver needs 0 < min <= max < 1)."""
_FILE_KEYS = ("constants_file", "coordinates_file", "dependent_coordinates_file", "mass_matrix_file",
              "h_vector_file", "mechanical_energy_file", "contact_properties_file", "watches_file")


def check_world_settings(settings: WorldSettings, main: Section | None, path) -> None:
    """Every ``[main]`` value in its range, and the pairs in order; ModelError at the key's line."""
    check_rules(settings, RULES, main, path)
    for small, large in (("minimum_timestep", "maximum_timestep"),
                         ("lcp_pivot_tolerance_min", "lcp_pivot_tolerance_max")):
        if getattr(settings, small) > getattr(settings, large):
            raise ModelError(f"{_key(small)} is larger than {_key(large)}", path, key_line(main, WorldSettings, small))
    for name in _FILE_KEYS:
        if not getattr(settings, name).strip():
            raise ModelError(f"{_key(name)} names no file", path, key_line(main, WorldSettings, name))


@dataclass
class WorldFile:
    """A world file: settings and the body files in the order of ``[bodies]``."""

    settings: WorldSettings = field(default_factory=WorldSettings)
    bodies: list[Located] = field(default_factory=list)
    path: Path | None = field(default=None, compare=False)
    generalized_start: list[tuple[str, Located]] = field(default_factory=list)  # (g'name, "position[, velocity]")
    main: Section | None = field(default=None, compare=False, repr=False)  # as read, for the lines of its keys

    def line(self, name: str) -> int | None:
        """The line of the key of settings field ``name`` (else of ``[main]``), None when not read from a file."""
        return key_line(self.main, WorldSettings, name) if self.main else None

    @property
    def directory(self) -> Path:
        """The working directory: ``current`` is the world file's folder."""
        base = self.path.parent if self.path else Path.cwd()
        wd = self.settings.working_directory.strip()
        return base if wd.lower() in ("current", "") else (base / wd)

    def resolve(self, name: str) -> Path:
        """A model file name with the ``current`` token replaced by the world file's stem."""
        stem = self.path.stem if self.path else "model"
        name = name.strip()
        if name.lower().startswith("current."):
            name = stem + name[len("current") :]
        return self.directory / name


def decimal_separator_of(text: str, path=None) -> str:
    """The ``decimalSeparator`` a world text declares (``.`` when absent); ModelError at its
    line when it is neither ``.`` nor ``,``."""
    for line in significant_lines(text, path):
        key, sep, value = line.text.partition("=")
        if sep and key.strip().lower() == "decimalseparator":
            separator = value.strip() or "."
            if separator not in (".", ","):
                raise ModelError(f"decimalSeparator must be '.' or ',', not '{separator}'", path, line.number)
            return separator
    return "."


def parse_world(text: str, path: str | Path | None = None) -> WorldFile:
    """A :class:`WorldFile` from the text of a ``.wld`` file."""
    separator = decimal_separator_of(text, path)
    sections = parse_ini(text, path)
    for s in sections:
        if s.name.lower() not in ("main", "bodies", GENERALIZED_START.lower()):
            warn(f"unknown section [{s.name}] (ignored)", path, s.line)
    main = find_section(sections, "main")
    if main is None:
        raise ModelError("no [main] section", path, 1)
    settings = read_settings(WorldSettings, main, path, separator)
    check_world_settings(settings, main, path)
    bodies_section = find_section(sections, "bodies")
    bodies = [Located(e.value, e.line) for e in bodies_section.entries] if bodies_section else []
    for e, b in zip(bodies_section.entries if bodies_section else [], bodies):
        if not b.text:
            raise ModelError(f"'{e.key}' names no body file", path, e.line)
    start = find_section(sections, GENERALIZED_START)
    generalized_start = [(e.key, Located(e.value, e.line)) for e in start.entries] if start else []
    return WorldFile(settings, bodies, Path(path) if path else None, generalized_start, main)


def _key(field_name: str) -> str:
    return WorldSettings.__dataclass_fields__[field_name].metadata["key"]


def format_world(world: WorldFile) -> str:
    """The text of a ``.wld`` file."""
    sep = world.settings.decimal_separator
    lines = ["[main]", *format_settings(world.settings, sep), "[bodies]"]
    lines += [f"body{i} = {b.text}" for i, b in enumerate(world.bodies, start=1)]
    if world.generalized_start:
        lines += [f"[{GENERALIZED_START}]", *(f"{key} = {value.text}" for key, value in world.generalized_start)]
    return "\n".join(lines) + "\n"
