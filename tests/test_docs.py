"""The documentation site builds with no warning, its description-format page lists every field
the reader accepts, and every gallery example ran and left its figure on its page (the site: the
session's one build, tests/conftest.py ``site``)."""

import pytest

from conftest import ROOT

from fetorsion.description import chain_fields, fields

pytestmark = [pytest.mark.slow, pytest.mark.fe]  # the gallery runs the FE examples (coarse meshes)


def test_every_field_is_on_the_built_pages(site):
    for page, sections in (("description-format.html", fields.CRANK_SECTIONS), ("chain-format.html", chain_fields.CHAIN_SECTIONS)):
        html = (site.html / page).read_text()
        for s in sections:
            for f in s.fields:
                key = f.key[1:-1] if f.key.startswith("<") else f.key
                assert key in html, f"{page}: {s.header} {f.key}"


def test_every_example_ran_with_its_figure(site):
    for script in sorted((ROOT / "examples").glob("*.py")):
        html = (site.html / "auto_examples" / f"{script.stem}.html").read_text()
        assert f"sphx_glr_{script.stem}_001.png" in html, f"{script.name}: no figure on its page"
        assert (site.html / "_images" / f"sphx_glr_{script.stem}_001.png").is_file()
