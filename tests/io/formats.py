"""Each MBDS file type with its parser and formatter, for the io tests."""

from mbds.io.body import format_body, parse_body
from mbds.io.constants import format_constants, parse_constants
from mbds.io.contacts import format_contacts, parse_contacts
from mbds.io.coordinates import (
    format_coordinates,
    format_dependent_coordinates,
    parse_coordinates,
    parse_dependent_coordinates,
)
from mbds.io.equations import (
    format_expressions,
    format_matrix,
    parse_energy,
    parse_expressions,
    parse_matrix,
)
from mbds.io.job import format_job, parse_job
from mbds.io.shape import format_shape, parse_shape
from mbds.io.watches import format_watches, parse_watches
from mbds.io.world import format_world, parse_world

FORMATS = {
    "wld": (parse_world, format_world),
    "job": (parse_job, format_job),
    "bdy": (parse_body, format_body),
    "exs": (parse_shape, format_shape),
    "gc": (parse_coordinates, format_coordinates),
    "dc": (parse_dependent_coordinates, format_dependent_coordinates),
    "cns": (parse_constants, format_constants),
    "hv": (parse_expressions, format_expressions),
    "me": (parse_energy, format_expressions),
    "mmx": (parse_matrix, format_matrix),
    "cop": (parse_contacts, format_contacts),
    "wtc": (parse_watches, format_watches),
}
