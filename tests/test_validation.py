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
