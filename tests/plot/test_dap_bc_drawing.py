"""DAP_BC bodies drawn as DAP_BC's anim draws them (manual Sec. B.2, inAnimate; Figure B.2(b)):
the drawing description a run writes into its history, and what shapes / animate draw from it,
checked against the history's r, p and rP."""

import matplotlib.image
import numpy as np
import pytest
import xarray as xr
from matplotlib.colors import to_rgba
from PIL import Image
from typer.testing import CliRunner

from mbds import dapbc, plot
from mbds.analysis.dapbc import DapbcSettings
from mbds.cli.main import app
from mbds.model.dapbc.drawing import drawing_variables
from mbds.errors import ModelError
from mbds.io.dapbc import read_dapbc_folder
from mbds.plot.motion import frame_samples
from tests.examples import copy_example

EXTRA = """
    P4 = Point_struct;
    P4.Bindex = 2;
    P4.sPlocal = [0; -0.5];
    Points_anim = [P4];
    Bodies(2).color = 'r';
"""
"""Added to SP's inAnimate: the pendulum's lower end as an animation point, the pendulum red."""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """SP (0.4 s; with EXTRA) and Cart_A (0.3 s), run as ``mbds run`` runs them."""
    root = tmp_path_factory.mktemp("dap_bc")
    sp = copy_example("dap_bc/SP", root / "SP")
    animate = sp / "inAnimate.m"
    animate.write_text(animate.read_text().replace("    Points_anim = [];\n", EXTRA))
    cart = copy_example("dap_bc/Cart_A", root / "Cart_A")
    for folder, final in ((sp, 0.4), (cart, 0.3)):
        dapbc.run_folder(folder, "forward", DapbcSettings(final, 0.02, True))
    opened = {"SP": plot.open_run(sp), "Cart_A": plot.open_run(cart)}
    yield opened, {"SP": sp, "Cart_A": cart}
    for ds in opened.values():
        ds.close()


def on_body(ds, body, index, local):
    """World coordinates of the body-frame points ``local`` of ``body`` (1-based) at a sample."""
    (x, y), phi = ds["r"].values[index, body - 1], ds["p"].values[index, body - 1]
    c, s = np.cos(phi), np.sin(phi)
    local = np.asarray(local, dtype=float)
    return np.column_stack([x + c * local[:, 0] - s * local[:, 1], y + s * local[:, 0] + c * local[:, 1]])


def artist(ax, gid):
    (found,) = [a for a in ax.lines + ax.collections if a.get_gid() == gid]
    return found


def test_the_history_describes_the_drawing(runs):
    ds = runs[0]["SP"]
    assert list(ds["body_shape"].values) == ["rect", "line"]
    np.testing.assert_array_equal(ds["body_width"].values, [0.4, 0.0])
    np.testing.assert_array_equal(ds["body_height"].values, [0.2, 1.0])
    assert list(ds["body_color"].values) == ["#000000", "#ff0000"] and ds["body_height"].attrs["units"] == "m"
    np.testing.assert_array_equal(ds["point_body"].values, [0, 1, 2])
    np.testing.assert_array_equal(ds["point_local"].values, [[0, 0.2], [0, 0], [0, 0.5]])
    np.testing.assert_array_equal(ds["anim_point_body"].values, [2])
    np.testing.assert_array_equal(ds["anim_point_local"].values, [[0, -0.5]])
    assert list(ds["joint_type"].values) == ["tran", "rev"] and list(ds["force_type"].values) == ["ptp", "weight"]
    np.testing.assert_array_equal(ds["joint_points"].values, [[2, 1], [2, 3]])
    np.testing.assert_array_equal(ds["force_points"].values, [[2, 1], [0, 0]])
    assert [ds.attrs[f"animation_{k}"] for k in ("xmin", "xmax", "ymin", "ymax")] == [-0.5, 2.0, -1.0, 0.5]
    cart = runs[0]["Cart_A"]
    assert list(cart["body_shape"].values) == ["rect", "circle", "circle"] and cart.sizes["anim_point"] == 0


def test_sp_is_drawn_where_the_history_has_it(runs, tmp_path):
    ds = runs[0]["SP"]
    index = 13
    ax = plot.shapes(ds, time=float(ds["time"][index]))
    rect, line = ax.patches
    assert (rect.get_label(), rect.get_gid(), line.get_label(), line.get_gid()) == ("body 1", "rect", "body 2", "line")
    corners = [[-0.2, -0.1], [0.2, -0.1], [0.2, 0.1], [-0.2, 0.1], [-0.2, -0.1]]
    np.testing.assert_allclose(rect.get_xy(), on_body(ds, 1, index, corners), atol=1e-12)
    np.testing.assert_allclose(line.get_xy(), on_body(ds, 2, index, [[0, -0.5], [0, 0.5]]), atol=1e-12)
    assert line.get_edgecolor() == to_rgba("red") and rect.get_edgecolor() == to_rgba("black")
    r, rP = ds["r"].values[index], ds["rP"].values[index]
    tip = on_body(ds, 2, index, [[0, -0.5]])[0]
    np.testing.assert_allclose(artist(ax, "centres").get_offsets(), r, atol=1e-12)
    points = np.column_stack(artist(ax, "points").get_data())
    np.testing.assert_allclose(points, np.vstack([rP, tip]), atol=1e-12)
    np.testing.assert_allclose(np.column_stack(artist(ax, "joints").get_data()), rP, atol=1e-12)
    # the spring F1 from point 2 to point 1, dashed; one line from a centre to each point on its body
    (spring,) = artist(ax, "springs").get_segments()
    np.testing.assert_allclose(spring, rP[[1, 0]], atol=1e-12)
    assert artist(ax, "springs").get_linestyle()[0][1] is not None
    spokes = artist(ax, "spokes").get_segments()
    np.testing.assert_allclose(np.array(spokes), [[r[0], rP[1]], [r[1], rP[2]], [r[1], tip]], atol=1e-12)
    assert artist(ax, "links").get_segments() == []
    assert [t.get_text() for t in ax.texts] == ["  (1)", "  (2)"]
    assert ax.get_xlim() == (-0.5, 2.0) and ax.get_ylim() == (-1.0, 0.5)
    assert "model SP" in ax.get_title()
    plot.save(ax, tmp_path / "sp.png")
    image = matplotlib.image.imread(tmp_path / "sp.png")
    assert image.shape[:2] == (480, 640) and image[..., :3].std() > 0.01


def test_cart_wheels_are_circles_around_their_centres(runs):
    ds = runs[0]["Cart_A"]
    ax = plot.shapes(ds)
    cart, rear, front = ax.patches
    assert [p.get_gid() for p in ax.patches] == ["rect", "circle", "circle"]
    r = ds["r"].values[-1]
    for wheel, centre in ((rear, r[1]), (front, r[2])):
        np.testing.assert_allclose(wheel.get_center(), centre, atol=1e-12)
        assert wheel.get_radius() == 0.1
    corners = [[-0.4, -0.05], [0.4, -0.05], [0.4, 0.05], [-0.4, 0.05], [-0.4, -0.05]]
    np.testing.assert_allclose(cart.get_xy(), on_body(ds, 1, -1, corners), atol=1e-12)
    assert artist(ax, "springs").get_segments() == [] and len(artist(ax, "spokes").get_segments()) == 4
    assert ax.get_xlim() == (-0.2, 3.0) and ax.get_ylim() == (-0.2, 0.6)
    assert plot.shapes(ds, limits=(0, 1, 0, 1)).get_xlim() == (0, 1)


def test_animate_writes_a_gif_with_a_frame_per_sample_shown(runs, tmp_path):
    ds = runs[0]["SP"]
    animation = plot.animate(ds, fps=10, speed=0.4)
    frames = frame_samples(ds, 10, 0.4)
    assert len(frames) == 11
    plot.save(animation, tmp_path / "sp.gif", fps=10)
    with Image.open(tmp_path / "sp.gif") as gif:
        assert gif.n_frames == len(frames) and gif.size == (640, 480)
        first = np.asarray(gif.convert("RGB"))
        gif.seek(gif.n_frames - 1)
        assert np.abs(np.asarray(gif.convert("RGB")).astype(int) - first).sum() > 0


def test_the_cli_draws_and_animates_a_dap_bc_folder(runs, tmp_path):
    folders = runs[1]
    for args, out in ((["plot", "shapes", folders["Cart_A"], "--time", "0.1"], "cart.png"),
                      (["animate", folders["SP"] / "000" / "history.nc", "--fps", "5"], "sp.gif")):
        result = CliRunner().invoke(app, [str(a) for a in args] + ["-o", str(tmp_path / out)])
        assert result.exit_code == 0, result.output
        assert (tmp_path / out).stat().st_size > 0


def test_a_history_without_a_drawing_description_says_so(runs):
    ds = runs[0]["SP"].drop_vars("body_shape")
    with pytest.raises(ModelError, match="does not describe its drawing"):
        plot.shapes(ds)


def test_a_colour_that_is_not_matlabs_is_reported_at_its_line(tmp_path):
    sp = copy_example("dap_bc/SP", tmp_path / "SP")
    animate = sp / "inAnimate.m"
    animate.write_text(animate.read_text().replace("Bodies(2).H = 1.0;", "Bodies(2).color = 'orange';"))
    with pytest.raises(ModelError, match="unknown 'orange'") as info:
        read_dapbc_folder(sp)
    assert info.value.file.endswith("inAnimate.m") and info.value.line == 10


def test_links_and_limits_without_a_window(runs):
    """A rev-rev joint is drawn as a line between its points (anim: cyan); without inAnimate's
    window the axes hold everything drawn."""
    ds = runs[0]["SP"]
    linked = ds.assign(joint_type=("joint", ["tran", "rev-rev"]))
    linked.attrs = {k: v for k, v in ds.attrs.items() if not k.startswith("animation_")}
    ax = plot.shapes(linked, time=0.2)
    index = int(np.abs(ds["time"].values - 0.2).argmin())
    (link,) = artist(ax, "links").get_segments()
    np.testing.assert_allclose(link, ds["rP"].values[index, [1, 2]], atol=1e-12)
    drawn = np.vstack([np.column_stack(artist(ax, "points").get_data()), *(p.get_xy() for p in ax.patches)])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x0 < drawn[:, 0].min() and drawn[:, 0].max() < x1 and y0 < drawn[:, 1].min() and drawn[:, 1].max() < y1
    assert ax.get_xlim() != (-0.5, 2.0)


@pytest.mark.parametrize("name", ["Rod", "AA"])
def test_models_without_joints_or_shapes_write_their_drawing(tmp_path, name):
    """Rod has no joints, AA no shapes: the description still goes through NetCDF."""
    data, coords, attrs = drawing_variables(read_dapbc_folder(copy_example(f"dap_bc/{name}", tmp_path / name)))
    xr.Dataset(data, coords=coords, attrs=attrs).to_netcdf(tmp_path / "drawing.nc", engine="netcdf4")
    with xr.open_dataset(tmp_path / "drawing.nc") as ds:
        assert ds.sizes["joint"] == (0 if name == "Rod" else 4)
        assert set(ds["body_shape"].values) == ({"line"} if name == "Rod" else {"none"})
        assert ds.attrs["animation_xmax"] == (1.5 if name == "Rod" else 0.9)
