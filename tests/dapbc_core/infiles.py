"""Writing small DAP_BC model folders for tests: each in-file from a list of element field dicts."""

from __future__ import annotations

from pathlib import Path

#: in-file -> (array it sets, constructor)
ROLES = {"inBodies": ("Bodies", "Body_struct"), "inPoints": ("Points", "Point_struct"),
         "inUvectors": ("Uvectors", "Unit_struct"), "inForces": ("Forces", "Force_struct"),
         "inJoints": ("Joints", "Joint_struct"), "inFuncts": ("Functs", "Funct_struct")}


def _value(value) -> str:
    if isinstance(value, str):
        return f"'{value}'"
    if isinstance(value, (list, tuple)):
        return "[" + "; ".join(repr(float(v)) for v in value) + "]"
    return repr(value)


def write_model(folder: Path, **elements: list[dict]) -> Path:
    """A model folder with one in-file per role (``inBodies=[{...}, ...]``; roles not given are
    written with empty arrays)."""
    folder.mkdir(parents=True, exist_ok=True)
    for role, (array, constructor) in ROLES.items():
        lines = [f"function {role}", "    include_global", ""]
        names = []
        for k, fields in enumerate(elements.get(role, []), start=1):
            name = f"E{k}"
            names.append(name)
            lines.append(f"{name} = {constructor};")
            lines += [f"{name}.{field} = {_value(value)};" for field, value in fields.items()]
        lines.append(f"{array} = [{'; '.join(names)}];")
        (folder / f"{role}.m").write_text("\n".join(lines) + "\n")
    return folder
