"""Reference checks of a read DAP_BC model: every body, point, unit-vector and function index
names an existing element, each error reported at the line that set the bad index."""

from __future__ import annotations

from mbds.errors import ModelError
from mbds.io.dapbc.records import DapbcModel, Element

#: element type -> fields it requires (nonzero), as the manual's tables after B.4 and B.5 list them
JOINT_NEEDS = {
    "rev": ("iPindex", "jPindex"),
    "tran": ("iPindex", "jPindex", "iUindex", "jUindex"),
    "rev-rev": ("iPindex", "jPindex"),
    "rev-tran": ("iPindex", "jPindex", "iUindex"),
    "rigid": (),
    "disc": ("iBindex",),
    "rel-rot": ("iFunct",),
    "rel-tran": ("iPindex", "jPindex", "iFunct"),
}
FORCE_NEEDS = {
    "ptp": ("iPindex", "jPindex"),
    "rot-sda": (),
    "weight": (),
    "flocal": ("iBindex",),
    "f": ("iBindex",),
    "T": ("iBindex",),
    "user": (),
}
_LISTS = {"iPindex": "points", "jPindex": "points", "iUindex": "uvectors", "jUindex": "uvectors",
          "iBindex": "bodies", "jBindex": "bodies", "iFunct": "functs", "Bindex": "bodies"}
_NOUN = {"points": "point", "uvectors": "unit vector", "bodies": "body", "functs": "function"}


def _fail(element: Element, name: str, message: str):
    """ModelError at the line that set field ``name`` (else the element's type, else its making)."""
    pos = element.where(name if name in element.field_sources else "type")
    return ModelError(message, pos.file if pos else None, pos.line if pos else None)


def _check_index(model: DapbcModel, element: Element, label: str, name: str, required: bool) -> None:
    index = getattr(element, name)
    kind = _LISTS[name]
    count = len(getattr(model, kind))
    if index == 0:
        if required:
            raise _fail(element, "type", f"{label} ({element.type}) needs {name} (a {_NOUN[kind]} index)")
        return
    if index > count:
        have = f"the model has {count} {kind}" if count else f"the model has no {kind}"
        raise _fail(element, name, f"{label}: {name} = {index} names no {_NOUN[kind]}; {have}")


def _body_of(model: DapbcModel, element: Element, point_field: str) -> int:
    return model.points[getattr(element, point_field) - 1].Bindex


def check_references(model: DapbcModel) -> None:
    """Raise ModelError at the first bad index (points, unit vectors, joints, forces, functions)."""
    for kind, label in (("points", "Point"), ("uvectors", "Unit vector"), ("points_anim", "Animation point")):
        for k, element in enumerate(getattr(model, kind), start=1):
            _check_index(model, element, f"{label} {k}", "Bindex", required=False)
    for k, joint in enumerate(model.joints, start=1):
        label = f"Joint {k}"
        needs = JOINT_NEEDS[joint.type]
        for name in ("iPindex", "jPindex", "iUindex", "jUindex", "iBindex", "jBindex", "iFunct"):
            _check_index(model, joint, label, name, name in needs)
        _check_joint_bodies(model, joint, label)
    for k, force in enumerate(model.forces, start=1):
        label = f"Force {k}"
        needs = FORCE_NEEDS[force.type]
        for name in ("iPindex", "jPindex", "iBindex", "jBindex", "iFunct"):
            _check_index(model, force, label, name, name in needs)
        if force.type == "ptp" and _body_of(model, force, "iPindex") == _body_of(model, force, "jPindex"):
            raise _fail(force, "jPindex", f"{label}: points {force.iPindex} and {force.jPindex} are on the same body")
        if force.type == "rot-sda" and force.iBindex == force.jBindex:
            raise _fail(force, "jBindex", f"{label}: rot-sda needs two different bodies (iBindex, jBindex)")
        if force.type == "user" and model.user_force_file is None and model.user_force_py is None:
            raise _fail(force, "type", f"{label} is of type 'user' but the folder has no user_force.m "
                                       "(or user_force.py)")
    for k, funct in enumerate(model.functs, start=1):
        _check_funct(funct, f"Function {k}")


def _check_joint_bodies(model: DapbcModel, joint, label: str) -> None:
    if joint.iPindex and joint.jPindex and _body_of(model, joint, "iPindex") == _body_of(model, joint, "jPindex"):
        raise _fail(joint, "jPindex", f"{label}: points {joint.iPindex} and {joint.jPindex} are on the same "
                                      f"body {_body_of(model, joint, 'iPindex')}")
    for point_field, unit_field in (("iPindex", "iUindex"), ("jPindex", "jUindex")):
        point, unit = getattr(joint, point_field), getattr(joint, unit_field)
        if point and unit and model.uvectors[unit - 1].Bindex != model.points[point - 1].Bindex:
            raise _fail(joint, unit_field, f"{label}: unit vector {unit} is on body "
                                           f"{model.uvectors[unit - 1].Bindex} but point {point} is on body "
                                           f"{model.points[point - 1].Bindex}; they must be on the same body")
    if joint.type in ("rigid", "rel-rot") and joint.iBindex == joint.jBindex:
        raise _fail(joint, "jBindex", f"{label}: {joint.type} needs two different bodies (iBindex, jBindex)")


def _check_funct(funct, label: str) -> None:
    if funct.type == "a":
        if len(funct.coeff) != 3:
            raise _fail(funct, "coeff", f"{label} (type 'a') needs coeff = [c1 c2 c3] (Eq. 8.1), "
                                        f"got {len(funct.coeff)} value(s)")
    elif funct.t_end <= funct.t_start:
        raise _fail(funct, "t_end", f"{label} (type '{funct.type}') needs t_end > t_start "
                                    f"(got {funct.t_start:g} and {funct.t_end:g})")
