"""The web report in a real headless browser (Debian's chromium, installed by scripts/setup.sh):
the 3D mode-shape view renders something, the Campbell diagram is drawn, and the console
shows no error. Skips, saying why, where no browser is installed."""

from __future__ import annotations

import shutil
import subprocess

import numpy as np
import pytest

from conftest import GEOMETRY, plain, toml_text
from fetorsion.cli import main

BROWSER = next((b for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)
pytestmark = [pytest.mark.fe, pytest.mark.skipif(BROWSER is None, reason="no chromium: install it with "
                                                 "scripts/setup.sh (apt-get install chromium) to run the browser test")]
FLAGS = ["--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--enable-logging=stderr", "--v=0", "--virtual-time-budget=8000"]


def browse(page, *args) -> tuple[str, str]:
    """Open ``page``; (standard output, the browser's log with the page's console)."""
    p = subprocess.run([BROWSER, *FLAGS, *args, f"file://{page}"], capture_output=True, text=True, timeout=180)
    return p.stdout, p.stderr


def console_errors(log: str) -> list[str]:
    return [line for line in log.splitlines() if "CONSOLE" in line and ("Uncaught" in line or "Error" in line)]


def colourful_share(png) -> float:
    """Share of pixels with a saturated colour: the mode view's colour scale, never a blank
    white or grey canvas (HSV saturation above 0.35)."""
    from PIL import Image

    hsv = np.asarray(Image.open(png).convert("RGB").convert("HSV"), dtype=float)
    return float(np.mean(hsv[..., 1] > 0.35 * 255))


def plain_copy(folder):
    """The Peugeot crank without fillets and drillings (cheap to mesh), as a description file."""
    path = folder / "glx.toml"
    path.write_text(toml_text(plain("peugeot_glx.toml").raw))
    return path


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    folder = tmp_path_factory.mktemp("html")
    assert main(["modal", str(plain_copy(folder)), "--mesh-size", "30", "--modes", "10", "--html", str(folder / "modes.html")]) == 0
    assert main(["campbell", str(GEOMETRY / "renault21.toml"), "--html", str(folder / "campbell.html")]) == 0
    return folder


def test_mode_view_renders_in_the_browser(pages):
    shot = pages / "modes.png"
    _, log = browse(pages / "modes.html", "--window-size=1200,900", f"--screenshot={shot}")
    assert shot.exists(), log[-2000:]
    # The 3D view (coloured by |u|) fills the top of the page: a blank canvas would leave it white.
    assert colourful_share(shot) > 0.03
    assert not console_errors(log), console_errors(log)


def test_campbell_plot_is_present_with_its_crossings(pages):
    dom, log = browse(pages / "campbell.html", "--dump-dom")
    assert 'id="campbell"' in dom and "js-plotly-plot" in dom
    assert dom.count('class="point plotly-customdata"') >= 5  # the crossings' markers, SVG drawn by plotly
    assert "crossings" in dom
    assert not console_errors(log), console_errors(log)


def test_page_is_self_contained(pages):
    text = (pages / "modes.html").read_text()
    assert "<script src=" not in text and "https://" not in text.split("</script>")[-1]
    assert (pages / "modes.html").stat().st_size < 25 * 2**20
