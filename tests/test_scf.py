"""Fillet stress concentration from fetorsion's static 3D FE (issue 14) against a published fit."""

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
