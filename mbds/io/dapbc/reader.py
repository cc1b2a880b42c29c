"""Reading a DAP_BC model folder (inBodies.m, inPoints.m, inUvectors.m, inForces.m,
inJoints.m, inFuncts.m or inFuncs.m, inAnimate.m, and user_force.m or user_force.py) into a
:class:`~mbds.io.dapbc.records.DapbcModel`.  What the reader accepts: docs/dapbc-files.md."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mbds.errors import ModelError
from mbds.io.dapbc.checks import check_references
from mbds.io.dapbc.interpreter import InFile
from mbds.io.dapbc.parser import parse
from mbds.io.dapbc.records import Body, DapbcModel, Element, Force, Funct, Joint, PlotWindow, Point, Uvector

#: in-file role -> (accepted file names, the array it must set, the record type of its elements)
IN_FILES = (
    ("inBodies", ("inBodies.m",), "Bodies", Body),
    ("inPoints", ("inPoints.m",), "Points", Point),
    ("inUvectors", ("inUvectors.m",), "Uvectors", Uvector),
    ("inForces", ("inForces.m",), "Forces", Force),
    ("inJoints", ("inJoints.m",), "Joints", Joint),
    ("inFuncts", ("inFuncts.m", "inFuncs.m"), "Functs", Funct),
    ("inAnimate", ("inAnimate.m",), "Points_anim", Point),
)


def is_dapbc_folder(path: str | Path) -> bool:
    """True when ``path`` is a folder holding inBodies.m (a DAP_BC model)."""
    return (Path(path) / "inBodies.m").is_file()


def read_source(path: Path) -> str:
    """A file's text; ModelError when it is not readable UTF-8 text."""
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise ModelError(f"not UTF-8 text (byte {exc.start})", path) from None
    except OSError as exc:
        raise ModelError(f"cannot read: {exc.strerror}", path) from None


def read_dapbc_folder(path: str | Path) -> DapbcModel:
    """Read and check a DAP_BC model folder.  Bad input raises ModelError ``file:line: ...``.

    Files other than inBodies.m may be missing; their arrays are then empty."""
    folder = Path(path)
    if not is_dapbc_folder(folder):
        raise ModelError("not a DAP_BC model folder: inBodies.m is missing", folder)
    model = DapbcModel(folder=folder)
    shared: dict = {}
    set_at: dict = {}
    for role, names, array, record_type in IN_FILES:
        present = [folder / n for n in names if (folder / n).is_file()]
        if len(present) > 1:
            raise ModelError(f"both {present[0].name} and {present[1].name} exist; keep one", present[1])
        if not present:
            continue
        file = present[0]
        model.files[role] = file
        InFile(parse(read_source(file), str(file)), shared, set_at).run()
        if array not in shared:
            if role == "inAnimate":
                continue
            raise ModelError(f"the file never sets '{array}' (write '{array} = [...];', "
                             f"or '{array} = [];' when there are none)", file)
        shared[array] = _element_list(shared[array], array, record_type, set_at[array])
        if role == "inBodies" and not shared[array]:
            raise ModelError("the model has no bodies", set_at[array].file, set_at[array].line)
    model.bodies = shared["Bodies"]
    model.points = shared.get("Points", [])
    model.uvectors = shared.get("Uvectors", [])
    model.forces = shared.get("Forces", [])
    model.joints = shared.get("Joints", [])
    model.functs = shared.get("Functs", [])
    model.points_anim = shared.get("Points_anim", [])
    model.window = PlotWindow(**{k: _limit(shared, set_at, k) for k in ("xmin", "xmax", "ymin", "ymax")})
    for name in ("user_force.m", "user_force.py"):
        if (folder / name).is_file():
            setattr(model, "user_force_file" if name.endswith(".m") else "user_force_py", folder / name)
    check_references(model)
    return model


def _element_list(value, array: str, record_type: type[Element], pos) -> list:
    if isinstance(value, Element):
        value = [value]
    if isinstance(value, np.ndarray) and value.size == 0:
        return []
    if not isinstance(value, list):
        raise ModelError(f"'{array}' must be an array of {record_type.__name__} structs, "
                         f"not {'text' if isinstance(value, str) else 'numbers'}", pos.file, pos.line)
    for k, element in enumerate(value, start=1):
        if not isinstance(element, record_type):
            raise ModelError(f"'{array}' element {k} is a {type(element).__name__} struct; "
                             f"expected {record_type.__name__} structs", pos.file, pos.line)
    return value


def _limit(shared: dict, set_at: dict, name: str) -> float | None:
    if name not in shared:
        return None
    value = shared[name]
    if not isinstance(value, np.ndarray) or value.shape != (1, 1) or not np.isfinite(value[0, 0]):
        pos = set_at[name]
        raise ModelError(f"'{name}' must be a finite number", pos.file, pos.line)
    return float(value[0, 0])
