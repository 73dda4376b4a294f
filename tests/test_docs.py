"""The documentation site builds with no warning, its description-format page lists every field
the reader accepts, and every gallery example ran and left its figure on its page."""

import os
import shutil
import subprocess
import sys

import pytest

from conftest import ROOT

from fetorsion.description import fields

pytestmark = [pytest.mark.slow, pytest.mark.fe]  # the gallery runs the FE examples (coarse meshes)

HTML = ROOT / "docs/_build/html"


@pytest.fixture(scope="module")
def site():
    # sphinx-gallery skips an example whose source it ran before: remove its output so that every
    # example runs in this build, as on a clean clone
    shutil.rmtree(ROOT / "docs/auto_examples", ignore_errors=True)
    env = dict(os.environ, FETORSION_DOCS_PYTHON=sys.executable)
    # -W: any warning fails the build; -E: read every page again, so no warning hides in a cache
    p = subprocess.run(["bash", "scripts/docs.sh", "-W", "-E"], cwd=ROOT, env=env, capture_output=True, text=True,
                       timeout=1200)
    assert p.returncode == 0, (p.stdout + p.stderr)[-4000:]
    return HTML


def test_every_field_is_on_the_built_pages(site):
    for page, sections in (("description-format.html", fields.CRANK_SECTIONS), ("chain-format.html", fields.CHAIN_SECTIONS)):
        html = (site / page).read_text()
        for s in sections:
            for f in s.fields:
                key = f.key[1:-1] if f.key.startswith("<") else f.key
                assert key in html, f"{page}: {s.header} {f.key}"


def test_every_example_ran_with_its_figure(site):
    for script in sorted((ROOT / "examples").glob("*.py")):
        html = (site / "auto_examples" / f"{script.stem}.html").read_text()
        assert f"sphx_glr_{script.stem}_001.png" in html, f"{script.name}: no figure on its page"
        assert (site / "_images" / f"sphx_glr_{script.stem}_001.png").is_file()
