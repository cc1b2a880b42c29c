"""``mbds plot``, ``mbds animate`` and ``mbds-campaign plot``: figures written to files."""

from __future__ import annotations

import functools
from pathlib import Path

from mbds.errors import ModelError
from mbds.io.job import expand_versions

KINDS = ("shapes", "watches", "wear", "energy", "multipliers", "coordinates", "outline")


def plot_command(kind: str, path: Path, output: Path | None, time: float | None, body: str | None,
                 versions: str | None) -> Path:
    """Draw figure ``kind`` of the run(s) at ``path`` into ``output`` (default: ``<kind>.png``
    beside the history); the path written."""
    import matplotlib

    matplotlib.use("Agg")
    from mbds import plot
    from mbds.plot.source import history_paths

    if kind not in KINDS:
        raise ModelError(f"unknown figure {kind!r}; the figures are {', '.join(KINDS)}")
    paths = history_paths(path)
    if kind == "wear":
        run = plot.open_run(paths[-1])
        chosen = expand_versions(versions) if versions else None
        figure = plot.wear(path, body or _worn_body(run), versions=chosen)
        folder = paths[-1].parent.parent if len(paths) > 1 else paths[-1].parent
    else:
        run = plot.open_run(paths[-1])
        figure = {
            "shapes": lambda: plot.shapes(run, time=time),
            "watches": lambda: plot.watches(run),
            "energy": lambda: plot.energy(run),
            "multipliers": lambda: plot.multipliers(run),
            "coordinates": lambda: plot.coordinates(run),
            "outline": lambda: plot.lost_work_outline(run, body or _worn_body(run)),
        }[kind]()
        folder = paths[-1].parent
    return plot.save(figure, output or folder / f"{kind}.png")


def _worn_body(run) -> str:
    """The body that lost the most work at its points in ``run`` (the one a wear figure is of)."""
    loss = run["point_lost_work"].groupby(run["point_body"]).sum()
    return str(run["body"].values[int(loss["point_body"].values[int(loss.values.argmax())])])


def animate_command(path: Path, output: Path | None, fps: float, speed: float, contacts: bool) -> Path:
    """Animate the run at ``path`` into ``output`` (default: ``animation.mp4`` or ``.gif``
    beside its history); the path written."""
    import matplotlib

    matplotlib.use("Agg")
    from mbds import plot
    from mbds.plot.source import history_paths

    from mbds.plot.figure import VIDEO_FORMATS

    if output is not None and output.suffix.lower().lstrip(".") not in VIDEO_FORMATS:
        raise ModelError(f"an animation is saved as {' or '.join(VIDEO_FORMATS)}", output)
    history = history_paths(path)[-1]
    animation = plot.animate(plot.open_run(history), fps=fps, speed=speed, contacts=contacts)
    return plot.save(animation, output or history.parent / f"animation.{plot.video_suffix()}", fps=fps)


def campaign_plot_command(job: Path, output: Path | None) -> list[Path]:
    """The figures of a collected campaign: its summary and the worn shapes of every body that
    lost work, into ``output`` (default: the campaign folder's ``figures``)."""
    import matplotlib

    matplotlib.use("Agg")
    from mbds import open_campaign, plot
    from mbds.campaign.section import campaign_folder
    from mbds.io.dapbc_job import is_dapbc_job
    from mbds.io.job import read_checked_job
    from mbds.plot.batch import save_figures

    if is_dapbc_job(job):
        raise ModelError("mbds-campaign plot draws wear campaigns; draw a DAP_BC campaign's runs from "
                         "mbds.open_campaign (docs/campaigns.md, 'DAP_BC models')", job)
    campaign = campaign_folder(read_checked_job(job))  # the model is not read: the campaign file has what is drawn
    folder = output or campaign / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    # the figures read the summary alone, read here once: the figures are drawn at once by
    # forked processes, which must not share an open file
    tree = open_campaign(campaign, load=True, runs=False)
    root = tree.ds
    loss = root["point_lost_work"].sum([d for d in root["point_lost_work"].dims if d != "point"])
    worn = [name for index, name in enumerate(str(b) for b in root["body"].values)
            if float(loss.values[root["point_body"].values == index].sum()) > 0]
    drawings = [(functools.partial(plot.wear, tree, name), folder / f"wear_{name}.png") for name in worn]
    # the wear figures (a panel per variant) take longest: they start first
    *wear, summary = save_figures([*drawings, (functools.partial(plot.campaign_summary, tree), folder / "summary.png")])
    return [summary, *wear]
