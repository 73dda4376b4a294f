"""Plausible cranks of new users (issue 53): the generator itself, and a seeded sample of the
sweep (benchmarks/bench_plausible_sweep.py, docs/plausible-cranks.md) through both FE steps."""

import numpy as np
import pytest

from fetorsion.description.crank import parse_crank
from fetorsion.description.plausibility import plausibility_warnings
from fetorsion.description.samples import LAYOUTS, plausible_crank, plausible_cranks


def test_draws_are_valid_plausible_and_repeatable():
    """Every draw passes the reader and warns on nothing (the plausibility ranges are the
    reader's own), each layout is drawn, each feature on and off; one seed, one crank set."""
    raws = plausible_cranks(7, 120)
    cranks = [parse_crank(raw, source=f"draw {i}") for i, raw in enumerate(raws)]
    assert all(not plausibility_warnings(c) for c in cranks)
    assert {c.cylinders for c in cranks} == set(LAYOUTS)
    for key in ("fillets", "oil_holes"):
        assert 0 < sum(key in raw for raw in raws) < len(raws), key
    assert 0 < sum("counterweight_radius" in raw["webs"][0] for raw in raws) < len(raws)
    assert plausible_cranks(7, 3) == raws[:3]
    assert plausible_crank(np.random.default_rng(1)) != plausible_crank(np.random.default_rng(2))
