"""Split pins (issue 53): the even-firing 90° V6, whose every throw's pin is two half pins 30° apart
with a flying web between them. The description's checks, the TDC lags and firing against a hand
calculation, the order sums against the vector sum of six unit phasors, the flying web's inertia
against OpenCASCADE's integration of the same solid, the rod loads' moment about the one pin master
against numpy's cross product, the refusals (formula webs, M53), and the solid meshes."""

import math
import tomllib
from types import SimpleNamespace

import numpy as np
import pytest

from conftest import ROOT

from fetorsion.description.crank import parse_crank
from fetorsion.errors import DescriptionError, FetorsionError
from fetorsion.excitation.campbell import major_orders, order_sums

V6 = ROOT / "geometry" / "v6_split_pin.toml"


def v6_raw() -> dict:
    with open(V6, "rb") as f:
        return tomllib.load(f)


def v6(**pins):
    raw = v6_raw()
    for p in raw["pins"]:
        p.update(pins)
    return parse_crank(raw, source=str(V6))


def problems_of(raw) -> str:
    with pytest.raises(DescriptionError) as info:
        parse_crank(raw, source="v6.toml")
    return str(info.value)


def test_a_split_pin_cylinders_tdc_lag_is_its_throw_plus_its_half_plus_its_bank():
    """λ_c = a_t + s_c + ψ_c by hand, for the example's alternate numbering: odd cylinders (left
    bank, front half: s = 0, ψ = 0), even ones (right bank, rear half: s = −30°, ψ = −90°) on
    throws at 0, 120, 240°."""
    e = v6().engine
    hand = [0.0, 0.0 - 30.0 - 90.0, 120.0, 120.0 - 30.0 - 90.0, 240.0, 240.0 - 30.0 - 90.0]
    assert np.degrees(e.tdc_lags()) == pytest.approx(hand, abs=1e-12)
    assert np.degrees(e.half_pin_angles) == pytest.approx([0, -30, 0, -30, 0, -30], abs=1e-12)
    # each big end at its half pin's mid-length: ±(L + w)/4 = ±(50 + 6)/4 = ±14 mm
    assert np.array(e.rod_offsets) * 1e3 == pytest.approx([-14, 14, -14, 14, -14, 14], abs=1e-12)


def test_the_split_v6_fires_every_120_degrees_and_its_orders_sum_so():
    """Firing 1-6-5-4-3-2 takes, cylinder by cylinder, the first TDC after the one before (a
    four-stroke's TDCs at λ and λ + 360°): by hand 1 at 0, 6 (λ 120) at 120, 5 (λ 240) at 240,
    4 (λ 0) at 360, 3 (λ 120) at 480, 2 (λ −120 ≡ 240) at 600. The rigid crank's order sums are
    then the vector sum of six unit phasors 120°·k apart, |Σ_k e^{−iq 2πk/3}|/6: 1 at the multiples
    of z/2 = 3, 0 at every other order (0.5 … 2.5, 4, 5 …)."""
    e = v6().engine
    phi = np.degrees(e.firing_angles())
    assert phi == pytest.approx([0.0, 600.0, 480.0, 360.0, 240.0, 120.0], abs=1e-9)
    assert np.diff(np.sort(phi)) == pytest.approx([120.0] * 5, abs=1e-9)
    orders = np.arange(0.5, 12.01, 0.5)
    hand = np.abs(np.exp(-1j * np.outer(orders, 2 * np.pi * np.arange(6) / 3)).sum(axis=1)) / 6
    assert order_sums(e, np.ones(6), orders)[0] == pytest.approx(hand, abs=1e-12)
    assert list(major_orders(e)) == [3.0, 6.0, 9.0, 12.0]
    for q in (0.5, 1.0, 1.5, 2.0, 2.5, 4.0, 5.0):
        assert order_sums(e, np.ones(6), [q])[0, 0] < 1e-12


def test_unsplit_the_same_v6_fires_unevenly():
    """The split is what evens the firing: without it (s = 0) the throw-mates are 90° apart, λ = 0,
    −90, 120, 30, 240, 150, and 1-6-5-4-3-2 fires (by hand) 1 at 0, 6 at 150, 5 at 240, 4 at 390,
    3 at 480, 2 at 630: intervals 150/90°. Order 3 then sums three phasors at 0° and three at 90°
    (3φ mod 360), |3 + 3i|/6 = √2/2, order 6 cancels (0° and 180°), and only order 12 adds fully."""
    raw = v6_raw()
    for p in raw["pins"]:
        del p["split_angle_deg"], p["flying_web_thickness"]
    raw["engine"]["rod_spacing"] = 23.0
    e = parse_crank(raw, source="v6.toml").engine
    assert np.degrees(e.tdc_lags()) == pytest.approx([0, -90, 120, 30, 240, 150], abs=1e-12)
    assert np.degrees(e.firing_angles()) == pytest.approx([0, 630, 480, 390, 240, 150], abs=1e-9)
    assert order_sums(e, np.ones(6), [3.0, 6.0])[0] == pytest.approx([math.sqrt(0.5), 0.0], abs=1e-12)
    assert list(major_orders(e)) == [12.0]


@pytest.mark.parametrize("change, field, words", [
    ({"split_angle_deg": 0.0}, "pins.1.split_angle_deg", "must not be 0"),
    ({"split_angle_deg": 180.0}, "pins.1.split_angle_deg", "180"),
    ({"flying_web_thickness": 0.0}, "pins.1.flying_web_thickness", "> 0"),
    ({"flying_web_thickness": 50.0}, "pins.1.flying_web_thickness", "must fit the pin"),
    ({"flying_web_thickness": 40.0}, "pins.1.flying_web_thickness", "no room for the 6.0 mm oil drilling"),
    ({"flying_web_thickness": 44.5}, "pins.1.flying_web_thickness", "longer than the 2.8 mm pin fillet"),
])
def test_bad_split_fields_are_refused_by_name(change, field, words):
    raw = v6_raw()
    raw["pins"][0].update(change)
    text = problems_of(raw)
    assert field in text and words in text


def test_halves_that_do_not_overlap_are_refused_naming_pin_diameter_stroke_and_split():
    """At stroke 150 mm a 45° split puts the half pins' centres 2R sin(22.5°) = 150 sin 22.5° =
    57.40 mm apart, above the 57 mm pin: nothing of the pin joins the halves but the flying web."""
    raw = v6_raw()
    raw["engine"].update(stroke=150.0, rod_length=500.0)
    for p in raw["pins"]:
        p["split_angle_deg"] = -45.0
    text = problems_of(raw)
    chord = 150.0 * math.sin(math.radians(22.5))
    assert "pins.1.split_angle_deg" in text and "do not overlap" in text
    assert f"{chord:.4f}"[:5] in text and "stroke 150" in text and "pin diameter 57" in text and "-45" in text


@pytest.mark.parametrize("engine, pins, field, words", [
    ({"rods": "fork-and-blade"}, {}, "pins.1.split_angle_deg", 'rods = "side-by-side"'),
    ({"rod_spacing": 23.0}, {}, "engine.rod_spacing", "leave rod_spacing out"),
    ({}, {"split_angle_deg": None}, "pins.1.flying_web_thickness", "give split_angle_deg too"),
])
def test_a_split_pin_needs_a_vee_with_side_by_side_rods_and_every_pin_split(engine, pins, field, words):
    raw = v6_raw()
    raw["engine"].update(engine)
    for k, v in pins.items():
        raw["pins"][0].pop(k) if v is None else raw["pins"][0].update({k: v})
    text = problems_of(raw)
    assert field in text and words in text


def test_a_split_pin_on_an_in_line_engine_is_refused():
    raw = v6_raw()
    for k in ("layout", "bank_angle_deg", "numbering", "rods"):
        del raw["engine"][k]
    raw["engine"].update(cylinders=3, firing_order=[1, 3, 2])
    text = problems_of(raw)
    assert "pins.1.split_angle_deg" in text and 'needs layout = "vee"' in text


def test_plausibility_warns_on_a_split_or_flying_web_far_from_any_engine():
    from fetorsion.description.plausibility import plausibility_warnings

    assert plausibility_warnings(v6()) == []
    lines = plausibility_warnings(v6(split_angle_deg=-5.0, flying_web_thickness=1.0))
    assert any("pins.1.split_angle_deg = -5" in w for w in lines)
    assert any("pins.1.flying_web_thickness = 1 mm" in w for w in lines)


def test_formula_webs_are_refused_on_a_split_pin_naming_it():
    """No classical formula has a flying web: carter (the CLI's default) is refused, naming the
    pin and the methods that take it; a run takes fe (crank_web_method)."""
    from fetorsion.lumped_model.lumped import lumped
    from fetorsion.webs.methods import crank_web_method

    crank = v6()
    for method in ("carter", "ker-wilson", "beam", "chart"):
        with pytest.raises(FetorsionError, match=r"webs\.1: pins\.1 is a split pin .* \(fe, fe-held\)"):
            lumped(crank, 17, method)
    assert crank_web_method(crank) == "fe"


def test_m53_refuses_split_pins_by_name():
    from fetorsion.design.m53 import run_m53_crank, split_pin_refusal

    crank = v6()
    assert "IACS UR M53 does not cover split pins (pins 1, 2, 3)" in split_pin_refusal(crank)
    with pytest.raises(FetorsionError, match="does not cover split pins"):
        run_m53_crank(crank, [], np.zeros((1, 0)), [1000.0])


def test_the_flying_webs_inertia_is_the_stadiums():
    """The closed form (rectangle and half discs by the parallel-axis theorem) against a direct sum
    over a 1601 × 801 grid of the stadium (points within r of the segment joining the half-pin
    centres), in its own frame: chord c along y, the crank axis d = R cos 15° behind its centre along
    z. The grid's boundary cells (0.04 mm) bound the sum's error to about 1e-3 of the whole."""
    from fetorsion.lumped_model.parts import flying_web_inertia

    crank = v6()
    pin, R, rho = crank.pins[0], crank.engine.crank_radius, crank.material.density
    r, c = pin.diameter / 2, 2 * R * math.sin(math.radians(15.0))
    y, z = np.meshgrid(np.linspace(-r - c / 2, r + c / 2, 1601), np.linspace(-r, r, 801), indexing="ij")
    dy, dz = y[1, 0] - y[0, 0], z[0, 1] - z[0, 0]
    inside = np.hypot(np.clip(np.abs(y) - c / 2, 0.0, None), z) <= r
    d = R * math.cos(math.radians(15.0))
    grid = rho * pin.flying_web * ((y**2 + (z + d) ** 2) * inside).sum() * dy * dz
    assert flying_web_inertia(pin, rho, R) == pytest.approx(grid, rel=2e-3)


@pytest.mark.fe
def test_the_solid_pins_inertia_matches_the_lumped_split_pin():
    """OpenCASCADE integrates the built solid's pin part; it is cut one fillet inside each half pin's
    outer end (fillet metal belongs to the web), so the lumped pin less two 2.8 mm slices of the half
    pin must match it to OCC's integration (1e-5). Without pin drillings: the lumped drilling is
    [Seyedalian]'s flat-ended one, 4e-5 more metal removed than the solid's drilling with its ends
    on the pin's curved surface."""
    from dataclasses import replace

    from fetorsion.lumped_model.parts import pin_inertia
    from fetorsion.solid.geometry import crank_mass_properties

    raw = v6_raw()
    raw["oil_holes"]["in_pins"] = False
    crank = parse_crank(raw, source=str(V6))
    _, parts = crank_mass_properties(crank)
    pin, R, rho, r = crank.pins[0], crank.engine.crank_radius, crank.material.density, crank.fillets.pin
    slice_ = replace(pin, length=r, split_angle=0.0, flying_web=0.0)
    lumped = pin_inertia(pin, rho, R) - 2 * pin_inertia(slice_, rho, R)
    assert parts["pin_1"].polar_inertia == pytest.approx(lumped, rel=1e-5)


def test_each_rod_on_a_split_pin_loads_the_one_master_with_its_moment():
    """A unit force e at rod c's half-pin centre, (d, y_c, z_c), is the same force at the master,
    (0, y_m, z_m) midway between the halves' axes, plus the moment (d, y_c − y_m, z_c − z_m) × e
    (numpy's cross product); e is tangential/radial at the half pin's own angle a_t + s_c."""
    from fetorsion.description.cylinders import pin_master_centre, rod_centre
    from fetorsion.response.pin_loads import pin_load_map

    crank = v6()
    e = crank.engine
    labels = ["front"] + [x for t in range(3) for x in (f"J{t + 1}", f"P{t + 1}")] + ["J4", "rear"]
    names = ("tx", "ty", "tz", "rx", "ry", "rz")
    cc = SimpleNamespace(crank=crank, n_master_dofs=6 * len(labels),
                         dof=lambda label, name: 6 * labels.index(label) + names.index(name))
    load = pin_load_map(cc)
    R = e.crank_radius
    for c in range(6):
        t = e.throw_of_cylinder(c)
        a = math.radians([0.0, 120.0, 240.0][t] + (-30.0 if c % 2 else 0.0))
        assert rod_centre(e, c) == pytest.approx(R * np.array([math.cos(a), math.sin(a)]), abs=1e-15)
        master = pin_master_centre(e, t, crank.pins[t].split_angle)
        mid = math.radians([0.0, 120.0, 240.0][t] - 15.0)
        assert master == pytest.approx(R * math.cos(math.radians(15)) * np.array([math.cos(mid), math.sin(mid)]))
        arm = np.array([e.rod_offset(c), *(R * np.array([math.cos(a), math.sin(a)]) - master)])
        block = load[c].reshape(2, len(labels), 6)[:, labels.index(f"P{t + 1}")]
        for k, f in enumerate((np.array([0, -math.sin(a), math.cos(a)]), np.array([0, math.cos(a), math.sin(a)]))):
            assert block[k, :3] == pytest.approx(f, abs=1e-15)
            assert block[k, 3:] == pytest.approx(np.cross(arm, f), abs=1e-15)


@pytest.mark.fe
def test_the_split_v6_solid_meshes_at_a_coarse_size():
    """The whole V6 (three split pins, flying webs, fillets at each half's outer end, a drilling in
    each half) builds and meshes; every part has elements and the mesh's volume is the solid's."""
    from fetorsion.solid.mesh import mesh_crank

    crank = v6()
    cm = mesh_crank(crank, size=0.012)
    assert {f"pin_{t + 1}" for t in range(3)} <= set(cm.part_names)
    counts = np.bincount(cm.part, minlength=len(cm.part_names))
    assert counts.min() > 0
