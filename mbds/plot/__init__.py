"""Pictures of runs and campaigns with matplotlib, for notebooks and for ``mbds plot``.

Every function takes what ``mbds.plot.open_run`` / ``xr.open_dataset`` (a history.nc) or
``mbds.open_campaign`` return and returns matplotlib objects to restyle; ``save`` writes any of
them atomically. Runs are dispatched on their ``kind`` attribute (``mbds``, or ``dap_bc`` for the
DAP_BC front-end's histories; see docs/results.md)."""

from mbds.plot.campaign import campaign_summary, wear
from mbds.plot.figure import save, video_suffix
from mbds.plot.motion import animate, shapes
from mbds.plot.series import coordinates, energy, lost_work_outline, multipliers, watches
from mbds.plot.source import open_run

__all__ = [
    "animate", "campaign_summary", "coordinates", "energy", "lost_work_outline", "multipliers", "open_run",
    "save", "shapes", "video_suffix", "wear", "watches",
]
