"""What the example scripts print, as the documentation's gallery ran them (the session's one site
build: tests/conftest.py ``site``, with docs/_ext/gallery_argv.py's coarse meshes), checked
against the API; running them again here repeated the gallery's three minutes."""

import re
from pathlib import Path

import pytest

import fetorsion

from conftest import ROOT, assert_picture

pytestmark = [pytest.mark.slow, pytest.mark.fe]


def numbers(line: str) -> list[float]:
    return [float(x) for x in re.findall(r"[-+]?\d+(?:\.\d+)?", line)]


def lines_with(text: str, word: str) -> list[str]:
    return [line for line in text.splitlines() if word in line]


# What each script prints, checked against fetorsion's API run here and against the relations the
# printed numbers must obey; printed values carry their print rounding (half the last digit).
def check_lumped_vs_fe(out: str):
    crank = fetorsion.load(ROOT / "geometry/peugeot_glx.toml")
    f_fe = numbers(lines_with(out, "FE (")[0])[-1]
    for line in lines_with(out, "-DOF lumped"):
        dof, f, pct = numbers(line)[0], numbers(line)[-2], numbers(line)[-1]
        assert f == pytest.approx(fetorsion.lumped(crank, int(dof)).frequencies_hz[0], abs=0.05)
        assert pct == pytest.approx(100 * (f / f_fe - 1), abs=0.06)


def check_web_thickness(out: str):
    crank = fetorsion.load(ROOT / "geometry/peugeot_glx.toml")
    rows = [numbers(line) for line in out.splitlines() if re.fullmatch(r"\s*[\d.]+\s+[\d.]+\s*", line)]
    assert len(rows) == 6
    for h, f in rows:
        variant = fetorsion.with_values(crank, {"webs.*.thickness": h})
        assert f == pytest.approx(fetorsion.lumped(variant, 17).frequencies_hz[0], abs=0.05)
    fe = [numbers(line)[-1] for line in lines_with(out, "FE at")]
    # the FE and the lumped model agree on which end of the sweep is stiffer
    assert (fe[1] > fe[0]) == (rows[-1][1] > rows[0][1])


def check_campbell(out: str):
    res = fetorsion.run_campbell(fetorsion.load(ROOT / "geometry/renault21.toml"))
    order, rpm, severity = numbers(lines_with(out, "worst:")[0])
    worst = max((c for c in res.crossings if c.in_range), key=lambda c: c.severity)
    assert (order, rpm) == (pytest.approx(worst.order), pytest.approx(worst.rpm, abs=0.5))
    assert severity == pytest.approx(worst.severity, abs=5e-4)


def check_mendes(out: str):
    chain = fetorsion.load(ROOT / "examples/mendes2008/mwm6_chain.toml")
    order, mode, f, rpm = numbers(lines_with(out, "major-order resonance")[0])
    assert mode == 1 and f == pytest.approx(fetorsion.lumped(chain).frequencies_hz[0], abs=0.05)
    assert order * rpm / 60 == pytest.approx(f, rel=1e-3)  # a crossing: order x speed = the mode's frequency
    for line in lines_with(out, "published peak"):
        peak, peak_rpm, model, model_rpm, pct, drpm = numbers(line.split("published peak")[1])
        assert pct == pytest.approx(100 * (model / peak - 1), abs=0.2) and drpm == model_rpm - peak_rpm


CHECKS = {"examples/lumped_vs_fe.py": check_lumped_vs_fe, "examples/web_thickness_study.py": check_web_thickness,
          "examples/campbell_renault.py": check_campbell, "examples/mendes2008_six_cylinder.py": check_mendes}


def printed(site, script: str) -> str:
    """What an example printed in the gallery's run: every output block of its page's source."""
    out, inside = [], False
    for line in (site.examples / f"{Path(script).stem}.rst").read_text().splitlines():
        if line.strip() == ".. code-block:: none":
            inside = True
        elif inside and line and not line.startswith("    "):
            inside = False
        elif inside:
            out.append(line[4:])
    return "\n".join(out)


@pytest.mark.parametrize("script", list(CHECKS))
def test_example_prints_what_the_api_gives(site, script):
    text = printed(site, script)
    assert text.strip(), f"{script}: no output on its gallery page"
    CHECKS[script](text)


def test_render_example(site):
    assert_picture(site.pictures / "first_torsional.png", min_ink=0.05)
    assert_picture(site.pictures / "lumped_17dof_modes.png")
