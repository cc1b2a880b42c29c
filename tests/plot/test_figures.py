"""What the figure functions draw: polygons and lines against the history, labels with units,
images of the right size that are not blank."""

import matplotlib.image
import numpy as np
import pytest
from matplotlib.collections import LineCollection
from PIL import Image

import mbds
from mbds import plot
from mbds.errors import ModelError


@pytest.fixture(scope="module")
def runs(model_runs):
    opened = {name: plot.open_run(folder) for name, folder in model_runs.items()}
    yield opened
    for ds in opened.values():
        ds.close()


def world(ds, body, index):
    """The closed polygon of ``body`` in the world at sample ``index``, from the history alone."""
    local = mbds.outline(ds, body)
    x, y, angle = (float(ds[n].sel(body=body).values[index]) for n in ("body_x", "body_y", "body_angle"))
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([x + c * local[:, 0] - s * local[:, 1], y + s * local[:, 0] + c * local[:, 1]])


@pytest.mark.parametrize("name", ["woodpecker", "wearballs", "2mass"])
def test_shapes_draws_every_body_where_the_history_has_it(runs, name):
    ds = runs[name]
    time = float(ds["time"].values[len(ds["time"]) // 2])
    ax = plot.shapes(ds, time=time)
    bodies = [str(b) for b in ds["body"].values]
    assert [p.get_label() for p in ax.patches] == bodies
    index = len(ds["time"]) // 2
    for patch, body, kind in zip(ax.patches, bodies, ds["body_kind"].values):
        np.testing.assert_allclose(patch.get_xy(), world(ds, body, index), atol=1e-12)
        assert patch.get_gid() == kind
        if kind == "virtual":
            assert not patch.get_fill() and patch.get_linestyle() == "--"
        elif kind == "fixed":
            assert patch.get_hatch()
        else:
            np.testing.assert_allclose(patch.get_facecolor()[:3], ds["body_color"].sel(body=body).values)
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "y (m)"
    assert f"model {name}, version 000" in ax.get_title()


def test_a_saved_figure_has_its_size_and_is_not_blank(runs, tmp_path):
    path = plot.save(plot.shapes(runs["wearballs"]), tmp_path / "shapes.png", dpi=50)
    image = matplotlib.image.imread(path)
    assert image.shape[:2] == (240, 320)  # 6.4 x 4.8 in at 50 dpi
    assert image[..., :3].std() > 0.05
    assert [p.name for p in tmp_path.iterdir()] == ["shapes.png"]  # no temporary file left


def test_animate_draws_frames_at_the_chosen_rate(runs, tmp_path):
    ds = runs["woodpecker"]
    duration = float(ds["time"].values[-1] - ds["time"].values[0])
    animation = plot.animate(ds, fps=10, speed=0.01)
    frames = round(duration / 0.01 * 10) + 1
    path = plot.save(animation, tmp_path / "run.gif", fps=10, dpi=40)
    with Image.open(path) as gif:
        assert gif.n_frames == frames
        assert gif.size == (256, 192)
    ax = animation._fig.axes[0]
    assert ax.texts[0].get_text() == f"t = {ds['time'].values[-1]:.3f} s"  # the last frame drawn
    last = np.abs(ds["time"].values - ds["time"].values[-1]).argmin()
    np.testing.assert_allclose(ax.patches[2].get_xy(), world(ds, "bird", last), atol=1e-12)


def test_watches_draws_one_line_per_watch_and_the_accumulated_work(runs):
    ds = runs["woodpecker"]
    figure = plot.watches(ds)
    normal, tangential, work = figure.axes
    watches = ds.sizes["watch"]
    assert len(normal.lines) == len(tangential.lines) == len(work.lines) == watches
    np.testing.assert_array_equal(normal.lines[1].get_ydata(), ds["impulse_normal"].values[:, 1])
    np.testing.assert_allclose(work.lines[1].get_ydata(), np.cumsum(ds["work"].values[:, 1]))
    assert normal.get_ylabel() == "normal impulse (N s)" and work.get_xlabel() == "time (s)"
    # every joule lost at a watch is in the run's lost work (the watches cover all contacts here)
    assert work.lines[1].get_ydata()[-1] <= ds.attrs["run_lost_work"] * (1 + 1e-9)
    with pytest.raises(ModelError, match="no watch"):
        plot.watches(ds, watch=["moon#0"])


def test_lost_work_outline_colours_each_shape_point(runs):
    ds = runs["2mass"]
    ax = plot.lost_work_outline(ds, "mass2")
    lines = next(c for c in ax.collections if isinstance(c, LineCollection))
    mine = ds["point_body_name"].values == "mass2"
    assert len(lines.get_segments()) == mine.sum()
    np.testing.assert_array_equal(lines.get_array(), ds["point_lost_work"].values[mine])


def test_energy_draws_the_balance_of_the_run(runs):
    ds = runs["2mass"]
    ax = plot.energy(ds)
    assert len(ax.lines) == 4 and ax.get_ylabel() == "energy (J)"
    balance = ax.lines[3].get_ydata()
    # E + lost - driver stays at its start value (energy balance of the run, docs/theory.md)
    np.testing.assert_allclose(balance, balance[0], atol=1e-9)
    with pytest.raises(ModelError, match="no Lagrange multipliers"):
        plot.multipliers(ds)


def test_coordinates_has_a_panel_per_unit(runs):
    figure = plot.coordinates(runs["woodpecker"])
    metres, radians = figure.axes
    assert metres.get_ylabel() == "coordinate (m)" and radians.get_ylabel() == "coordinate (rad)"
    # ring y, bird x, y, both sleeve sides x, y; ring, bird and both sleeve sides Rz
    assert len(metres.lines) == 7 and len(radians.lines) == 4


def test_wear_of_a_campaign_has_a_panel_per_variant_and_a_line_per_version(campaign_job):
    with mbds.open_campaign(campaign_job.parent / "campaign") as tree:
        figure = plot.wear(tree, "mass1")
        panels = [ax for ax in figure.axes if ax.get_visible() and ax.lines]
        assert len(panels) == tree.ds.sizes["variant"] == 2
        for ax, variant in zip(panels, tree.ds["variant"].values):
            assert [line.get_label() for line in ax.lines] == ["version 000", "version 001"]
            polygon = mbds.outline(tree.ds, "mass1", 1, variant=variant)
            np.testing.assert_array_equal(np.column_stack(ax.lines[1].get_data()), polygon)
            light, dark = (np.mean(line.get_color()[:3]) for line in ax.lines)
            assert light > dark


def test_wear_of_a_chain_reads_its_versions(campaign_job):
    chain = next(p for p in (campaign_job.parent / "campaign").iterdir() if p.is_dir())
    figure = plot.wear(chain, "mass1", versions=[1])
    assert len(figure.axes[0].lines) == 1
    with pytest.raises(ModelError, match="no version 007"):
        plot.wear(chain, "mass1", versions=[7])


def test_campaign_summary_has_a_line_per_variant(campaign_job):
    with mbds.open_campaign(campaign_job.parent / "campaign") as tree:
        figure = plot.campaign_summary(tree)
        lost, final, reshaping = figure.axes[:3]
        assert len(lost.lines) == len(final.lines) == len(reshaping.lines) == 2
        np.testing.assert_array_equal(lost.lines[0].get_ydata(), tree.ds["run_lost_work"].isel(variant=0).values)
        np.testing.assert_array_equal(final.lines[1].get_ydata(), tree.ds["end_energy"].isel(variant=1).values)
        shift = reshaping.lines[0].get_ydata()
        x, y = (tree.ds[n].isel(variant=0).values for n in ("shape_x", "shape_y"))
        assert np.isnan(shift[0]) and shift[1] == np.hypot(x[1] - x[0], y[1] - y[0]).max()
        assert lost.get_ylabel() == "lost work in the run (J)"
