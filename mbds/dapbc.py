"""Running DAP_BC model folders: ``simulate`` reads a folder, builds and compiles its system
(cached), runs one of the registered analyses and returns DAP_BC's post arrays as an xarray
Dataset (docs/dapbc.md); ``run_folder`` also writes it to ``FOLDER/000/history.nc``."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

import xarray as xr

from mbds.analysis import analysis as registered_analysis
from mbds.analysis.dapbc import DapbcResult, DapbcSettings
from mbds.data.dapbc_history import FILE_NAME, dapbc_dataset, write_dapbc_history
from mbds.errors import ModelError
from mbds.io.dapbc import is_dapbc_folder, read_dapbc_folder
from mbds.model.dapbc.system import DapbcSystem, build_system

__all__ = ["DapbcSettings", "ModelError", "analyse", "is_dapbc_folder", "load", "run_folder", "simulate"]

RUN_FOLDER = "000"


def load(folder: str | Path) -> DapbcSystem:
    """Read the folder and compile its system (or load it from the model cache)."""
    return build_system(read_dapbc_folder(folder))


def analyse(system: DapbcSystem, analysis: str, settings: DapbcSettings,
            progress: Callable | None = None) -> tuple[DapbcResult, xr.Dataset]:
    """Run ``analysis`` on a built system; the result and its dataset."""
    wall = time.perf_counter()
    result = registered_analysis(analysis)(system, settings, progress)
    return result, dapbc_dataset(system, result, settings, time.perf_counter() - wall)


def simulate(folder: str | Path, analysis: str = "forward", final_time: float = 1.0, report_step: float = 0.01,
             method: str = "dopri5", rtol: float = 1e-6, atol: float = 1e-9, correct_ic: bool = True,
             projection: bool = True, progress: Callable | None = None) -> xr.Dataset:
    """Run a DAP_BC model folder; times 0, report_step, ..., final_time (s).  ``attrs["nfev"]``
    is DAP_BC's count of function evaluations; ``projection=False`` gives DAP_BC's algorithm
    exactly (no projection onto the constraints; see DapbcSettings)."""
    settings = DapbcSettings(final_time, report_step, correct_ic, method, rtol, atol, projection)
    return analyse(load(folder), analysis, settings, progress)[1]


def run_folder(folder: str | Path, analysis: str, settings: DapbcSettings,
               progress: Callable | None = None) -> tuple[DapbcResult, Path]:
    """Run and write ``FOLDER/000/history.nc``; the result and the path written."""
    system = load(folder)
    result, dataset = analyse(system, analysis, settings, progress)
    out = Path(folder) / RUN_FOLDER
    out.mkdir(exist_ok=True)
    write_dapbc_history(out / FILE_NAME, dataset)
    return result, out / FILE_NAME
