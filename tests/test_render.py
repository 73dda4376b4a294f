"""Off-screen mode images: a real picture of the expected size, drawn without a display."""

import numpy as np
import pytest

from fetorsion.report.render import mode_scale, render_gif, render_mode

pytestmark = [pytest.mark.fe]


def twisted_bar(n=(13, 4, 4)):
    """A tetrahedral bar along x and a twist displacement about the x axis."""
    import pyvista as pv
    grid = pv.ImageData(dimensions=n, spacing=(0.02, 0.01, 0.01), origin=(0.0, -0.015, -0.015)).triangulate()
    tets = grid.cells.reshape(-1, 5)[:, 1:]
    nodes = np.asarray(grid.points)
    angle = 0.5 * nodes[:, 0] / nodes[:, 0].max()
    u = np.column_stack([np.zeros(len(nodes)), -angle * nodes[:, 2], angle * nodes[:, 1]])
    return nodes, tets, u


def test_render_mode_image(tmp_path):
    from PIL import Image
    nodes, tets, u = twisted_bar()
    out = render_mode(nodes, tets, u, tmp_path / "mode.png", title="mode 1: 123.4 Hz, torsional",
                      window_size=(800, 400))
    img = np.asarray(Image.open(out).convert("RGB"))
    assert img.shape == (400, 800, 3)
    not_white = np.any(img < 240, axis=2)
    # Both views hold a drawn bar: each half has foreground pixels, and far from all of them.
    for half in (not_white[:, :400], not_white[:, 400:]):
        assert 0.005 < half.mean() < 0.6
    assert not list(tmp_path.glob(".*tmp*"))  # no temporary file left behind


def test_render_gif(tmp_path):
    from PIL import Image
    nodes, tets, u = twisted_bar()
    out = render_gif(nodes, tets, u, tmp_path / "mode.gif", frames=4, window_size=(320, 240))
    with Image.open(out) as gif:
        assert gif.n_frames == 4 and gif.size == (320, 240)


def test_mode_scale_makes_peak_a_fraction_of_size():
    nodes, _, u = twisted_bar()
    s = mode_scale(nodes, u, 0.1)
    assert np.linalg.norm(u * s, axis=1).max() == pytest.approx(0.1 * np.ptp(nodes, axis=0).max())
