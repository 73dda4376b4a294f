"""Plausible cranks of new users (issue 53): the generator itself, and a seeded sample of the
sweep (benchmarks/bench_plausible_sweep.py, docs/plausible-cranks.md) through both FE steps."""

import numpy as np
import pytest

from fetorsion.description.crank import parse_crank
from fetorsion.description.plausibility import plausibility_warnings
from fetorsion.description.samples import LAYOUTS, plausible_crank, plausible_cranks


def test_draws_are_valid_plausible_and_repeatable():
    """Every draw passes the reader and warns on nothing (the plausibility ranges are the
    reader's own), each layout is drawn, each feature on and off; one seed, one crank set."""
    raws = plausible_cranks(7, 120)
    cranks = [parse_crank(raw, source=f"draw {i}") for i, raw in enumerate(raws)]
    assert all(not plausibility_warnings(c) for c in cranks)
    assert {c.engine.cylinders for c in cranks} == set(LAYOUTS)
    for key in ("fillets", "oil_holes"):
        assert 0 < sum(key in raw for raw in raws) < len(raws), key
    assert 0 < sum("counterweight_radius" in raw["webs"][0] for raw in raws) < len(raws)
    assert plausible_cranks(7, 3) == raws[:3]
    assert plausible_crank(np.random.default_rng(1)) != plausible_crank(np.random.default_rng(2))


def test_vee_draws_are_valid_and_fire_as_their_layout():
    """Vees of 6-12 cylinders (two rods side by side on each pin): every draw is read without a
    warning; the V8, V10 and V12 fire every 720°/z, the 60° V6 on three 120° throws does not (it
    would need split pins)."""
    from fetorsion.description.samples import VEE_LAYOUTS
    from fetorsion.excitation.torque import firing_angles

    cranks = [parse_crank(raw, source=f"vee {i}") for i, raw in enumerate(plausible_cranks(7, 40, "vee"))]
    assert all(not plausibility_warnings(c) for c in cranks)
    assert {c.engine.cylinders for c in cranks} == set(VEE_LAYOUTS)
    for c in cranks:
        z = c.engine.cylinders
        gaps = np.diff(np.sort(np.degrees(firing_angles(c.engine))))
        assert c.throws == z // 2 and (z == 6) != np.allclose(gaps, 720.0 / z)


def test_a_drilling_at_its_fillet_is_refused_before_any_fe():
    """The sweep's refusal path: a crank whose journal drilling is tangent to its fillets (length
    2 × fillet + drilling) is refused by the reader, in its own words, before any FE."""
    from fetorsion.studies.plausible import try_crank

    raw = plausible_crank(np.random.default_rng(3), 4)
    d, r = 6.0, 3.0
    raw["fillets"] = {"journal": r, "pin": 2.0}
    raw["oil_holes"] = {"diameter": d, "in_journals": True, "in_pins": False}
    for j in raw["journals"]:
        j["length"] = 2 * r + d
    row = try_crank(raw, "tangent drilling")
    assert row["status"] == "refused" and row["step"] == "read"
    assert "journals.1.length" in row["message"] and "touches the 3.0 mm fillets" in row["message"]


@pytest.mark.fe
@pytest.mark.slow
@pytest.mark.parametrize("layout, index", [("in-line", 0), ("in-line", 5), ("vee", 0)])
def test_a_sample_of_the_sweep_meshes_and_solves(layout, index):
    """Three cranks of the sweeps (seed 53: in-line #0 a five-cylinder with hollow pins and
    counterweights, #5 a three-cylinder with drillings; vee #0 a V8 with fillets) through both FE
    steps at the default mesh: they mesh and give a mode that carries torsion (the whole sweeps:
    benchmarks/bench_plausible_sweep.py, docs/plausible-cranks.md)."""
    from fetorsion.studies.plausible import try_crank

    row = try_crank(plausible_cranks(53, index + 1, layout)[index], f"plausible {layout} seed 53 #{index}")
    assert row["status"] == "ok", row
    assert row["modal"]["f1_hz"] > 0 and row["lumped, fe webs"]["f1_hz"] > 0


def test_the_first_mode_carrying_torsion_is_found_below_the_mostly_torsional_one():
    """The sweep's crank #6 (a bare flat four, 88 821 DOF): its modes 1-11 as `fetorsion modal` gave
    them (frequency, torsion share). The first with 10 % torsion is mode 4 at 1019.8 Hz (28 %, the
    lumped chain's 1074 Hz, +5.3 %); with 30 % the rule skips to mode 10; the first mostly torsional
    one is mode 11 (2905.8 Hz)."""
    from fetorsion.errors import FetorsionError
    from fetorsion.modes import TORSION_SHARE_NOTED, first_with_torsion

    hz = [364.3, 521.3, 943.0, 1019.8, 1093.0, 1356.6, 1522.6, 1847.1, 2138.5, 2634.9, 2905.8]
    torsion = [0.000, 0.021, 0.000, 0.280, 0.000, 0.169, 0.000, 0.142, 0.000, 0.474, 0.507]
    fractions = np.array([[t, 1 - t, 0.0] for t in torsion])
    assert first_with_torsion(hz, fractions, TORSION_SHARE_NOTED, "modes") == 1019.8
    assert first_with_torsion(hz, fractions, 0.3, "modes") == 2634.9
    with pytest.raises(FetorsionError, match="no mode with 60 % torsion among the 11 modes"):
        first_with_torsion(hz, fractions, 0.6, "modes")
