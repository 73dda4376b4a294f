"""The web report in a real headless browser (Debian's chromium, installed by scripts/setup.sh,
driven by Playwright): the 3D mode-shape view renders and animates, the Campbell diagram is
drawn with its crossings, and the console shows no error. Skips, saying why, where no
browser can be had."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from conftest import GEOMETRY, plain, toml_text
from fetorsion.cli import main

BROWSER = next((shutil.which(b) for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)
try:
    from playwright.sync_api import sync_playwright
except ImportError:  # pragma: no cover - the test extra installs it
    sync_playwright = None
pytestmark = [pytest.mark.fe, pytest.mark.slow,  # a whole run with FE (~40 s) behind the page
              pytest.mark.skipif(BROWSER is None, reason="no chromium: scripts/setup.sh installs it with apt-get; "
                                 "without it the browser test of report.html cannot run"),
              pytest.mark.skipif(sync_playwright is None, reason="playwright is not installed (pip install -e '.[test]')")]
# Software WebGL, so the test needs no GPU.
ARGS = ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]


def plain_copy(folder, name="renault21.toml"):
    """A reference crank without fillets and drillings (cheap to mesh), as a description file."""
    path = folder / name
    path.write_text(toml_text(plain(name).raw))
    return path


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A whole ``fetorsion run`` (FE included, coarse mesh): its report.html is what is tested."""
    folder = tmp_path_factory.mktemp("html")
    assert main(["run", str(plain_copy(folder)), "--out", str(folder / "report"), "--mesh-size", "30"]) == 0
    return folder / "report" / "report.html"


@pytest.fixture(scope="module")
def browser():
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=BROWSER, args=ARGS)
        yield b
        b.close()


@pytest.fixture
def opened(browser, report):
    """The report in a fresh page, with every console message and page error collected."""
    page = browser.new_page(viewport={"width": 1300, "height": 900})
    messages = []
    page.on("console", lambda m: messages.append((m.type, m.text)))
    page.on("pageerror", lambda e: messages.append(("pageerror", str(e))))
    page.goto(report.as_uri())
    yield page, messages
    page.close()


def pixels(png: bytes) -> np.ndarray:
    import io

    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=float)


def colourful_share(rgb: np.ndarray) -> float:
    """Share of strongly coloured pixels (max - min channel > 80 of 255): the surface is coloured
    by |u| on a rainbow scale; a blank canvas is white or grey."""
    return float(np.mean(rgb.max(axis=2) - rgb.min(axis=2) > 80))


def errors(messages) -> list:
    return [m for m in messages if m[0] in ("error", "pageerror")]


def test_mode_view_renders_and_animates(opened):
    page, messages = opened
    canvas = page.locator("#modes .gl-container canvas").first  # the WebGL canvas of the 3D scene
    canvas.wait_for(timeout=60_000)
    page.wait_for_timeout(1000)
    still = pixels(canvas.screenshot())
    assert colourful_share(still) > 0.05, "the 3D view's canvas is blank"
    # The deformation-scale slider redraws the surface at once (scale 1 -> 3)...
    page.locator("#modes-scale").fill("3")
    page.wait_for_timeout(500)
    scaled = pixels(canvas.screenshot())
    assert np.mean(np.abs(scaled - still).max(axis=2) > 40) > 0.002, "the scale slider did not move the surface"
    # ... and 'play' animates the oscillation: some later frame differs (polled, the machine may be slow).
    page.click("#modes-play")
    for _ in range(20):
        page.wait_for_timeout(250)
        if np.mean(np.abs(pixels(canvas.screenshot()) - scaled).max(axis=2) > 40) > 0.002:
            break
    else:
        pytest.fail("the oscillation did not animate")
    assert not errors(messages), errors(messages)


def test_campbell_plot_is_present_with_its_crossings(opened):
    page, messages = opened
    page.locator("#campbell .main-svg").first.wait_for(timeout=60_000)
    assert page.locator("#campbell .point").count() >= 5  # the crossings' markers
    assert "crossings" in page.locator("#campbell").inner_text()
    assert not errors(messages), errors(messages)


def test_page_is_self_contained_and_small(report):
    text = report.read_text()
    assert "<script src=" not in text and 'src="http' not in text
    assert report.stat().st_size < 25 * 2**20


def test_modal_and_campbell_write_their_own_pages(tmp_path, capsys):
    assert main(["campbell", str(GEOMETRY / "renault21.toml"), "--html", str(tmp_path / "c.html")]) == 0
    assert 'id="campbell"' in (tmp_path / "c.html").read_text()
    crank = plain_copy(tmp_path)
    capsys.readouterr()
    assert main(["modal", str(crank), "--mesh-size", "30", "--modes", "8", "--html", str(tmp_path / "m.html")]) == 0
    err = capsys.readouterr().err  # issue 54: a progress line per stage, with the share done
    for k, name in enumerate(("meshing", "assembling", "factorising", "eigensolving")):
        assert f"modal: {name} (stage {k + 1} of 4, " in err, err
    page = (tmp_path / "m.html").read_text()
    # the 3D mode view with its controls, offering each torsional and bending mode of the table
    assert 'id="modes-mode"' in page and 'id="modes-play"' in page and "fetorsionModeView(\"modes\"" in page
    assert page.count("<option") >= 2 and "torsional" in page
