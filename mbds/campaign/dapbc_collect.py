"""The summary of a collected campaign over a DAP_BC model (the root of ``campaign.nc``; the
runs' histories are its nodes ``/<variant>/000``, as :mod:`mbds.campaign.collect` makes them).

Dimensions ``variant``, ``body``, ``axis``, ``energy``; per variant the run task's ``status`` and
``wall`` time (s), DAP_BC's count of function evaluations ``nfev``, the integrator's ``steps``
and ``rejected_steps`` (-1: not done), and the state at the run's last report: ``end_time``
(s), ``end_r`` (m), ``end_p`` (rad) and ``end_eng`` (J); the varied keys are coordinates along
``variant`` (numbers when all their values are)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from mbds.campaign.collect import _name, provenance
from mbds.campaign.ledger import Ledger
from mbds.campaign.plan import Plan, Task

SUMMARY_VARIABLES = ("r", "p", "eng", "body", "axis", "energy")
"""The variables each run's history is read for."""
COUNTERS = {"nfev": "function evaluations (DAP_BC's count; -1: not done)",
            "steps": "accepted integrator steps (-1: not done)",
            "rejected_steps": "rejected integrator steps (-1: not done)"}


def dapbc_summary(plan: Plan, ledger: Ledger, runs: list[Task], histories: dict[str, xr.Dataset]) -> xr.Dataset:
    """The root dataset of a DAP_BC campaign from its run tasks and the done runs' ``histories``."""
    first = next(iter(histories.values()))
    nv, nb = len(runs), first.sizes["body"]
    end_r = np.full((nv, nb, 2), np.nan)
    end_p = np.full((nv, nb), np.nan)
    end_eng = np.full((nv, first.sizes["energy"]), np.nan)
    end_time, wall = np.full(nv, np.nan), np.full(nv, np.nan)
    counters = {name: np.full(nv, -1, dtype=np.int64) for name in COUNTERS}
    for k, task in enumerate(runs):
        history = histories.get(task.id)
        if history is None:
            continue
        end_r[k], end_p[k], end_eng[k] = (history[name].values[-1] for name in ("r", "p", "eng"))
        end_time[k] = history.attrs["final_time"]
        wall[k] = ledger.entry(task.id).get("wall", np.nan)
        for name in COUNTERS:
            counters[name][k] = history.attrs[name]
    data = {
        "status": ("variant", np.array([ledger.state(t.id) for t in runs], dtype=str),
                   {"long_name": "state of the run task in the ledger"}),
        "wall": ("variant", wall, {"long_name": "wall time of the run task", "units": "s"}),
        "end_time": ("variant", end_time, {"long_name": "time of the run's last report", "units": "s"}),
        "end_r": (("variant", "body", "axis"), end_r, {**first["r"].attrs, "comment": "at the last report"}),
        "end_p": (("variant", "body"), end_p, {**first["p"].attrs, "comment": "at the last report"}),
        "end_eng": (("variant", "energy"), end_eng, {**first["eng"].attrs, "comment": "at the last report"}),
        **{name: ("variant", counters[name], {"long_name": text}) for name, text in COUNTERS.items()},
    }
    coords = {
        "variant": ("variant", np.array([t.chain for t in runs], dtype=object), {"long_name": "variant of the campaign"}),
        "body": ("body", first["body"].values, dict(first["body"].attrs)),
        "axis": ("axis", first["axis"].values, dict(first["axis"].attrs)),
        "energy": ("energy", first["energy"].values, dict(first["energy"].attrs)),
    }
    for i, p in enumerate(plan.campaign.parameters if plan.campaign else ()):
        values = [p.values[v.picks[i]] for v in plan.variants]
        coords[_name(p.key)] = ("variant", _coordinate(values, [v.values[p.key] for v in plan.variants]),
                                {"key": p.key, "long_name": f"varied key {p.key}",
                                 "comment": "in the unit of the model's in-files (run settings: SI)"})
    return xr.Dataset(data, coords=coords, attrs=provenance(plan, ledger))


def _coordinate(values: list, texts: list[str]) -> np.ndarray:
    """Numbers when every value is one, else the values as written."""
    if all(isinstance(v, (int, float)) for v in values):
        return np.array(values, dtype=float)
    return np.array(texts, dtype=object)
