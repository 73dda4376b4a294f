"""Sphinx configuration of the fetorsion documentation (built by scripts/docs.sh).

Sphinx rather than MkDocs: the docstrings are numpydoc, which numpydoc renders as it is written;
sphinx-gallery runs the examples at build time and puts their figures on the page; myst-parser
reads the existing Markdown notes unchanged, equations included; and pydata-sphinx-theme is the
theme of the SciPy-ecosystem sites engineers already know.
"""

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(DOCS / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import fetorsion  # noqa: E402
from fetorsion.description import chain_fields, fields  # noqa: E402

# The description-format and chain-format pages include these: generated from the declarations
# the reader itself checks against, so that the documented fields cannot drift from the reader.
GENERATED = DOCS / "_generated"
GENERATED.mkdir(exist_ok=True)
for name, sections in (("crank-fields.md", fields.CRANK_SECTIONS), ("chain-fields.md", chain_fields.CHAIN_SECTIONS)):
    text = fields.markdown(sections)
    target = GENERATED / name
    if not target.exists() or target.read_text() != text:  # unchanged: no rebuild of the page
        target.write_text(text)

project = "fetorsion"
author = "the fetorsion authors"
copyright = "the fetorsion authors, MIT licence"
release = version = fetorsion.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "_ext", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.json", "auto_examples/*.md5"]

myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

autosummary_generate = True
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"  # numpydoc's Parameters sections say the types and units
numpydoc_show_class_members = False
numpydoc_validation_checks = set()

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r".*\.py$",  # execute every example
    "reset_argv": "gallery_argv.reset_argv",
    "abort_on_example_error": True,
    "download_all_examples": False,
    "show_memory": False,
    "image_scrapers": ("matplotlib",),
    "within_subsection_order": "FileNameSortKey",
    "min_reported_time": 0,
}

html_theme = "pydata_sphinx_theme"
html_title = "fetorsion"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
html_static_path = []


def _lumped_validation() -> str:
    """f1 of every lumped partition of both reference cranks against the measurement, computed
    now (milliseconds each): the validation page's first table cannot go stale."""
    rows = ["| crank | measured f1 [Hz] | model | " + " | ".join(METHODS) + " |",
            "|---|---|---|" + "---|" * len(METHODS)]
    for name in ("renault21", "peugeot_glx"):
        crank = fetorsion.load(ROOT / "geometry" / f"{name}.toml")
        measured = float(crank.notes["measured_first_torsional_hz"])
        for dof in fetorsion.PARTITIONS:
            cells = []
            for method in METHODS:
                f = fetorsion.lumped(crank, dof, stiffness=method).frequencies_hz[0]
                cells.append(f"{f:.1f} ({100 * (f / measured - 1):+.1f} %)")
            rows.append(f"| {crank.name} | {measured:g} | {dof} DOF | " + " | ".join(cells) + " |")
    return ("First torsional frequency, free-free, Hz (error against the measurement of [Seyedalian]); "
            "web stiffness by each classical method:\n\n" + "\n".join(rows) + "\n")


METHODS = ("carter", "ker-wilson", "beam")
_text = _lumped_validation()
if not (GENERATED / "lumped-validation.md").exists() or (GENERATED / "lumped-validation.md").read_text() != _text:
    (GENERATED / "lumped-validation.md").write_text(_text)
