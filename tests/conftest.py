import atexit
import copy
import os
import shutil
import tempfile
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GEOMETRY = ROOT / "geometry"

# Studies keep every sample's result in a store (default ~/.cache/fetorsion/samples): the tests,
# and the command lines they start, use a store of their own that lives as long as the session.
# A process the session starts that imports this file again (a Dask worker unpickling a test's
# model, a spawned studies process) inherits the store and makes none of its own: it would leave
# it behind, since such processes end without running their exit handlers.
if "FETORSION_TEST_STORE" not in os.environ:
    os.environ["FETORSION_STORE"] = os.environ["FETORSION_TEST_STORE"] = tempfile.mkdtemp(prefix="fetorsion-test-store-")
    atexit.register(shutil.rmtree, os.environ["FETORSION_STORE"], ignore_errors=True)


def read_raw(name: str) -> dict:
    with open(GEOMETRY / name, "rb") as fh:
        return tomllib.load(fh)


@pytest.fixture
def glx_raw():
    return read_raw("peugeot_glx.toml")


@pytest.fixture
def renault_raw():
    return read_raw("renault21.toml")


def simple_crank_raw(cylinders: int = 4) -> dict:
    """A hand-made crank with round numbers (mm), every journal/pin/web alike."""
    n = cylinders
    assert 1 <= n <= 4, "flat cranks of up to four throws"
    return copy.deepcopy({
        "units": {"length": "mm"},
        "material": {"youngs_modulus_pa": 200e9, "poisson_ratio": 0.25, "density_kgm3": 8000.0},
        "engine": {"cylinders": n, "stroke": 80.0, "rod_length": 140.0,
                   "crank_angles_deg": [0.0, 180.0, 180.0, 0.0][:n],
                   "firing_order": [1, 3, 4, 2] if n == 4 else list(range(1, n + 1))},
        "journals": [{"diameter": 60.0, "length": 25.0}] * (n + 1),
        "pins": [{"diameter": 50.0, "length": 24.0}] * n,
        "webs": [{"thickness": 20.0, "width_journal": 90.0, "width_pin": 70.0}] * (2 * n),
        "front": [{"diameter": 40.0, "length": 50.0}],
        "rear": [{"diameter": 80.0, "length": 15.0}],
    })


def plain(crank_or_path):
    """A crank (or the one in a reference file) without fillets, oil holes and uncertainty
    ranges: what eq. 14-17 and the web outline describe, and cheap to mesh coarsely."""
    import fetorsion

    crank = fetorsion.load(GEOMETRY / crank_or_path) if isinstance(crank_or_path, (str, Path)) else crank_or_path
    return fetorsion.with_values(crank, {}, details=False)


@pytest.fixture(scope="session")
def condensed_plain_renault():
    """(crank, fillets, condensed crank): the Renault 21 without fillets or drillings, condensed at
    30 mm with a cut at every fillet; built once for every test module that takes it (each took
    its own before: about 7 s a build)."""
    from fetorsion.design.stress import fillet_cuts, fillets_of
    from fetorsion.fe.condensed import run_condensed

    crank = plain("renault21.toml")
    fillets = fillets_of(crank)
    return crank, fillets, run_condensed(crank, 0.03, cuts=fillet_cuts(crank, fillets))


def assert_picture(path, min_ink: float = 0.005, min_colours: int = 3) -> None:
    """``path`` is a PNG that shows something: enough pixels differ from its background
    (the most common colour) and it holds several colours, so a blank or one-colour image fails."""
    import numpy as np
    from PIL import Image

    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    pixels = np.asarray(Image.open(path).convert("RGB")).reshape(-1, 3)
    colours, counts = np.unique(pixels, axis=0, return_counts=True)
    ink = 1.0 - counts.max() / len(pixels)
    assert ink >= min_ink, f"{path}: only {ink:.2%} of the pixels differ from the background"
    assert len(colours) >= min_colours, f"{path}: {len(colours)} colours"


def toml_text(data: dict) -> str:
    """A description dict as TOML (tables, arrays of tables, numbers, strings, lists): enough to
    write the test cranks as files for the command line."""

    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(value(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{ " + ", ".join(f'"{k}" = {value(x)}' for k, x in v.items()) + " }"
        return repr(float(v)) if isinstance(v, float) else str(v)

    lines = []
    for key, v in data.items():
        if isinstance(v, dict):
            lines += [f"[{key}]"] + [f'"{k}" = {value(x)}' for k, x in v.items()] + [""]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for item in v:
                lines += [f"[[{key}]]"] + [f'"{k}" = {value(x)}' for k, x in item.items()] + [""]
        else:
            lines.insert(0, f'"{key}" = {value(v)}')
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="session")
def site(tmp_path_factory):
    """The documentation site built once for the session (every gallery example run in it, with
    the arguments of docs/_ext/gallery_argv.py): ``html`` its folder, ``pictures`` where the
    examples that write pictures wrote them. tests/test_docs.py reads the pages;
    tests/test_examples.py what the examples printed (a run of its own would repeat the gallery's)."""
    import os
    import shutil
    import subprocess
    import sys
    from types import SimpleNamespace

    # sphinx-gallery skips an example whose source it ran before: remove its output so that every
    # example runs in this build, as on a clean clone
    shutil.rmtree(ROOT / "docs/auto_examples", ignore_errors=True)
    pictures = tmp_path_factory.mktemp("gallery")
    env = dict(os.environ, FETORSION_DOCS_PYTHON=sys.executable, FETORSION_GALLERY_OUT=str(pictures))
    # -W: any warning fails the build; -E: read every page again, so no warning hides in a cache
    p = subprocess.run(["bash", "scripts/docs.sh", "-W", "-E"], cwd=ROOT, env=env, capture_output=True, text=True,
                       timeout=1200)
    assert p.returncode == 0, (p.stdout + p.stderr)[-4000:]
    return SimpleNamespace(html=ROOT / "docs/_build/html", pictures=pictures, examples=ROOT / "docs/auto_examples")
