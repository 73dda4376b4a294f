"""Fatigue strength, equivalent stresses and criteria (fetorsion.design.fatigue) against hand
evaluations of the cited formulas, the textbook's worked examples and the criteria's limits."""

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from fetorsion.description.crank import parse_crank
from fetorsion.design import fatigue as F
from fetorsion.errors import DescriptionError, FetorsionError

ROOT = Path(__file__).resolve().parents[1]
TH = np.linspace(0.0, 4.0 * np.pi, 721)  # two engine revolutions, 1° steps


# --- IACS UR M53 on a made-up crank: σ_B 800 N/mm², pin 60 mm, R_H 3 mm, journal 70 mm, R_G 3.5 mm,
# oil bore 8 mm; local alternating stresses σ_BH 90, τ_H 60, σ_BG 70, τ_G 55, σ_BO 40, τ_TO 80 N/mm².

def test_m53_fatigue_strength_equals_the_rule_evaluated_by_hand():
    # Same floating-point operations in another order: 1e-9 relative is far above round-off.
    pin = 1.05 * (0.42 * 800 + 39.3) * (0.264 + 1.073 * 60**-0.2 + (785 - 800) / 4900 + 196 / 800 * math.sqrt(1 / 3))
    journal = 1.05 * (0.42 * 800 + 39.3) * (0.264 + 1.073 * 70**-0.2 + (785 - 800) / 4900
                                            + 196 / 800 * math.sqrt(1 / 3.5))
    bore = 1.0 * (0.42 * 800 + 39.3) * (0.264 + 1.073 * 60**-0.2 + (785 - 800) / 4900 + 196 / 800 * math.sqrt(1 / 4))
    got = [F.m53_fatigue_strength(800e6, 0.060, 0.003, "drop-forged", "pin-fillet"),
           F.m53_fatigue_strength(800e6, 0.070, 0.0035, "drop-forged", "journal-fillet"),
           F.m53_fatigue_strength(800e6, 0.060, 0.004, "drop-forged", "oil-bore")]
    assert got == pytest.approx([pin * 1e6, journal * 1e6, bore * 1e6], rel=1e-9)
    # K by route; the oil bore never takes K > 1 (IRS Classification Notes, Section 6).
    free = F.m53_fatigue_strength(800e6, 0.060, 0.003, "free-form-forged")
    cast = F.m53_fatigue_strength(800e6, 0.060, 0.003, "cast-cold-rolled")
    assert (got[0] / free, cast / free) == pytest.approx((1.05, 0.93), rel=1e-12)


def test_m53_equivalent_stresses_and_acceptability_by_hand():
    assert F.m53_equivalent_fillet(90e6, 60e6) == pytest.approx(math.sqrt(90**2 + 3 * 60**2) * 1e6, rel=1e-12)
    assert F.m53_equivalent_fillet(90e6, 60e6, 10e6) == pytest.approx(math.sqrt(100**2 + 3 * 60**2) * 1e6, rel=1e-12)
    bore = 40 / 3 * (1 + 2 * math.sqrt(1 + 9 / 4 * (80 / 40) ** 2))
    assert F.m53_equivalent_oil_bore(40e6, 80e6) == pytest.approx(bore * 1e6, rel=1e-12)
    # Limits: pure bending gives σ, pure torsion at the bore τ (max principal stress of shear).
    assert F.m53_equivalent_oil_bore(40e6, 0.0) == pytest.approx(40e6, rel=1e-15)
    assert F.m53_equivalent_oil_bore(0.0, 80e6) == pytest.approx(80e6, rel=1e-15)

    locs = [F.LocationStress("pin", "pin-fillet", 0.060, 0.003, 90e6, 60e6),
            F.LocationStress("journal", "journal-fillet", 0.070, 0.0035, 70e6, 55e6),
            F.LocationStress("bore", "oil-bore", 0.060, 0.004, 40e6, 80e6)]
    steel = F.FatigueMaterial(800e6, 600e6, "machined", "drop-forged")
    res = F.run_fatigue(locs, steel, "iacs-m53")
    sigma_dw = 1.05 * (0.42 * 800 + 39.3) * (0.264 + 1.073 * 70**-0.2 + (785 - 800) / 4900
                                             + 196 / 800 * math.sqrt(1 / 3.5))
    q_journal = sigma_dw / math.sqrt(70**2 + 3 * 55**2)
    assert res.locations[1].safety == pytest.approx(q_journal, rel=1e-9)
    assert res.locations[1].required == 1.15
    qs = [a.safety for a in res.locations]
    assert res.governing.name == locs[int(np.argmin(qs))].name
    d = res.to_dict()
    assert d["governing"] == res.governing.name and len(d["locations"]) == 3 and d["material"]["defaulted"] == []


def test_m53_takes_nominal_stresses_times_kt():
    steel = F.FatigueMaterial(800e6, 600e6, "machined", "drop-forged")
    local = F.assess_m53(F.LocationStress("p", "pin-fillet", 0.06, 0.003, 90e6, 60e6), steel)
    nominal = F.assess_m53(F.LocationStress("p", "pin-fillet", 0.06, 0.003, 30e6, 40e6, kt_bending=3.0,
                                            kt_torsion=1.5), steel)
    assert nominal.safety == pytest.approx(local.safety, rel=1e-14)


# --- Textbook: Budynas–Nisbett (Shigley) 9th ed., worked examples, printed to 3 figures.

def test_marin_surface_factor_matches_example_6_3():
    # Example 6-3: S_ut = 520 MPa, machined: k_a = 4.51(520)^−0.265 = 0.860 (printed to 3 figures).
    assert F.marin_surface(520e6, "machined") == pytest.approx(0.860, abs=5e-4)
    # The same text: forged instead, 0.540.
    assert F.marin_surface(520e6, "as-forged") == pytest.approx(0.540, abs=5e-4)


def test_notch_factor_matches_example_6_6():
    # Example 6-6(b): S_ut = 690 MPa, r = 3 mm, K_t = 1.65: √a = 0.0622 √in, K_f = 1.55 (3 figures);
    # the 1-kpsi rounding of 690 MPa moves √a by < 1e-4 √in.
    assert F.neuber_sqrt_a(690e6) / math.sqrt(0.0254) == pytest.approx(0.0622, abs=1e-4)
    q = F.notch_sensitivity(690e6, 0.003)
    assert F.fatigue_notch_factor(1.65, q) == pytest.approx(1.55, abs=5e-3)


def test_endurance_limit_matches_solved_problem_7_2():
    # Budynas–Nisbett solutions, problem 7-2 (trial 1): SAE 2340, S_ut = 1226 MPa, machined,
    # d = 22 mm: k_a = 0.685, k_b = 0.893, S_e = 0.685(0.893)(0.5)(1226) = 375 MPa; the factors'
    # 3-figure rounding allows ±0.1 %.
    assert F.marin_surface(1226e6, "machined") == pytest.approx(0.685, abs=5e-4)
    assert F.marin_size(0.022) == pytest.approx(0.893, abs=5e-4)
    assert F.endurance_limit(1226e6, 0.022, "machined") == pytest.approx(375e6, rel=1e-3)


def test_textbook_factors_by_hand():
    # Exactly the printed formulas (1e-12: the same arithmetic).
    assert F.specimen_endurance_limit(1000e6) == 500e6 and F.specimen_endurance_limit(1600e6) == 700e6
    assert F.marin_size(0.080) == pytest.approx(1.51 * 80**-0.157, rel=1e-12)
    assert F.marin_reliability(0.99) == 0.814
    s = 900e6 / 6.894757293168361e6
    sqrt_a_in = 0.190 - 2.51e-3 * s + 1.35e-5 * s**2 - 2.67e-8 * s**3
    assert F.notch_sensitivity(900e6, 0.003, torsion=True) == pytest.approx(
        1 / (1 + sqrt_a_in * math.sqrt(0.0254) / math.sqrt(0.003)), rel=1e-12)
    with pytest.raises(FetorsionError, match="254 mm"):
        F.marin_size(0.3)
    with pytest.raises(FetorsionError, match="reliability"):
        F.marin_reliability(0.8)


def test_goodman_gerber_and_yield_on_a_made_up_fillet():
    # σ_a 60, σ_m 80, τ_a 25, τ_m 40 MPa nominal, K_t 2.0 / 1.6, pin 50 mm, r 2.5 mm, S_ut 900,
    # S_y 650 MPa, ground: every step written out from the book's equations.
    steel = F.FatigueMaterial(900e6, 650e6, "ground", "drop-forged")
    loc = F.LocationStress("pin", "pin-fillet", 0.050, 0.0025, 60e6, 25e6, 80e6, 40e6, kt_bending=2.0, kt_torsion=1.6)
    s = 900 / 6.894757293168361
    ra = (0.246 - 3.08e-3 * s + 1.51e-5 * s**2 - 2.67e-8 * s**3) * math.sqrt(0.0254e3)  # √mm
    rs = (0.190 - 2.51e-3 * s + 1.35e-5 * s**2 - 2.67e-8 * s**3) * math.sqrt(0.0254e3)
    kf = 1 + (2.0 - 1) / (1 + ra / math.sqrt(2.5))
    kfs = 1 + (1.6 - 1) / (1 + rs / math.sqrt(2.5))
    sa = math.sqrt((kf * 60) ** 2 + 3 * (kfs * 25) ** 2)
    sm = math.sqrt((kf * 80) ** 2 + 3 * (kfs * 40) ** 2)
    se = 1.58 * 900**-0.085 * (50 / 7.62) ** -0.107 * 0.5 * 900
    goodman = 1 / (sa / se + sm / 900)
    gerber = 0.5 * (900 / sm) ** 2 * (sa / se) * (-1 + math.sqrt(1 + (2 * sm * se / (900 * sa)) ** 2))
    n_y = 650 / math.sqrt((kf * 140) ** 2 + 3 * (kfs * 65) ** 2)
    a = F.assess_textbook(loc, steel)
    assert (a.strength, a.equivalent_alternating, a.equivalent_mean) == pytest.approx((se * 1e6, sa * 1e6, sm * 1e6),
                                                                                       rel=1e-9)
    assert (a.safety, a.yield_safety) == pytest.approx((goodman, n_y), rel=1e-9)
    assert F.assess_textbook(loc, steel, mean_stress="gerber").safety == pytest.approx(gerber, rel=1e-9)
    # Gerber lies outside Goodman (less conservative) with a mean stress; both equal S_e/σ_a without.
    assert gerber > goodman
    assert F.gerber_safety(100.0, 0.0, 300.0, 900.0) == F.goodman_safety(100.0, 0.0, 300.0, 900.0) == 3.0


# --- Multiaxial criteria on histories

@pytest.mark.parametrize("criterion", [F.crossland, F.findley])
def test_criteria_reduce_to_the_fatigue_limits(criterion):
    # Fully reversed pure bending at f: safety 1; pure torsion at t: safety 1. Crossland exact
    # (round-off); Findley's plane grid misses the maximum by ≤ 1 − cos(π/1800) relative.
    f, t = 300e6, 300e6 / math.sqrt(3.0)
    tol = 1e-12 if criterion is F.crossland else 1 - math.cos(math.pi / 1800)
    bend = criterion(f * np.sin(TH), 0 * TH, f, t)
    tors = criterion(0 * TH, t * np.sin(TH), f, t)
    assert bend["safety"] == pytest.approx(1.0, rel=tol, abs=0)
    assert tors["safety"] == pytest.approx(1.0, rel=tol, abs=0)
    # Another ratio t/f = 0.65 (Crossland α > 0, Findley k > 0.16): still both limits.
    t2 = 0.65 * f
    assert criterion(0.5 * f * np.sin(TH), 0 * TH, f, t2)["safety"] == pytest.approx(2.0, rel=tol, abs=0)
    assert criterion(0 * TH, 0.5 * t2 * np.sin(TH), f, t2)["safety"] == pytest.approx(2.0, rel=tol, abs=0)


def test_crossland_by_hand_in_phase_with_mean():
    # σ = 50 + 100 sin, τ = 60 sin (in phase): √J2,a = √(100²/3 + 60²), p_max = 150/3.
    f, t = 320e6, 200e6
    r = F.crossland(1e6 * (50 + 100 * np.sin(TH)), 1e6 * 60 * np.sin(TH), f, t)
    value = math.sqrt(100**2 / 3 + 60**2) + (3 * 200 / 320 - math.sqrt(3)) * 150 / 3
    assert r["value"] == pytest.approx(value * 1e6, rel=1e-12)
    assert r["safety"] == pytest.approx(200 / value, rel=1e-12)


def test_findley_by_hand_in_phase():
    # In-phase σ_a sin, τ_a sin: the worst plane maximises (1/2)|σ sin2θ − 2τ cos2θ| +
    # k (σ cos²θ + τ sin2θ) — evaluated here on a 10× finer grid by plain Python.
    f, t, sa, ta = 300e6, 190e6, 120e6, 50e6
    k = F.findley_k(f, t)
    best = max(0.5 * abs(sa * math.sin(2 * th) - 2 * ta * math.cos(2 * th))
               + k * abs(sa * math.cos(th) ** 2 + ta * math.sin(2 * th))
               for th in (i * math.pi / 18000 for i in range(18000)))
    r = F.findley(sa * np.sin(TH), ta * np.sin(TH), f, t)
    assert r["value"] == pytest.approx(best, rel=1 - math.cos(math.pi / 1800))


def test_run_fatigue_with_histories_and_default_steel():
    loc = F.LocationStress.from_history("pin", "pin-fillet", 0.048, 0.0025,
                                        80e6 + 60e6 * np.sin(TH), 40e6 * np.sin(TH + 0.3))
    assert (loc.bending_mean, loc.bending_alt) == pytest.approx((80e6, 60e6), rel=1e-12)
    res = F.run_fatigue([loc], None, "textbook", required=1.5)
    assert res.material == F.fatigue_material(None)[0] and len(res.defaulted) == 4
    assert res.material.tensile_strength == F.DEFAULT_FORGING_STEEL.tensile_strength
    a = res.governing
    assert a.required == 1.5 and set(a.criteria) == {"crossland", "findley"}
    # The criteria run on the same local history: the Crossland value is its own formula.
    assert a.criteria["crossland"]["sqrt_j2a"] > 0
    with pytest.raises(FetorsionError, match="method"):
        F.run_fatigue([loc], None, "fkm")


# --- The description's strength fields

def _renault(**material):
    data = tomllib.loads((ROOT / "geometry" / "renault21.toml").read_text())
    data["material"].update(material)
    return data


def test_description_strength_fields_parse():
    crank = parse_crank(_renault(tensile_strength_pa=950e6, yield_strength_pa=700e6, surface="ground",
                                 process="free-form-forged"), check_uncertainty=False)
    m = crank.material
    assert (m.tensile_strength, m.yield_strength, m.surface, m.process) == (950e6, 700e6, "ground", "free-form-forged")
    mat, defaulted = F.fatigue_material(m)
    assert defaulted == [] and mat.tensile_strength == 950e6
    plain = parse_crank(_renault(), check_uncertainty=False).material
    assert plain.tensile_strength is None and F.fatigue_material(plain)[1] == ["tensile_strength", "yield_strength",
                                                                              "surface", "process"]


@pytest.mark.parametrize("key, value, rule", [
    ("tensile_strength_pa", -5.0, "must be > 0"),
    ("tensile_strength_pa", "hard", "must be a finite number"),
    ("yield_strength_pa", 0.0, "must be > 0"),
    ("yield_strength_pa", 2e9, "must not exceed tensile_strength_pa"),
    ("surface", "polished", "must be one of"),
    ("process", "cast", "must be one of"),
])
def test_each_bad_strength_value_gives_one_error_naming_the_key(key, value, rule):
    fields = {"tensile_strength_pa": 900e6, key: value}
    with pytest.raises(DescriptionError) as err:
        parse_crank(_renault(**fields), check_uncertainty=False)
    problems = err.value.problems
    assert len(problems) == 1 and problems[0].field == f"material.{key}" and rule in problems[0].rule


def test_limits_strength_replaces_the_methods_own_by_hand():
    """[limits] fatigue_strength_bending_pa (against local stresses) in place of M53's σ_DW and of
    the textbook's S_e (then with the full K_t: q = 1), and fatigue_required_safety in place of the
    method's margin; written out by hand to 1e-12."""
    from fetorsion.description.model import Limits

    lim = Limits(continuous_shear=1e8, source="bench test", fatigue_strength_bending=310e6, fatigue_required_safety=1.4)
    loc = F.LocationStress("p", "pin-fillet", 0.06, 0.003, 30e6, 20e6, 15e6, 5e6, kt_bending=3.0, kt_torsion=2.0)
    m53 = F.run_fatigue([loc], None, "iacs-m53", limits=lim).locations[0]
    assert m53.strength == 310e6 and m53.required == 1.4
    assert m53.safety == pytest.approx(310e6 / math.sqrt(90e6**2 + 3 * 40e6**2), rel=1e-12)
    tb = F.run_fatigue([loc], None, "textbook", limits=lim).locations[0]
    sa, sm = math.sqrt(90e6**2 + 3 * 40e6**2), math.sqrt(45e6**2 + 3 * 10e6**2)
    assert tb.safety == pytest.approx(1 / (sa / 310e6 + sm / F.DEFAULT_FORGING_STEEL.tensile_strength), rel=1e-12)
    plain = F.run_fatigue([loc], None, "iacs-m53").locations[0]  # without it: the rule's own
    assert plain.strength != 310e6 and plain.required == F.M53_REQUIRED_Q
