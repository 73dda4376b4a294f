"""IACS UR M68's permissible torsional vibration stresses (design/shaft_limits.py) against a
worked shaft done by hand: every factor written out with its own numbers, not the module's."""

from __future__ import annotations

import json
import math

import pytest

from fetorsion.description.marine import CK_FACTORS
from fetorsion.design.shaft_limits import shaft_limit
from fetorsion.errors import ParameterError


def test_a_keyed_alloy_shaft_below_the_knee_by_hand():
    # An intermediate shaft with a keyway on a tapered connection (C_K 0.6), d = 350 mm, an alloy
    # steel of σ_B 850 N/mm² (capped at 800 for the formula), at 70 % of the rated speed.
    r = shaft_limit("keyway_tapered", 0.350, 850e6, 0.70, material="alloy")
    cd = 0.35 + 0.93 * 350.0 ** -0.2            # = 0.638184 (350^0.2 = 3.22711)
    tau_c = (800.0 + 160.0) / 18.0 * 0.6 * cd * (3.0 - 2.0 * 0.70**2)  # 53.333 · 0.6 · 0.63818 · 2.02
    tau_t = 1.7 * tau_c / math.sqrt(0.6)
    assert cd == pytest.approx(0.638184, abs=2e-6) and tau_c == pytest.approx(41.2522, abs=2e-4)
    assert tau_t == pytest.approx(90.536, abs=2e-3)
    assert r.sigma_b_pa == 800e6 and r.sigma_b_stated_pa == 850e6 and r.ck == 0.6
    assert r.cd == pytest.approx(cd, rel=1e-9)
    assert r.tau_c_pa == pytest.approx(tau_c * 1e6, rel=1e-9)
    assert r.tau_t_pa == pytest.approx(tau_t * 1e6, rel=1e-9)


def test_above_the_knee_the_speed_factor_is_1_38_and_no_transient_limit():
    # a plain intermediate shaft (integral flange, C_K 1), d = 200 mm, carbon steel 500 N/mm², λ 0.95
    r = shaft_limit("integral_flange", 0.200, 500e6, 0.95)
    tau_c = (500.0 + 160.0) / 18.0 * 1.0 * (0.35 + 0.93 * 200.0 ** -0.2) * 1.38
    assert r.tau_c_pa == pytest.approx(tau_c * 1e6, rel=1e-9)
    assert r.tau_t_pa is None  # no barred range above λ 0.8 in a propulsion line
    # the two branches meet at λ = 0.9: 3 − 2 · 0.81 = 1.38
    below = shaft_limit("integral_flange", 0.200, 500e6, 0.9 - 1e-12).tau_c_pa
    assert below == pytest.approx(r.tau_c_pa, rel=1e-9)
    # a carbon steel stronger than 760 N/mm² is taken at 760
    assert shaft_limit("shrink_fit", 0.2, 900e6, 0.5).sigma_b_pa == 760e6
    json.dumps(r.to_dict())
    assert "τ_C" in r.table()


def test_the_read_rows_of_the_ck_table():
    # the rows read in Lloyd's Register's naval rules, Vol 2, Pt 5, Ch 1, Table 1.3.1
    assert (CK_FACTORS["integral_flange"], CK_FACTORS["shrink_fit"], CK_FACTORS["keyway_tapered"]) == (1.0, 1.0, 0.6)


@pytest.mark.parametrize("kwargs, field", [
    (dict(feature="integral_flange", diameter_m=0.2, sigma_b_pa=500e6, speed_ratio=1.06), "speed_ratio"),
    (dict(feature="integral_flange", diameter_m=0.0, sigma_b_pa=500e6, speed_ratio=0.5), "diameter_m"),
    (dict(feature="integral_flange", diameter_m=-0.1, sigma_b_pa=500e6, speed_ratio=0.5), "diameter_m"),
    (dict(feature="spline", diameter_m=0.2, sigma_b_pa=500e6, speed_ratio=0.5), "feature"),
    (dict(feature="integral_flange", diameter_m=0.2, sigma_b_pa=0.0, speed_ratio=0.5), "sigma_b_pa"),
    (dict(feature="integral_flange", diameter_m=0.2, sigma_b_pa=5e8, speed_ratio=0.5, material="bronze"), "material"),
])
def test_bad_inputs_are_refused_by_name(kwargs, field):
    with pytest.raises(ParameterError) as exc:
        shaft_limit(**kwargs)
    assert exc.value.parameter == field and str(exc.value).startswith(field)
