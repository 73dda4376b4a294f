"""Sensitivity of f1 to the reconstructed inputs, against exact scaling laws."""

import copy
import math

import pytest

import fetorsion
from fetorsion.description.crank import parse_crank
from fetorsion.errors import DescriptionError
from fetorsion.studies.sensitivity import run_sensitivity, with_values

from conftest import GEOMETRY, read_raw


def only(raw, uncertainty):
    raw = copy.deepcopy(raw)
    raw["uncertainty"] = uncertainty
    return parse_crank(raw)


def test_with_values_changes_only_the_named_field():
    crank = fetorsion.load(str(GEOMETRY / "peugeot_glx.toml"))
    changed = with_values(crank, {"webs.*.thickness": 21.0, "pins.2.length": 25.0})
    assert all(w.thickness == pytest.approx(0.021) for w in changed.webs)
    assert changed.pins[1].length == pytest.approx(0.025) and changed.pins[0].length == crank.pins[0].length
    assert changed.journals == crank.journals and crank.webs[0].thickness == pytest.approx(0.023)
    # the variant shares the tables off its changed paths: the nominal's own data stays as read
    assert crank.raw == fetorsion.load(str(GEOMETRY / "peugeot_glx.toml")).raw
    assert changed.raw["pins"][0] is crank.raw["pins"][0] and changed.raw["pins"][1] is not crank.raw["pins"][1]


def test_f1_scales_with_sqrt_of_youngs_modulus():
    # Every stiffness is G·J/L_e with G ∝ E and no inertia depends on E: f ∝ √E exactly.
    crank = only(read_raw("renault21.toml"), {"material.youngs_modulus_pa": [150e9, 230e9]})
    row = run_sensitivity(crank).rows[0]
    assert row.f1_high_hz / row.f1_low_hz == pytest.approx(math.sqrt(230 / 150), rel=1e-12)


def test_f1_scales_with_inverse_sqrt_of_density_without_attachments():
    # Crank alone: every inertia ∝ ρ, so f ∝ 1/√ρ exactly.
    crank = only(read_raw("peugeot_glx.toml"), {"material.density_kgm3": [7000.0, 8000.0]})
    row = run_sensitivity(crank).rows[0]
    assert row.f1_low_hz / row.f1_high_hz == pytest.approx(math.sqrt(8000 / 7000), rel=1e-12)


def test_group_moves_members_together_and_band_brackets_each_input():
    crank = fetorsion.load(str(GEOMETRY / "renault21.toml"))
    s = run_sensitivity(crank)
    material = next(r for r in s.rows if r.field == "material")
    # Cast iron: E/ρ falls from 210/7850 to 165/7100, so f1 falls by about √ of that ratio.
    ratio = math.sqrt((165 / 7100) / (210 / 7850))
    assert material.f1_low_hz / s.f1_hz == pytest.approx(ratio, rel=0.02)  # attachments do not scale with ρ
    lo, hi = s.band_hz
    assert all(lo <= min(r.f1_low_hz, r.f1_high_hz) and max(r.f1_low_hz, r.f1_high_hz) <= hi
               for r in s.rows)


def test_group_member_rules():
    raw = read_raw("renault21.toml")
    raw["uncertainty"] = {"mat": {"material.density_kgm3": [8000.0, 9000.0]}}
    with pytest.raises(DescriptionError) as info:
        parse_crank(raw)
    assert "uncertainty.mat.material.density_kgm3" in str(info.value)


@pytest.mark.fe
def test_fe_check_material_follows_exact_scaling():
    # Crank alone, same geometry and mesh: FE f1 ∝ √(E/ρ) exactly, as in the lumped model.
    from fetorsion.studies.sensitivity import fe_check
    crank = only(read_raw("peugeot_glx.toml"),
                 {"material": {"material.youngs_modulus_pa": [165e9, 212e9], "material.density_kgm3": [7100.0, 7870.0]}})
    row = fe_check(crank, run_sensitivity(crank), count=1, mesh_size=0.03)[0]
    expected = math.sqrt((212 / 7870) / (165 / 7100))
    assert row["fe_f1_high_hz"] / row["fe_f1_low_hz"] == pytest.approx(expected, rel=1e-6)
    assert row["fe_change_percent"] == pytest.approx(row["lumped_change_percent"], rel=1e-6)
