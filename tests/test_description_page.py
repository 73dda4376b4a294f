"""The documented description format cannot drift from the reader.

Three links: the reader refuses to accept a field that ``fetorsion/description/fields.py`` does
not declare (``Table.finish`` raises); every declared field is in the generated Markdown; the
site's description-format and chain pages include that generated Markdown.
"""

import ast
import copy

import pytest

from conftest import ROOT, read_raw

from fetorsion.description import chain_fields, fields
from fetorsion.description.chain import parse_chain
from fetorsion.description.crank import parse_crank
from fetorsion.description.reader import Table

SECTION_SETS = {"crank": fields.CRANK_SECTIONS, "chain": chain_fields.CHAIN_SECTIONS}


@pytest.mark.parametrize("kind", SECTION_SETS)
def test_every_declared_field_is_in_the_generated_page(kind):
    text = fields.markdown(SECTION_SETS[kind])
    for section in SECTION_SETS[kind]:
        body = text.split(f"### `{section.header}`", 1)[1].split("\n### ", 1)[0]  # this table's part of the page
        for f in section.fields:
            shown = f"*{f.key[1:-1]}*" if f.key.startswith("<") else f"`{f.key}`"
            assert f"| {shown} |" in body, f"{section.header} {f.key} is not on the page"


@pytest.mark.parametrize("page, kind", [("description-format.md", "crank"), ("chain-format.md", "chain")])
def test_the_pages_include_the_generated_tables(page, kind):
    # docs/conf.py writes _generated/<kind>-fields.md from fields.markdown() before every build
    assert f"_generated/{kind}-fields.md" in (ROOT / "docs" / page).read_text()
    assert f'"{kind}-fields.md"' in (ROOT / "docs/conf.py").read_text()


def test_the_reader_refuses_to_read_an_undeclared_field():
    t = Table({"made_up": 1.0}, "units", [], schema=fields.CRANK_SCHEMA)
    t.number("made_up")
    with pytest.raises(RuntimeError, match="does not declare"):
        t.finish()
    t = Table({}, "not_a_table", [], schema=fields.CRANK_SCHEMA)
    with pytest.raises(RuntimeError, match="does not declare"):
        t.finish()


def _every_option(raw: dict) -> dict:
    """The Renault 21 description with every optional table and the less common branches filled in."""
    raw = copy.deepcopy(raw)
    n = raw["engine"]["cylinders"]
    raw["material"].update(tensile_strength_pa=9e8, yield_strength_pa=6.5e8, surface="ground", process="drop-forged",
                           source="test")
    raw["front"] = [{"diameter": 30.0, "length": 20.0, "bore": 0.0}]
    raw["rear"] = [{"diameter": 60.0, "length": 10.0}]
    raw["fillets"] = {"journal": 2.0, "pin": 2.0}
    raw["oil_holes"] = {"diameter": 5.0, "in_journals": True, "in_pins": True}
    raw["bearings"] = {"clearance": 0.03, "oil_viscosity_pa_s": 0.01, "load_n": 2000.0, "speed_rpm": 3000.0,
                       "axial_stiffness_n_per_m": 1e8, "thrust_journal": 1, "source": "test"}
    raw["dampers"] = [
        {"type": "rubber", "at": "front", "ring_inertia_kgm2": 6e-3, "hub_inertia_kgm2": 1e-3, "name": "r",
         "source": "test", "allowed_power_w": 100.0, "temperature_c": 60.0,
         "dynamic_table": [[20.0, 300.0, 3e4, 0.3], [20.0, 600.0, 4e4, 0.4],
                           [80.0, 300.0, 2e4, 0.3], [80.0, 600.0, 3e4, 0.4]]},
        {"type": "viscous", "at": "rear", "ring_inertia_kgm2": 6e-3, "housing_inertia_kgm2": 1e-3,
         "damping_nms_per_rad": 10.0},
        {"type": "tuned", "ring_inertia_kgm2": 6e-3, "stiffness_nm_per_rad": 3e4, "damping_nms_per_rad": 1.0},
    ]
    raw["limits"] = {"fatigue_method": "fe", "fatigue_strength_bending_pa": 4e8, "fatigue_required_safety": 1.2, "additional_bending_pa": 1e7,
                     "source": "test"}
    ex = raw["excitation"]
    for key in ("pressure_csv", "imep_pa", "peak_pressure_pa"):
        ex.pop(key, None)
    ex.update(imep_pa=1.2e6, compression_ratio=9.0, intake_pressure_pa=1e5, polytropic_exponent=1.3,
              combustion_start_deg=-15.0, combustion_duration_deg=50.0, wiebe_a=5.0, wiebe_m=2.0,
              overspeed_factor=1.1, modal_damping_ratio=0.02, modal_damping_ratio_source="test", modal_damping_band=[0.01, 0.02],
              modal_damping_source="test")
    assert len(raw["journals"]) == n + 1
    return raw


def test_a_description_with_every_option_reads():
    # Every branch of the reader runs its finish() against the declared fields: none raises.
    parse_crank(_every_option(read_raw("renault21.toml")), source=str(ROOT / "geometry/renault21.toml"),
                check_uncertainty=False)
    for name in ("peugeot_glx.toml", "renault21.toml"):
        parse_crank(read_raw(name), source=str(ROOT / "geometry" / name))


def test_a_chain_with_every_option_reads():
    import tomllib

    raw = tomllib.loads((ROOT / "examples/mendes2008/mwm6_chain.toml").read_text())
    raw["chain"]["relative_damping_nms_per_rad"] = [0.0] * (len(raw["chain"]["inertias_kgm2"]) - 1)
    raw["limits"] = {"continuous_torque_nm": 1e4, "transient_torque_nm": 2e4, "source": "test"}
    parse_chain(raw, source=str(ROOT / "examples/mendes2008/mwm6_chain.toml"))


ACCESSORS = {"number", "integer", "text", "flag", "numbers", "tables", "table", "get", "raw", "choice",
             "_per_journal", "_per_spring"}


def test_every_literal_field_the_reader_asks_for_is_declared():
    # A static check on the reader's source as well, for branches no description above reaches:
    # a literal key handed to a Table accessor must be declared in some table.
    declared = set().union(*(s.keys for s in fields.CRANK_SECTIONS + chain_fields.CHAIN_SECTIONS))
    declared |= {s.name for s in fields.CRANK_SECTIONS + chain_fields.CHAIN_SECTIONS}
    tree = ast.parse((ROOT / "fetorsion/description/crank.py").read_text())
    asked = set()
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        func = node.func
        name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
        receiver = func.value.id if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) else ""
        # t.number("key"), _per_journal(t, "key", ...); data.get / ex.get read a raw dict, not a Table
        key = node.args[1] if name.startswith("_per") and len(node.args) > 1 else node.args[0] if node.args else None
        if name in ACCESSORS and receiver not in {"data", "ex", "spec", "raw"} \
                and isinstance(key, ast.Constant) and isinstance(key.value, str):
            asked.add(key.value)
    assert asked, "the scan found no accessor call"
    assert asked <= declared, sorted(asked - declared)
