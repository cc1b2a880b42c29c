"""The dataset of a DAP_BC analysis: the arrays of DAP_BC's post (manual Table B.10) under
DAP_BC's names and meanings, with CF attributes and units, written as ``history.nc``
(attribute ``kind = "dap_bc"``; the schema is in docs/dapbc.md)."""

from __future__ import annotations

import platform
from pathlib import Path

import numpy as np
import xarray as xr

from mbds._version import version as mbds_version
from mbds.analysis.dapbc import DapbcResult, DapbcSettings
from mbds.io.text import atomic_path
from mbds.model.dapbc.system import DapbcSystem

FILE_NAME = "history.nc"
ENERGIES = ("kinetic", "potential", "total")
COORDINATE_UNITS = ("m", "m", "rad")


def _cf(long_name: str, units: str) -> dict:
    return {"long_name": long_name, "units": units}


def dapbc_dataset(system: DapbcSystem, result: DapbcResult, settings: DapbcSettings, wall_time: float) -> xr.Dataset:
    """The history of one analysis; arrays indexed (time, ...), bodies and points 1-based in
    the coordinates ``body`` and ``point`` as in the in-files."""
    nt, n = len(result.times), system.n
    nb = n // 3
    q, qd, qdd = (a.reshape(nt, nb, 3) for a in (result.y[:, :n], result.y[:, n:], result.post.qdd))
    tb, tba, tpa = ("time", "body"), ("time", "body", "axis"), ("time", "point", "axis")
    data = {
        "r": (tba, q[:, :, :2], _cf("translational coordinates of the mass centres", "m")),
        "rd": (tba, qd[:, :, :2], _cf("translational velocities of the mass centres", "m s-1")),
        "rdd": (tba, qdd[:, :, :2], _cf("translational accelerations of the mass centres", "m s-2")),
        "p": (tb, q[:, :, 2], _cf("rotational coordinates (body angles)", "rad")),
        "pd": (tb, qd[:, :, 2], _cf("rotational velocities", "rad s-1")),
        "pdd": (tb, qdd[:, :, 2], _cf("rotational accelerations", "rad s-2")),
        "rP": (tpa, result.post.rP, _cf("coordinates of the points", "m")),
        "rPd": (tpa, result.post.rPd, _cf("velocities of the points", "m s-1")),
        "Jac": (("time", "constraint", "coordinate"), result.post.jac,
                {"long_name": "Jacobian matrix D = dPhi/dq of the constraints",
                 "comment": "units: those of the constraint row over those of the coordinate (coordinate_unit)"}),
        "Lam": (("time", "constraint"), result.post.lam,
                {"long_name": "Lagrange multipliers (M q'' - Jac^T Lam = h)",
                 "comment": "N for rows in metres, N m for rows in radians, N m-1 for rows in m2"}),
        "eng": (("time", "energy"), result.post.eng, _cf("energy (kinetic, potential of gravity and linear springs, total)", "J")),
    }
    coords = {
        "time": ("time", result.times, {"standard_name": "time", "long_name": "time", "units": "s", "axis": "T"}),
        "body": ("body", np.arange(1, nb + 1, dtype=np.int32), {"long_name": "body index (inBodies)"}),
        "point": ("point", np.arange(1, system.n_points + 1, dtype=np.int32), {"long_name": "point index (inPoints)"}),
        "axis": ("axis", np.array(["x", "y"], dtype=object), {"long_name": "x-y frame axis"}),
        "constraint": ("constraint", np.arange(1, system.nc + 1, dtype=np.int32), {"long_name": "constraint equation (joint order)"}),
        "constraint_name": ("constraint", np.array(system.constraint_names, dtype=object), {"long_name": "joint, type and row"}),
        "coordinate": ("coordinate", np.arange(1, n + 1, dtype=np.int32), {"long_name": "body coordinate (x1, y1, phi1, x2, ...)"}),
        "coordinate_unit": ("coordinate", np.array(COORDINATE_UNITS * nb, dtype=object), {"long_name": "unit of the coordinate"}),
        "energy": ("energy", np.array(ENERGIES, dtype=object), {"long_name": "energy part"}),
    }
    attrs = {
        "Conventions": "CF-1.10",
        "title": f"mbds {result.analysis} analysis of DAP_BC model {system.source.name}",
        "kind": "dap_bc",
        "model": system.source.name,
        "analysis": result.analysis,
        "mbds_version": mbds_version(),
        "python_version": platform.python_version(),
        "final_time": settings.final_time,
        "report_step": settings.report_step,
        "method": settings.method,
        "rtol": settings.rtol,
        "atol": settings.atol,
        "projection": int(settings.projection),
        "correct_ic": int(settings.correct_ic and result.correction is not None),
        "nfev": result.nfev,
        "steps": result.steps,
        "rejected_steps": result.rejected,
        "wall_time": wall_time,
        "input_files": " ".join(sorted(p.name for p in system.source.inputs)),
    }
    attrs.update({f"input_{p.name}": p.read_text(encoding="utf-8") for p in system.source.inputs})
    drawing = system.drawing
    return xr.Dataset({**data, **drawing[0]}, coords={**coords, **drawing[1]}, attrs={**attrs, **drawing[2]})


def write_dapbc_history(path: str | Path, dataset: xr.Dataset) -> None:
    """Write ``dataset`` to ``path`` atomically (temporary file, then rename)."""
    with atomic_path(path) as tmp:
        dataset.to_netcdf(tmp, format="NETCDF4", engine="netcdf4")
