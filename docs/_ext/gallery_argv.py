"""The command-line arguments the documentation's gallery runs each example with.

The FE examples take a mesh size; the gallery runs them on a coarse mesh so that each finishes in
under a minute when the site is built (tests/test_examples.py checks what they print there).
Paths are absolute: sphinx-gallery runs every example from inside examples/.
"""

import os
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

ARGV = {
    "lumped_vs_fe.py": [str(ROOT / "geometry/peugeot_glx.toml"), "30"],
    "web_thickness_study.py": ["40"],
    "render_first_torsional.py": [str(ROOT / "geometry/renault21.toml"), "{tmp}", "30"],
}


def reset_argv(gallery_conf, script_vars):
    """sphinx-gallery's ``reset_argv`` hook: the arguments after the script's name."""
    args = ARGV.get(Path(script_vars["src_file"]).name, [])
    # pictures the script writes go to a temporary folder, not into the source tree (the one the
    # tests name, FETORSION_GALLERY_OUT, where they look at them)
    out = os.environ.get("FETORSION_GALLERY_OUT") or tempfile.mkdtemp(prefix="fetorsion-gallery-")
    return [out if a == "{tmp}" else a for a in args]
