"""Run the wearballs job (campaigns/wearballs/wearballs.job: versions 000-013, full breakTime,
createNextVersionAtEnd = 1) and print, per version, each ball's area, the lost work and the
wall time.

Run from the repository root: ``.venv/bin/python benchmarks/wearballs_job.py``.

The job runs in a temporary copy of campaigns/wearballs, so the repository is not touched.
Columns: the area (mm^2) of each ball's shape in that version's own ``.exs`` files (the shape
the version ran with; the last row is the version the job created at its end, not run);
``lost J``: the mechanical energy lost at contacts during the version's run (``run_lost_work``
of its ``history.nc``); ``wall s``: wall time of the version's run, model loading included
(compiled code comes from ``MBDS_CACHE_DIR``, so the first run of a cold cache includes
compiling the stepper).
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

from mbds.data.history import read_attributes
from mbds.io.folder import read_model_files, version_name
from mbds.model.geometry import polygon_properties
from mbds.simulation.job import run_job
from mbds.simulation.versions import existing_versions

ROOT = Path(__file__).resolve().parents[1]
BALLS = [f"ball{k}" for k in range(1, 6)]


def main() -> int:
    with tempfile.TemporaryDirectory(prefix="mbds-wearballs-") as temp:
        folder = Path(temp) / "wearballs"
        shutil.copytree(ROOT / "campaigns" / "wearballs", folder, ignore=shutil.ignore_patterns("[0-9][0-9][0-9]"))
        begun = time.perf_counter()
        result = run_job(folder / "wearballs.job")
        total = time.perf_counter() - begun
        walls = {number: wall for number, _, wall in result.runs}
        print(f"{'version':>7} " + " ".join(f"{b + ' mm2':>11}" for b in BALLS) + f" {'lost J':>9} {'wall s':>7}")
        for number in existing_versions(folder):
            version = folder / version_name(number)
            files = read_model_files(version)
            areas = {b.main.name: polygon_properties(s.points).area for b, s in zip(files.bodies, files.shapes)}
            history = version / "history.nc"
            lost = f"{read_attributes(history)['run_lost_work']:9.4f}" if history.is_file() else f"{'-':>9}"
            wall = f"{walls[number]:7.2f}" if number in walls else f"{'-':>7}"
            print(f"{version_name(number):>7} " + " ".join(f"{1e6 * areas[b]:11.2f}" for b in BALLS) + f" {lost} {wall}")
        print(f"job: {len(result.runs)} versions run, {len(result.created)} created, {total:.1f} s in all"
              + (f"; stopped: {result.stopped}" if result.stopped else ""))
        return 1 if result.stopped else 0


if __name__ == "__main__":
    sys.exit(main())
