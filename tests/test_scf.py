"""Fillet stress concentration from fetorsion's static 3D FE (issue 14) against a published fit."""

import json
import math

import numpy as np
import pytest

from fetorsion.description.model import Material
from fetorsion.design.scf import nominal_shear, peterson_stepped_torsion, stepped_shaft_scf

STEEL = Material(210e9, 0.3, 7850.0, "steel")


@pytest.mark.fe
def test_stepped_shaft_scf_matches_petersons_torsion_fit():
    # D/d = 1.2, r/d = 0.05 (h/r = 2, inside the fit's 0.25..4): Peterson's fit gives 1.560.
    d, D, r = 0.040, 0.048, 0.002
    published = peterson_stepped_torsion(D, d, r)
    fe, info = stepped_shaft_scf(d, D, r, size=0.008, fillet_size=r / 4, material=STEEL)
    # Issue 14: within 5 %. Measured: 1.556 at r/4 (78 k DOF) and 1.553 at r/16 (238 k DOF),
    # so the mesh is converged to 0.2 % and the rest is the fit's own reading of the chart.
    assert fe.scf == pytest.approx(published, rel=0.05)
    assert fe.scf == pytest.approx(1.553, rel=0.01)  # the converged FE value (r/16), mesh error at r/4
    # The peak lies on the fillet's arc (within the radius of its centre), not at an end face.
    x, y, z = fe.where_m
    assert math.hypot(x - (3 * d - r), math.hypot(y, z) - (d / 2 + r)) == pytest.approx(r, rel=0.02)
    assert info["dofs"] > 10_000


def test_hollow_nominal_shear_is_the_elementary_formula():
    # τ = T r / J with J = π (D⁴ − d⁴)/32 at r = D/2: written out independently of nominal_shear.
    T, D, d = 500.0, 0.05, 0.02
    J = math.pi * (D**4 - d**4) / 32
    assert nominal_shear(T, D, d) == pytest.approx(T * (D / 2) / J, rel=1e-14)
    assert np.allclose(nominal_shear(np.array([T, 2 * T]), D), [16 * T / (math.pi * D**3), 32 * T / (math.pi * D**3)])


@pytest.mark.fe
def test_stepped_shaft_bending_scf_against_the_published_fits():
    """Bending of a stepped round bar, D/d = 1.5, r/d = 0.1 (h/r = 2.5, inside both fits), pure
    couple: the FE peak principal stress over 32 M/(π d³), converged (fillet elements r/2 and r/4
    within 2 %), against Peterson's chart fit and Roark's. Those fits come from estimates built
    on 2D and groove solutions; published 3D FE of filleted shafts finds them low by up to 24 %
    ([TiptonSorem], Machine Design 2009). So the check is: not below the fit, and not above it by
    more than that 24 %. Measured: 1.822 (r/2), 1.832 (r/4) against 1.743 (Peterson) and 1.733
    (Roark), +5 %: the issue's "within 5 % of Peterson" holds here only by a hair, and on
    D/d = 1.2, r/d = 0.05 the converged FE is 2.21 against 1.95 (+13 %)."""
    from fetorsion.design.scf import peterson_stepped_bending, roark_stepped_bending

    d, D, r = 0.040, 0.060, 0.004
    coarse, _ = stepped_shaft_scf(d, D, r, size=0.008, fillet_size=r / 2, material=STEEL, load="bending")
    fe, info = stepped_shaft_scf(d, D, r, size=0.008, fillet_size=r / 4, material=STEEL, load="bending")
    assert fe.scf == pytest.approx(coarse.scf, rel=0.02)  # converged
    for fit in (peterson_stepped_bending(D, d, r), roark_stepped_bending(D, d, r)):
        assert fit <= fe.scf <= 1.24 * fit
    # the peak sits on the tension side's extreme fibre (bending about z: y = -d/2 side), on the fillet
    x, y, z = fe.where_m
    assert abs(y) > 0.9 * (d / 2) and abs(z) < 0.3 * (d / 2)


def test_bending_fits_by_hand():
    """Peterson's and Roark's coefficient sets written out for one point of each range."""
    from fetorsion.design.scf import peterson_stepped_bending, roark_stepped_bending

    # h/r = 2.5 (upper sets), 2h/D = 1/3
    s, hr, t = math.sqrt(2.5), 2.5, 1 / 3
    pet = [1.232 + 0.832 * s - 0.008 * hr, -3.813 + 0.968 * s - 0.260 * hr, 7.423 - 4.868 * s + 0.869 * hr,
           -3.839 + 3.070 * s - 0.600 * hr]
    roa = [1.225 + 0.831 * s - 0.010 * hr, -3.790 + 0.958 * s - 0.257 * hr, 7.374 - 4.834 * s + 0.862 * hr,
           -3.809 + 3.046 * s - 0.595 * hr]
    for fit, c in ((peterson_stepped_bending, pet), (roark_stepped_bending, roa)):
        assert fit(0.060, 0.040, 0.004) == pytest.approx(c[0] + c[1] * t + c[2] * t**2 + c[3] * t**3, rel=1e-12)


def test_transverse_hole_fits_by_hand():
    """Peterson's tube-with-a-transverse-hole fits, written out for a solid bar (d_i = 0) and a tube."""
    from fetorsion.design.oilbore import peterson_transverse_hole_bending, peterson_transverse_hole_torsion

    a = 0.1
    assert peterson_transverse_hole_torsion(40.0, 4.0) == pytest.approx(
        4 - 6.055 * a + 32.764 * a**2 - 38.33 * a**3, rel=1e-12)
    assert peterson_transverse_hole_bending(40.0, 4.0) == pytest.approx(3 - 6.25 * a + 41 * a**2 - 45 * a**3, rel=1e-12)
    q, a = 0.5, 0.2
    c = (-6.055 + 3.184 * q - 3.461 * q**2, 32.764 - 30.121 * q + 39.887 * q**2, -38.33 + 51.542 * math.sqrt(q) - 27.483 * q)
    assert peterson_transverse_hole_torsion(50.0, 10.0, 25.0) == pytest.approx(4 + c[0] * a + c[1] * a**2 + c[2] * a**3,
                                                                               rel=1e-12)
    with pytest.raises(Exception, match="0 < d < D"):
        peterson_transverse_hole_torsion(40.0, 40.0)


@pytest.mark.fe
@pytest.mark.slow
def test_transverse_hole_scf_converges_within_ten_percent_of_peterson():
    """A 4 mm hole through a 40 mm bar (the oil bore's model): the peak σ₁ on the drilling's wall
    at wall elements d/16 and d/24 (issue 27: two successive levels within 2 %, and within 10 % of
    Peterson's value). Measured (2-core EPYC): torsion 4.026 → 3.980 (1.2 %), bending 3.004 →
    2.971 (1.1 %); Peterson 3.684 and 2.740, the FE 8.0 % and 8.4 % above and still coming down
    (d/32 on a coarser grading: torsion 3.92, bending 2.96)."""
    from fetorsion.design.oilbore import (peterson_transverse_hole_bending, peterson_transverse_hole_torsion,
                                          run_oil_bore_scf)

    D, d = 0.040, 0.004
    res = run_oil_bore_scf(D, d, material=STEEL)
    for load, fit in (("torsion", peterson_transverse_hole_torsion), ("bending", peterson_transverse_hole_bending)):
        assert res.change(load) < 0.02, res.table()
        assert getattr(res, load) == pytest.approx(fit(D, d), rel=0.10), res.table()
        # the peak is inside the drilling, not at its edge, and not deeper than the hole's diameter
        depth = res.rows[-1][f"{load}_depth_m"]
        assert 0 < depth < d, res.table()


def test_oil_bore_table_interpolates_the_direct_fe_of_the_reference_cranks():
    """The shipped d/D table of a drilled solid bar (d/24, least-squares quadratic) read at the
    reference cranks' own ratios (0.083 – 0.104, none on the table's grid) against the direct FE
    of those sections (shipped separately): within 2 %, the mesh's own convergence level (issue
    27). Measured: within 0.8 %."""
    import fetorsion
    from conftest import GEOMETRY
    from fetorsion.design.oilbore import SHIPPED_OIL_BORE, oil_bore_key, table_scfs

    direct = json.loads(SHIPPED_OIL_BORE.read_text())
    for name in ("renault21", "peugeot_glx"):
        crank = fetorsion.load(GEOMETRY / f"{name}.toml")
        for part in (crank.pins[0], crank.journals[0]):
            d = crank.oil_holes.diameter
            fe = direct[oil_bore_key(part.diameter, d, part.bore, 0.3)]
            table = table_scfs(part.diameter, d, part.bore, 0.3)
            for load in ("torsion", "bending"):
                assert table[load] == pytest.approx(fe[load], rel=0.02), (name, part, load)
    assert table_scfs(0.05, 0.005, 0.02, 0.3) is None  # a bored section: not the table's
    assert table_scfs(0.05, 0.015, 0.0, 0.3) is None  # d/D 0.3: outside it


@pytest.mark.fe
@pytest.mark.slow  # 17-28 s: one throw FE at the stress mesh; the default run stays under 10 minutes
def test_a_throws_web_stiffness_and_its_fillet_scfs_are_one_fe(monkeypatch):
    """The lumped ``fe`` column's throw stiffness and the fillet SCFs of the same throw: one mesh,
    one factorisation. The stiffness is T / twist of the SCF run's own torsion field, and equals a
    separate static-torsion solve of the same mesh (one more right-hand side changes nothing but
    round-off: 1e-9)."""
    import fetorsion
    import fetorsion.solid.mesh as solid_mesh
    from fetorsion.design.scf import throw_scfs
    from fetorsion.fe.tetmesh import TetMesh
    from fetorsion.webs import throwfe

    crank = fetorsion.load("geometry/renault21.toml")
    throw = throwfe.throw_of(crank, 0)
    size, fine = 0.02, 0.5 * crank.fillets.pin  # coarse: what is checked is the sharing, not the value
    meshes = []
    real = solid_mesh.mesh_crank
    monkeypatch.setattr(solid_mesh, "mesh_crank", lambda *a, **k: meshes.append(a) or real(*a, **k))
    throwfe._LAST_END_LOADED.clear()
    k = throwfe.torsional_stiffness_fe(throw, size, fine)
    cases, info = throw_scfs(crank, 0, size, fine)
    assert len(meshes) == 1 and info["dofs"] == k.dofs
    fe = throwfe.end_loaded_fe(throw, size, fine)
    assert k.stiffness == throwfe.TORQUE / fe.solutions[0].twist
    cm = fe.mesh  # Gmsh's optimiser may place nodes differently on a second meshing: the same mesh
    alone, _ = throwfe.static_torsion(TetMesh(cm.nodes, cm.tets, cm.node_sets), throw.material)
    assert alone == pytest.approx(k.stiffness, rel=1e-9)
    assert set(cases) == {"torsion", "bending", "bending_vm"} and all(s.scf > 1 for c in cases.values() for s in c)
