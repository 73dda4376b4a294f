"""The condensed crank's bending: its damping with a source, the flag where its vibratory bending is
beyond the rule's, and the term-by-term bridge between the two fatigue methods (issue 52)."""

import math
from pathlib import Path

import numpy as np
import pytest
from conftest import plain, toml_text  # noqa: F401  (renault_raw is a fixture)

import fetorsion
from fetorsion.errors import FetorsionError


@pytest.mark.fe
def test_each_mode_takes_its_torsion_share_of_the_two_damping_ratios():
    """supported_damping with ζ_t 0.02 and ζ_b 0.10 on one throw in rigid bearings: the
    state-space eigenvalues λ of (M, C, K) — a second route, not the modal formula — give each
    mode's ratio −Re λ/|λ| = ζ_b + (ζ_t − ζ_b) s, s its torsion share of kinetic energy, to 1e-6
    (C is diagonal in the modal basis, so the eigenvalues are exact; 1e-6 is the eigensolver's
    round-off on ω² spread over 1e8). Without ζ_b every mode takes ζ_t."""
    import scipy.linalg

    from fetorsion.design.stress import fillet_cuts, fillets_of
    from fetorsion.fe.condensed import run_condensed
    from fetorsion.response.coupled import supported_damping
    from fetorsion.webs.throwfe import throw_of

    throw = throw_of(plain("renault21.toml"), 0)
    cc = run_condensed(throw, mesh_size=0.02, cuts=fillet_cuts(throw, fillets_of(throw)))
    md = cc.modes("bearings")
    expected = 0.10 + (0.02 - 0.10) * md.fractions[:, 0]
    for zb, want in ((0.10, expected), (None, np.full(len(expected), 0.02))):
        K, M, C, _ = supported_damping(cc, "bearings", 0.02, zb)
        n = len(K)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
        lam = scipy.linalg.eigvals(A)
        lam = lam[(lam.imag > 0) & (np.abs(lam) > 1.0)]  # one of each pair, elastic modes
        got = -lam.real / np.abs(lam)
        w = np.abs(lam)
        order = np.argsort(w)
        got, w = got[order], w[order]
        wn = 2 * np.pi * md.frequencies_hz
        assert len(w) == len(wn)
        np.testing.assert_allclose(w, wn, rtol=1e-6)
        np.testing.assert_allclose(got, want, rtol=1e-6, atol=1e-9)
    assert (md.fractions[:, 0] > 0.9).any() and (md.fractions[:, 0] < 0.1).any()  # both kinds are there


def _with_excitation(raw, **fields):
    raw = {**raw, "excitation": {**raw["excitation"], **fields}}
    return raw


def test_a_bending_damping_ratio_needs_its_source(tmp_path, renault_raw):
    """The ratio without a source is refused, naming the field; a source without a ratio too; both
    together are read; the bending damping's source and whether it is assumed follow them."""
    from fetorsion.response.coupled import bending_damping

    bad = [({"bending_damping_ratio": 0.05}, "excitation.bending_damping_ratio_source"),
           ({"bending_damping_ratio_source": "a test"}, "excitation.bending_damping_ratio_source"),
           ({"bending_damping_ratio": 1.5, "bending_damping_ratio_source": "a test"}, "excitation.bending_damping_ratio")]
    for fields, name in bad:
        path = tmp_path / "x.toml"
        path.write_text(toml_text(_with_excitation(renault_raw, **fields)))
        with pytest.raises(FetorsionError, match=name.replace(".", r"\.")):
            fetorsion.load(path)
    path = tmp_path / "ok.toml"
    path.write_text(toml_text(_with_excitation(renault_raw, bending_damping_ratio=0.05,
                                               bending_damping_ratio_source="a hammer test")))
    crank = fetorsion.load(path)
    assert bending_damping(crank) == {"ratio": 0.05, "source": "a hammer test", "assumed": False}
    own = bending_damping(fetorsion.load(Path(__file__).parents[1] / "geometry" / "renault21.toml"))
    assert own["assumed"] and own["ratio"] == 0.02


def test_the_bending_reference_is_m53s_moment_at_the_web_or_the_cut():
    """vibratory_bending's reference, by [KR-M53] §2.1 statics written independently
    (m53.throw_loads): at a journal fillet the web-centre moment M_BRF (the rule's nominal, the
    larger there), at a pin fillet the triangular diagram's value at the cut, the larger there.
    A history carrying twice the reference at every fillet reads 2 and is flagged."""
    from fetorsion.design.m53 import alternating, throw_loads, throw_spans
    from fetorsion.design.recovered import BENDING_FLAG, vibratory_bending
    from fetorsion.design.recovery import throw_index, throw_origin
    from fetorsion.design.stress import fillets_of
    from fetorsion.excitation.torque import cylinder_pin_forces
    from fetorsion.response.cycle import LoadCycle

    crank = plain("renault21.toml")
    fillets = [f for f in fillets_of(crank) if f.kind in ("pin", "journal")]
    rated = 6000.0
    fr = float(alternating(cylinder_pin_forces(crank, rated)["radial"]))
    ref = []
    for f in fillets:
        i = throw_index(crank, fillets, f)
        spans = throw_spans(crank, i)
        x = f.x - throw_origin(crank, fillets, i)
        a, b = (spans.L3 - spans.L2) / spans.L3, spans.L2 / spans.L3
        at_cut = a * fr * x if x < spans.L2 else b * fr * (spans.L3 - x)
        web = throw_loads(spans, np.array([fr]), np.array([0.0]))["M_BRF"][0 if x < spans.L2 else 1, 0]
        ref.append(max(at_cut, web))
        assert (at_cut > web) == (f.kind == "pin"), f.label
    angles = np.linspace(0, 4 * np.pi, 72, endpoint=False)
    history = np.zeros((2, len(fillets), 6, len(angles)))
    history[1, :, 5] = 2 * np.array(ref)[:, None] * np.cos(angles)  # Mz in the plane of throw angle 0
    cycle = LoadCycle("t", np.array([3000.0, 5000.0]), angles, [f.label for f in fillets],
                      np.zeros((2, len(fillets), 6)), history, np.zeros(len(fillets)))
    rows = vibratory_bending(crank, cycle, fillets, np.array([[f.x, 0, 0] for f in fillets]), rated)
    for r, want in zip(rows, ref):
        assert r["determinate_nm"] == pytest.approx(want, rel=1e-9)
        assert r["ratio"] == pytest.approx(2.0, rel=1e-9) and r["flag"] is (2.0 > BENDING_FLAG)
        assert r["rpm"] == 5000.0


def test_the_bridges_factors_are_the_steps_between_the_two_safeties():
    """place_bridge on figures written by hand: each factor is its own step (loads, SCF against
    recovery, combination, strength, mean) and the product is fe's safety over M53's."""
    from fetorsion.design.bridge import place_bridge
    from fetorsion.design.fatigue import FatigueAssessment
    from fetorsion.design.m53 import M53Location

    m53 = M53Location("throw 1: pin fillet", "pin-fillet", 0.0, 0.0, 10e6, 200e6, 400e6, {"alpha_B": 2.5})
    same = {"m53_sigma_v_pa": 190e6, "fe_sigma_v_pa": 171e6}  # the recovery 10 % under the rule's SCFs
    fe = FatigueAssessment("P1 fillet", "pin-fillet", "findley-recovered", 360e6, 150e6, -50e6, 2.6, 1.0,
                           criteria={"findley": {"safety_without_mean": 2.3}})
    b = place_bridge(fe, 2.6, m53, same)
    f = b["factors"]
    assert f["stress"] == pytest.approx(190 / 171)
    assert f["load"] == pytest.approx((200 / 190) * (171 / 150))
    assert f["combination"] == pytest.approx(2.3 * 150 / 360)
    assert f["strength"] == pytest.approx(360 / 400)
    assert f["mean"] == pytest.approx(2.6 / 2.3)
    assert b["ratio"] == pytest.approx(2.6 / 2.0) and b["product"] == pytest.approx(b["ratio"], rel=1e-12)
    assert b["largest"] == max(f, key=lambda k: abs(math.log(f[k])))


def test_a_fatigue_method_comes_from_the_registry(monkeypatch, renault_raw, tmp_path):
    """A name not registered is refused naming where it was given, before any work; a method
    added to the registry is taken by the description's [limits] fatigue_method and answers
    through it."""
    from fetorsion.design import methods
    from fetorsion.design.crank_verdict import VerdictConfig

    crank = fetorsion.load(Path(__file__).parents[1] / "geometry" / "renault21.toml")
    with pytest.raises(FetorsionError, match="shigley.*iacs-m53, fe"):
        methods.described_method(crank, "shigley")
    assert methods.described_method(crank) == "iacs-m53"
    third = methods.FatigueMethod("half", "half of M53's safety", False, lambda loads: 1.0,
                                  lambda r: methods.MethodAnswer(0.5 * r, 1.0, "x", "x", 0.0, False))
    monkeypatch.setitem(methods.FATIGUE_METHODS, "half", third)
    raw = {**renault_raw, "limits": {"source": "a test", "fatigue_method": "half"}}
    path = tmp_path / "x.toml"
    path.write_text(toml_text(raw))
    assert methods.described_method(fetorsion.load(path)) == "half"
    c = VerdictConfig("t", (), {"iacs-m53": None, "half": 3.0})
    assert c.answer("half").safety == 1.5


def test_a_surface_treatment_states_its_factor_and_scales_the_local_strength(tmp_path, renault_raw):
    """[material] surface_treatment needs its factor and source (fetorsion ships none); the factor
    multiplies the fe path's local strength at the fillets (and at the bores unless the fillets
    were rolled), and with no mean Findley's safety grows by exactly that factor (k depends on
    t₋₁/f₋₁ only, λ on t₋₁)."""
    from types import SimpleNamespace

    from fetorsion.design.criterion import findley_constants, findley_surface
    from fetorsion.design.fatigue import fatigue_material
    from fetorsion.design.recovered import local_strength
    from fetorsion.design.recovery import StressZone

    for fields, name in (({"surface_treatment": "nitrided"}, "material.surface_treatment_factor"),
                         ({"surface_treatment_factor": 1.3, "surface_treatment_source": "x"},
                          "material.surface_treatment_factor"),
                         ({"surface_treatment": "polished"}, "material.surface_treatment")):
        path = tmp_path / "x.toml"
        path.write_text(toml_text({**renault_raw, "material": {**renault_raw["material"], **fields}}))
        with pytest.raises(FetorsionError, match=name.replace(".", r"\.")):
            fetorsion.load(path)
    influence = np.zeros((2, 3, 6))
    influence[:, 0, 5] = [2.0e5, 1.0e5]  # 2e5 Pa per N·m of Mz at the peak node
    zone = StressZone("z", "pin-fillet", np.zeros((2, 3)), np.zeros((2, 3, 3)), influence, np.zeros(3))
    strengths = {}
    for treatment in ("none", "fillet-rolled", "nitrided"):
        extra = {} if treatment == "none" else {"surface_treatment": treatment, "surface_treatment_factor": 1.4,
                                                "surface_treatment_source": "a rolling test"}
        path = tmp_path / f"{treatment}.toml"
        path.write_text(toml_text({**renault_raw, "material": {**renault_raw["material"], **extra}}))
        mat, _ = fatigue_material(fetorsion.load(path).material)
        for kind in ("pin-fillet", "oil-bore"):
            loc = SimpleNamespace(zone=zone, kind=kind, diameter=0.048, notch_radius=0.0025)
            strengths[treatment, kind] = local_strength(mat, loc).bending
    assert strengths["fillet-rolled", "pin-fillet"] == pytest.approx(1.4 * strengths["none", "pin-fillet"], rel=1e-12)
    assert strengths["fillet-rolled", "oil-bore"] == pytest.approx(strengths["none", "oil-bore"], rel=1e-12)
    assert strengths["nitrided", "oil-bore"] == pytest.approx(1.4 * strengths["none", "oil-bore"], rel=1e-12)
    f = strengths["none", "pin-fillet"]
    rng = np.random.default_rng(7)
    vib = rng.normal(size=(5, 3, 40)) * 1e8
    safe = [findley_surface(np.zeros((5, 3)), vib, *findley_constants(s, s / math.sqrt(3)))["safety"] for s in (f, 1.4 * f)]
    np.testing.assert_allclose(safe[1], 1.4 * safe[0], rtol=1e-12)
