"""Creating the next version of a model: copied files, worn shapes, updated constants.

The next version's folder (``NNN`` + 1 beside the source version) receives a byte-for-byte copy
of every model file the world file names (comments and layout kept), then the reshaped shape
files and the updated constants file are written over their copies, and ``wear.nc`` records
what changed and why. The folder is assembled under a temporary name and renamed at the end,
so it either appears complete or not at all.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from mbds._version import version as mbds_version
from mbds.errors import ModelError
from mbds.io.constants import ConstantsFile, format_constants
from mbds.io.folder import (
    ModelFiles,
    copy_model_files,
    read_model_files,
    version_name,
    version_number,
)
from mbds.io.netcdf import Variable, write_file
from mbds.io.shape import ShapeFile, format_shape
from mbds.io.text import process_umask, write_atomic
from mbds.wear.plan import WearPlan, plan_wear

WEAR_FILE = "wear.nc"


def create_next_version(folder: str | Path, losses: dict[str, np.ndarray]) -> Path:
    """Create version N + 1 beside version folder ``folder`` (version N) from the lost work per
    shape point of version N (``losses[body]``, J); return the new folder."""
    folder = Path(folder)
    version = version_number(folder)
    if version is None:
        raise ModelError("a version folder is named with three digits (000, 001, ...)", folder)
    target = folder.parent / version_name(version + 1)
    if target.exists():
        raise ModelError(f"version {version + 1:03d} exists already", target)
    files = read_model_files(folder)
    plan = plan_wear(files, losses, version)
    temporary = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=folder.parent))
    try:
        temporary.chmod(0o777 & ~process_umask())  # mkdtemp makes it private; a version gets the usual permissions
        copy_model_files(files, temporary)
        separator = files.separator
        for wear in plan.bodies:
            shape = next(s for b, s in zip(files.bodies, files.shapes) if b.main.name == wear.body)
            write_atomic(temporary / shape.path.relative_to(folder), format_shape(ShapeFile(wear.shape), separator))
        if plan.constants_after != plan.constants_before:
            cns = files.world.resolve(files.world.settings.constants_file)
            write_atomic(temporary / cns.relative_to(folder), format_constants(ConstantsFile(plan.constants_after), separator))
        write_file(temporary / WEAR_FILE, wear_variables(plan, files), wear_attributes(plan, version))
        os.rename(temporary, target)
    except BaseException:
        shutil.rmtree(temporary, ignore_errors=True)
        raise
    return target


def wear_variables(plan: WearPlan, files: ModelFiles) -> list[Variable]:
    """What a new version changed (the variables of ``wear.nc``, in xarray's order: each index
    before the variables along it): per reshaped body and watched point the loss used (J),
    displacement (m), direction and old and new coordinates (m, body frame); constants before
    and after."""
    data = []
    for wear in plan.bodies:
        old = next(s for b, s in zip(files.bodies, files.shapes) if b.main.name == wear.body).points
        dim = (f"{wear.body}_point",)
        data.append(Variable(dim[0], dim, np.asarray(wear.points), {}, coordinate=True))
        columns = [("loss", wear.loss, "J", f"lost work used for reshaping {wear.body}"),
                   ("displacement", wear.displacement, "m",
                    f"displacement of the points of {wear.body} along their direction")]
        for axis, label in enumerate("xy"):
            columns += [(f"direction_{label}", wear.direction[:, axis], "1",
                         f"reshaping direction, {label} (body frame)"),
                        (f"old_{label}", old[wear.points, axis], "m", f"{label} before reshaping (body frame)"),
                        (f"new_{label}", wear.shape[wear.points, axis], "m", f"{label} after reshaping (body frame)")]
        data += [Variable(f"{wear.body}_{name}", dim, np.asarray(values), {"units": units, "long_name": long_name})
                 for name, values, units, long_name in columns]
    names = list(plan.constants_after)
    if names:
        data.append(Variable("constant", ("constant",), np.asarray(names), {}, coordinate=True))
        for key, values, long_name in (
            ("constant_before", plan.constants_before, "constant in the source version"),
            ("constant_after", plan.constants_after, "constant in the new version"),
        ):
            data.append(Variable(key, ("constant",), np.asarray([values[n] for n in names]), {"long_name": long_name}))
    return data


def wear_attributes(plan: WearPlan, version: int) -> dict:
    """The global attributes of ``wear.nc``."""
    return {
        "title": "mbds wear update",
        "source_version": version_name(version),
        "new_version": version_name(version + 1),
        "mbds_version": mbds_version(),
        "reshaped_bodies": ",".join(w.body for w in plan.bodies),
        "Conventions": "CF-1.10",
    }
