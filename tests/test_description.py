"""Every validation rule names its field, value and rule; good files parse."""

import re
import copy

import pytest

import fetorsion
from fetorsion.description.chain import parse_chain
from fetorsion.description.crank import parse_crank
from fetorsion.errors import DescriptionError

from conftest import GEOMETRY, simple_crank_raw


def problems_of(raw):
    with pytest.raises(DescriptionError) as info:
        parse_crank(raw, source="test.toml")
    return info.value.problems, str(info.value)


@pytest.mark.parametrize("name", ["peugeot_glx.toml", "renault21.toml"])
def test_reference_cranks_parse(name):
    crank = fetorsion.load(GEOMETRY / name)
    assert crank.engine.cylinders == 4 and len(crank.webs) == 8
    assert crank.journals[0].diameter < 0.1  # mm converted to m
    assert crank.uncertainty, "reference geometries state their uncertainty"


def test_length_unit_scales_everything():
    raw_mm = simple_crank_raw()
    raw_m = copy.deepcopy(raw_mm)
    raw_m["units"]["length"] = "m"
    for group in ("journals", "pins", "front", "rear"):
        raw_m[group] = [{k: v / 1000 for k, v in t.items()} for t in raw_m[group]]
    raw_m["webs"] = [{k: v / 1000 for k, v in t.items()} for t in raw_m["webs"]]
    for key in ("stroke", "rod_length"):
        raw_m["engine"][key] /= 1000
    a, b = parse_crank(raw_mm), parse_crank(raw_m)
    assert a.journals == b.journals and a.webs == b.webs and a.engine == b.engine


SYNTHETIC = {"reciprocating_mass_kg": 0.5, "speed_range_rpm": [1000.0, 5000.0], "compression_ratio": 10.0,
             "peak_pressure_pa": 60.0e5}
CASES = [
    # (mutation, field named in the message, words of the rule)
    (lambda r: r["units"].update(length="furlong"), "units.length", "must be one of"),
    (lambda r: r["journals"].__setitem__(2, {"diameter": 60.0, "length": -5.0}), "journals.3.length", "> 0"),
    (lambda r: r["pins"].__setitem__(0, {"diameter": 50.0, "length": 24.0, "bore": 55.0}), "pins.1.bore", "smaller than diameter"),
    (lambda r: r["webs"].__setitem__(3, {"thickness": 20.0, "width_journal": 90.0, "width_pin": 40.0}),
     "webs.4.width_pin", "must lie inside its web"),
    (lambda r: r["webs"].__setitem__(0, {"thickness": 20.0, "width_journal": 55.0, "width_pin": 70.0}),
     "webs.1.width_journal", "must lie inside its web"),
    (lambda r: r["webs"].pop(), "webs", "needs 8"),
    (lambda r: r["engine"].update(firing_order=[1, 2, 2, 4]), "engine.firing_order", "permutation"),
    # A flat four (0/180/180/0) fires 1-3-4-2 or 1-2-4-3: after 1 and 2, cylinder 3's TDCs
    # (180°, 540°) are taken or past and 4's next one (720°) is the next cycle's.
    (lambda r: r["engine"].update(crank_angles_deg=[0.0, 180.0, 180.0, 0.0], firing_order=[1, 2, 3, 4]),
     "engine.firing_order", "cannot be fired by crank_angles_deg"),
    (lambda r: r["engine"].update(crank_angles_deg=[0.0, 180.0]), "engine.crank_angles_deg", "one angle per cylinder"),
    # The synthetic cycle against its engine: 1e5 Pa · 10^1.3 = 19.95 bar motored at TDC.
    (lambda r: r.update(excitation=dict(SYNTHETIC, peak_pressure_pa=19.0e5)), "excitation.peak_pressure_pa",
     "above the motored peak"),
    (lambda r: r.update(excitation=SYNTHETIC), "engine.bore", "> 0 for the gas force"),
    (lambda r: (r["engine"].update(bore=80.0, cycle_strokes=2), r.update(excitation=SYNTHETIC)),
     "excitation.peak_pressure_pa", "4-stroke"),
    (lambda r: r["engine"].update(rod_length=30.0), "engine.rod_length", "longer than the crank radius"),
    (lambda r: r["material"].update(poisson_ratio=0.6), "material.poisson_ratio", "< 0.5"),
    (lambda r: r["material"].pop("density_kgm3"), "material.density_kgm3", "required"),
    (lambda r: r["engine"].update(cylindres=4), "engine.cylindres", "not a known field"),
    (lambda r: r.update(fillets={"pin": 12.0}), "fillets.pin", "half the thickness"),
    (lambda r: r.update(oil_holes={"diameter": 30.0, "in_pins": True}), "oil_holes.diameter", "smaller than the length"),
    # Issue 53: a drilling's exit tangent to its fillets (25/2 - 15/2 - 5 = 0 mm) is a surface Gmsh cannot
    # mesh; one that cuts into them (24/2 - 16/2 - 5 = -1 mm) a notch no fillet or bore model describes.
    (lambda r: r.update(fillets={"journal": 5.0}, oil_holes={"diameter": 15.0, "in_journals": True}),
     "journals.1.length", "the drilling's exit touches the 5.0 mm fillets"),
    (lambda r: r.update(fillets={"pin": 5.0}, oil_holes={"diameter": 16.0, "in_pins": True}),
     "pins.4.length", "cuts 1.0 mm into the 5.0 mm fillets"),
    (lambda r: r.update(attachments=[{"name": "x", "at": "middle", "polar_inertia_kgm2": 1.0}]),
     "attachments.1.at", "must be one of"),
    (lambda r: r.update(attachments=[{"name": "x", "at": "rear", "polar_inertia_kgm2": -1.0}]),
     "attachments.1.polar_inertia_kgm2", "> 0"),
    (lambda r: r["webs"].__setitem__(0, {"thickness": 20.0, "width_journal": 90.0, "width_pin": 70.0,
                                         "counterweight_radius": 80.0}),
     "webs.1.counterweight_radius", "both"),
    (lambda r: r.update(uncertainty={"webs.*.thickness": [22.0, 25.0]}), "uncertainty.webs.*.thickness",
     "nominal value"),
    (lambda r: r.update(uncertainty={"webs.*.thicknes": [18.0, 25.0]}), "uncertainty.webs.*.thicknes",
     "does not name a numeric field"),
    (lambda r: r.update(uncertainty={"pins.*.length": [30.0, 20.0]}), "uncertainty.pins.*.length", "low < high"),
    # issue 56: the reference values of [meta] are typed and checked when read
    (lambda r: r.update(meta={"measured_first_torsional_hz": "530 Hz"}), "meta.measured_first_torsional_hz",
     "must be a frequency in Hz > 0"),
    (lambda r: r.update(meta={"paper_lumped_first_torsional_hz": {"17": -1.0}}), "meta.paper_lumped_first_torsional_hz",
     "must be a table of partition = frequency"),
    # issue 56: a count cannot vary between its bounds (it was refused only by the bounds' firing orders)
    (lambda r: r.update(uncertainty={"engine.cylinders": [3, 5]}), "uncertainty.engine.cylinders",
     "'engine.cylinders' is a count (an integer field)"),
]


@pytest.mark.parametrize("mutate, field, rule", CASES)
def test_each_rule_names_field_value_and_rule(mutate, field, rule):
    raw = simple_crank_raw()
    mutate(raw)
    problems, message = problems_of(raw)
    hits = [p for p in problems if p.field == field]
    assert hits, f"no problem names {field}: {message}"
    assert any(rule in p.rule for p in hits), message
    assert field in message and "test.toml" in message


def test_all_problems_reported_at_once():
    raw = simple_crank_raw()
    raw["journals"][0] = {"diameter": -1.0, "length": 0.0}
    raw["engine"]["firing_order"] = [1]
    problems, _ = problems_of(raw)
    assert {"journals.1.diameter", "journals.1.length", "engine.firing_order"} <= {p.field for p in problems}


@pytest.mark.parametrize("chain, field", [
    ({"inertias_kgm2": [1.0, 2.0], "stiffnesses_nm_per_rad": [1.0, 2.0]}, "chain.stiffnesses_nm_per_rad"),
    ({"inertias_kgm2": [1.0, -2.0], "stiffnesses_nm_per_rad": [1.0]}, "chain.inertias_kgm2[2]"),
    ({"inertias_kgm2": [1.0, 2.0], "stiffnesses_nm_per_rad": [1.0], "relative_damping_nms_per_rad": [1.0, 1.0]},
     "chain.relative_damping_nms_per_rad"),
    ({"inertias_kgm2": [1.0, 2.0], "stiffnesses_nm_per_rad": [1.0], "springs": [1.0]}, "chain.springs"),
])
def test_chain_rules(chain, field):
    with pytest.raises(DescriptionError) as info:
        parse_chain({"chain": chain})
    assert field in [p.field for p in info.value.problems], str(info.value)


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(DescriptionError, match="does not exist"):
        fetorsion.load(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[units\nlength = 'mm'")
    with pytest.raises(DescriptionError, match="not valid TOML"):
        fetorsion.load(bad)


def test_a_variant_is_its_base_with_its_own_tables_replaced_whole(tmp_path):
    """peugeot_glx_engine.toml extends peugeot_glx.toml: the geometry is the base's to the
    number, the tables the variant gives are the variant's alone (attachments: none in the
    base, four here; [meta]: the base's measured frequency of the crank ALONE is not inherited)."""
    base = fetorsion.load(GEOMETRY / "peugeot_glx.toml")
    engine = fetorsion.load(GEOMETRY / "peugeot_glx_engine.toml")
    for part in ("journals", "pins", "webs", "front", "rear", "fillets", "oil_holes", "material", "uncertainty"):
        assert getattr(engine, part) == getattr(base, part), part
    assert len(base.attachments) == 0 and len(engine.attachments) == 4
    assert base.excitation is None and engine.excitation is not None
    assert "measured_first_torsional_hz" in base.notes and "measured_first_torsional_hz" not in engine.notes
    # whole-table replacement: a variant's [fillets] with one key does not keep the base's other,
    # so the base's range on fillets.journal now names nothing and is refused by name
    (tmp_path / "base.toml").write_text((GEOMETRY / "peugeot_glx.toml").read_text())
    (tmp_path / "v.toml").write_text('extends = "base.toml"\n[fillets]\npin = 3.0\n')
    with pytest.raises(DescriptionError, match="fillets.journal.*does not name a numeric field"):
        fetorsion.load(tmp_path / "v.toml")
    (tmp_path / "w.toml").write_text('extends = "v.toml"\n[uncertainty]\n"fillets.pin" = [2.0, 4.0]\n')
    w = fetorsion.load(tmp_path / "w.toml")  # a variant of a variant
    assert w.fillets.pin == pytest.approx(3.0e-3) and w.fillets.journal == 0.0 and len(w.uncertainty) == 1


@pytest.mark.parametrize("path", ["webs.0.thickness", "webs.9.thickness", "webs.x.thickness", "bearings.1.length"])
def test_a_change_that_names_no_field_is_refused_by_its_path(path):
    """with_values (the studies', the calibration's and the design search's one way to a variant):
    a path whose table is not there (web 0 or 9 of eight, an index that is no number, a table the
    file lacks) was applied to nothing, so the variant came back equal to its base without a word."""
    crank = fetorsion.load(GEOMETRY / "peugeot_glx.toml")
    with pytest.raises(DescriptionError, match=re.escape(path) + ".*names no table"):
        fetorsion.with_values(crank, {path: 25.0})
    assert fetorsion.with_values(crank, {"webs.8.thickness": 25.0}).webs[7].thickness == pytest.approx(0.025)
