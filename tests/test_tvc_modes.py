"""The TVC's mode table (:mod:`fetorsion.design.tvc_modes`) against the two-inertia closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fetorsion.description.network import parse_network
from fetorsion.design.tvc_modes import mode_table

J1, J2, K = 1.0, 3.0, 1.0e4


def two_inertias():
    data = {"chain": {"name": "two", "stations": [{"name": "a", "inertia_kgm2": J1}, {"name": "b", "inertia_kgm2": J2}],
                      "shafts": [{"between": ["a", "b"], "stiffness_nm_per_rad": K}]}}
    return parse_network(data, "two.toml")


def test_mode_table_of_two_inertias_equals_the_closed_form():
    # f = √(k (J1 + J2)/(J1 J2))/2π; θ_b/θ_a = −J1/J2 (the momentum balance), the lighter station
    # swings most: a reads 1; resonances at 60 f/q inside the range only (to round-off, 1e-12)
    (row,) = mode_table(two_inertias(), np.array([1.0, 2.0, 3.0, 5.0]), (300.0, 1200.0))
    f = math.sqrt(K * (J1 + J2) / (J1 * J2)) / (2 * math.pi)
    assert row.frequency_hz == pytest.approx(f, rel=1e-12)
    assert np.allclose(row.amplitudes, [1.0, -J1 / J2], rtol=0, atol=1e-12)
    assert [q for q, _ in row.resonances] == [1.0, 2.0, 3.0]  # 60 f/5 = 220.6 rpm is below the range
    assert [n for _, n in row.resonances] == pytest.approx([60 * f, 30 * f, 20 * f], rel=1e-12)
