"""Static FE torsion (issue 8): closed forms, the stepped-shaft chart, throws, web method 'fe'."""

import dataclasses
import json
import math

import pytest

import fetorsion
from fetorsion.webs import throwfe
from fetorsion.description.crank import parse_crank
from fetorsion.description.model import Material
from fetorsion.webs.methods import WEB_METHODS, web_equivalent_length
from fetorsion.webs.sections import cylinder_equivalent_length, step_fillet_length
from fetorsion.fe.tetmesh import cylinder_mesh
from fetorsion.webs.throwfe import static_torsion, stepped_shaft_mesh, throw_of

from conftest import GEOMETRY, simple_crank_raw

pytestmark = [pytest.mark.fe]

STEEL = Material(210e9, 0.3, 7850.0, "steel")
G = STEEL.shear_modulus


def test_cylinder_matches_gj_over_l():
    L, D = 0.2, 0.05
    k, _ = static_torsion(cylinder_mesh(L, D, 0.01), STEEL)
    # Pure torsion of a round bar is bilinear in x and y, z: inside P2, so only the
    # curved-boundary geometry error is left (measured 1e-5).
    assert k == pytest.approx(G * math.pi * D**4 / (32 * L), rel=5e-3)


def test_nestorides_fit_reproduces_its_own_test_datum():
    # tsecdl.f comment: d21 = 1.5, rr1 = 0.15 -> 0.060469665 (real kind of the Fortran code)
    assert step_fillet_length(1.0, 1.5, 0.075) == pytest.approx(0.060469665, rel=1e-6)
    assert step_fillet_length(1.0, 1.5, 0.3) == 0.0  # ρ > 0.52: no correction


def test_stepped_shaft_matches_sections_plus_nestorides_fillet():
    d, D, l_small, l_large, r = 0.04, 0.06, 0.12, 0.12, 0.003  # D/d = 1.5, r/(d/2) = 0.15
    k, _ = static_torsion(stepped_shaft_mesh(d, D, l_small, l_large, r, 0.01), STEEL)
    fe = G * math.pi * d**4 / (32 * k)
    sections = l_small + l_large * (d / D) ** 4
    nestorides = step_fillet_length(d, D, r)
    assert fe == pytest.approx(sections + nestorides, rel=5e-3)  # issue 8: ≤ 0.5 %
    # The step's own extra length: a chart fit read to about ±0.003 d (measured 0.0015 d
    # here, 0.006 d at ρ = 0.3 where the fit is flatter).
    assert (fe - sections) / d == pytest.approx(nestorides / d, abs=3e-3)


def _crank(cylinders=2):
    raw = simple_crank_raw(cylinders)
    raw["front"], raw["rear"] = [], []
    return parse_crank(raw)


def test_throw_of_is_journal_centre_to_journal_centre():
    crank = fetorsion.load(GEOMETRY / "peugeot_glx.toml")
    t = throw_of(crank, 3)
    assert [j.length for j in t.journals] == [0.5 * crank.journals[3].length, 0.5 * crank.journals[4].length]
    assert t.pins == (crank.pins[3],) and t.webs == crank.webs[6:8] and t.throws == 1
    assert throw_of(crank, 0) == throw_of(crank, 1)  # equal throws compare equal: one FE run
    with pytest.raises(fetorsion.FetorsionError, match="throw 5"):
        throw_of(crank, 4)


def test_whole_crank_is_its_throws_in_series():
    """Cutting at mid-journal with rigid faces costs nothing measurable: the static FE of
    the bare 2-throw crank equals the series of its throws and half end journals."""
    crank = _crank(2)
    size = 0.012
    whole = throwfe.torsional_stiffness_fe(crank, size)
    d_e = crank.journals[0].diameter
    ends = (crank.journals[0], crank.journals[-1])
    series = 0.5 * sum(cylinder_equivalent_length(j, d_e) for j in ends)
    series += sum(throwfe.torsional_stiffness_fe(throw_of(crank, i), size).equivalent_length(G_of(crank), d_e)
                  for i in range(2))
    # Same mesh size both ways; measured 0.14 % on the GLX crank (4 throws).
    assert whole.equivalent_length(G_of(crank), d_e) == pytest.approx(series, rel=5e-3)


def G_of(crank):
    return crank.material.shear_modulus


def test_fe_method_runs_fe_once_per_distinct_throw(monkeypatch, tmp_path):
    crank = _crank(2)
    calls = []
    real = throwfe.torsional_stiffness_fe
    monkeypatch.setattr(throwfe, "torsional_stiffness_fe", lambda *a, **k: calls.append(1) or real(*a, **k))
    monkeypatch.setattr(throwfe, "_CACHE", {})
    monkeypatch.setenv(throwfe.CACHE_ENV, str(tmp_path / "cache.json"))
    d_e = crank.journals[0].diameter
    values = [web_equivalent_length(crank, w, d_e, "fe") for w in range(4)]
    assert len(calls) == 1  # both throws alike
    assert max(values) == pytest.approx(min(values), rel=1e-12)
    # Between the elementary beam bound (no local flexibility: too stiff) and 3x it.
    assert WEB_METHODS["beam"](crank, 0, d_e) < values[0] < 3 * WEB_METHODS["beam"](crank, 0, d_e)
    # The user cache file is read back in a fresh process (here: a cleared memory cache).
    assert len(json.loads((tmp_path / "cache.json").read_text())) == 1
    monkeypatch.setattr(throwfe, "_CACHE", {})
    assert web_equivalent_length(crank, 0, d_e, "fe") == values[0] and len(calls) == 1
    # A different throw is a different key.
    other = dataclasses.replace(crank, pins=tuple(dataclasses.replace(p, length=0.02) for p in crank.pins))
    assert throwfe.throw_key(throw_of(other, 0), None) != throwfe.throw_key(throw_of(crank, 0), None)


def test_short_drilled_journal_throw_meshes():
    """Issue 53's three-cylinder (the Renault's sections, 20 mm journals, 2.5 mm fillets, 5 mm
    drillings): the whole crank leaves 10 - 2.5 - 2.5 = 5 mm between each journal drilling and
    its fillets, but a half journal drilled at its own mid-length left 5 - 2.5 - 2.5 = 0 mm, and
    Gmsh could not mesh the tangent edges. The throw carries no journal drilling (its place is the
    throw's end face); the pin drilling stays, and the throw meshes."""
    from fetorsion.solid.mesh import default_fillet_size, mesh_crank

    renault = fetorsion.load(GEOMETRY / "renault21.toml")
    journals = tuple(dataclasses.replace(j, length=0.020) for j in renault.journals[:4])
    engine = dataclasses.replace(renault.engine, cylinders=3, crank_angles=(0.0, 2 * math.pi / 3, 4 * math.pi / 3),
                                 firing_order=(1, 2, 3))
    three = dataclasses.replace(renault, engine=engine, journals=journals, pins=renault.pins[:3],
                                webs=renault.webs[:6], uncertainty={})
    throw = throw_of(three, 1)
    assert not throw.oil_holes.in_journals and throw.oil_holes.in_pins
    size = throwfe.default_mesh_size(throw)
    mesh = mesh_crank(throw, size, default_fillet_size(throw, size, "stress"), "stress")
    assert mesh.quality.min_sicn > 0 and mesh.quality.n_tets > 1000


def test_reference_throws_are_shipped():
    """`fetorsion run --all` (every web method) must not mesh the reference throws again."""
    from fetorsion.design.scf import SHIPPED_SCF, scf_key

    shipped = json.loads(throwfe.SHIPPED_CACHE.read_text())
    scfs = json.loads(SHIPPED_SCF.read_text())
    for name in ("peugeot_glx", "renault21"):
        crank = fetorsion.load(GEOMETRY / f"{name}.toml")
        for i in range(crank.throws):
            assert throwfe.throw_key(throw_of(crank, i), None) in shipped, (name, i)
    for name in ("peugeot_glx", "renault21", "inline6_diesel"):  # `fetorsion run` meshes no SCF throw of theirs
        assert scf_key(fetorsion.load(GEOMETRY / f"{name}.toml")) in scfs, name


def test_the_reference_cranks_in_bearing_throw_stiffnesses_are_shipped(monkeypatch):
    """Each reference crank's fe-held entry is found under the key the code computes today (no
    FE; the cache of the environment left out). The key once held every engine field, and the vee
    engines' new ones orphaned both entries silently: a `run --no-fe` then condensed the whole
    crank (37 s) for one column of the lumped table. A field that does not change a stiffness
    (firing order, rods, banks) leaves the key as it is."""
    monkeypatch.delenv(throwfe.CACHE_ENV, raising=False)
    monkeypatch.setattr(throwfe, "_CACHE", {})
    for name in ("renault21.toml", "peugeot_glx.toml"):
        crank = fetorsion.load(GEOMETRY / name)
        assert throwfe.held_stiffnesses_stored(crank), name
        fired = dataclasses.replace(crank, engine=dataclasses.replace(crank.engine, firing_order=(1, 2, 4, 3)))
        assert throwfe.held_key(fired, 0.01) == throwfe.held_key(crank, 0.01)
