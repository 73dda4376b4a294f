"""Validation against the measured 530 Hz (Renault 21) and 905.9 Hz (Peugeot GLX) as a test
(issue 13), by the code path that makes the README's validation table."""

import pytest
from conftest import GEOMETRY

import fetorsion
from fetorsion.description.defaults import CHECK_MESH_SIZE
from fetorsion.studies.validation import FE_ERROR_BOUND, run_validation


@pytest.mark.fe
@pytest.mark.parametrize("name", ["renault21.toml", "peugeot_glx.toml"])
def test_measured_f1_inside_fe_band_and_within_stated_error(name):
    # coarse, fast model (25 mm, no fillets or drillings): 3 FE runs of ~20 k DOF per crank
    res = run_validation(fetorsion.load(GEOMETRY / name), CHECK_MESH_SIZE, details=False)
    assert res.band_hz[0] < res.fe_hz < res.band_hz[1]
    assert res.measured_inside, res.table()
    assert abs(res.error) <= FE_ERROR_BOUND, res.table()


@pytest.fixture(scope="module", params=["renault21.toml", "peugeot_glx.toml"])
def default_modal(request):
    """A reference crank and its free-free FE at the default mesh (fillets and drillings), solved
    once for the module's two tests of it (pytest runs the tests of one crank together, so one
    crank's FE system is held at a time)."""
    from fetorsion.fe.crankfe import run_modal

    crank = fetorsion.load(GEOMETRY / request.param)
    return crank, run_modal(crank)


@pytest.mark.slow
@pytest.mark.fe
def test_modal_mesh_default_within_its_stated_f1_error(default_modal):
    from fetorsion.fe.crankfe import MODAL_F1_ERROR, run_modal
    from fetorsion.solid.mesh import default_fillet_size

    crank, modal = default_modal
    # Independent, finer discretisation of the same crank where f1 is most sensitive (the
    # fillet-size study of docs/modal-mesh.md): fillet and drilling elements × 0.8.
    fine = 0.8 * default_fillet_size(crank, 0.010, "modal")
    finer_f1 = run_modal(crank, fillet_size=fine, purpose="stress").first_torsional()
    assert modal.first_torsional() == pytest.approx(finer_f1, rel=MODAL_F1_ERROR)


@pytest.mark.slow
@pytest.mark.fe
def test_free_fe_condensed_and_full_model_in_bearings_agree_at_the_default_mesh(default_modal):
    """Issue 26, at the default mesh with fillets and drillings: the free-free 3D FE and the
    condensed crank's free-free f1 within 0.5 % (one system: expected ~1e-10), and the condensed
    crank in rigid bearings against the full 3D FE with the same bearings within 0.1 % (first 10
    modes)."""
    import numpy as np

    from fetorsion.fe.condensed import run_condensed

    crank, fe = default_modal
    cc = run_condensed(crank, system=fe.system, keep_full=True)
    assert cc.modes("free").first_torsional() == pytest.approx(fe.first_torsional(), rel=5e-3)
    np.testing.assert_allclose(cc.modes("bearings", 10).frequencies_hz, cc.full_modes("bearings", 10), rtol=1e-3)
