"""The verdict's shorter ways to the same numbers (issue 52's speed): each against the long way it
replaces, or against an analytic root."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import fetorsion
from fetorsion.description.model import Damper

GEOMETRY = Path(__file__).resolve().parent.parent / "geometry"


@pytest.fixture(scope="module")
def renault():
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.stress import fillets_of
    from fetorsion.response.forced import response_setup

    crank = fetorsion.load(GEOMETRY / "renault21.toml")
    # the lumped chain solved as the condensed crank is (projected on its modes), on fewer speeds
    setup = dataclasses.replace(response_setup(crank, rpm=np.linspace(1000, 7000, 61)), projected=True)
    return crank, setup, fillets_of(crank), verdict_scfs(crank)


def test_misfire_responses_superpose_on_the_firing_one(renault):
    """with_misfires (one block solve of the cylinders' changes of force, added to the firing
    response) against each misfire's own solve: the same linear system, to round-off."""
    from fetorsion.response.forced import misfire_harmonics

    crank, setup, _, _ = renault
    motored = misfire_harmonics(crank, setup)
    together = setup.with_misfires(motored)
    assert [s.misfire for s in together] == list(range(crank.engine.cylinders))
    for c, s in enumerate(together):
        alone = setup.with_misfire(c, motored).free_response
        assert np.abs(s.free_response - alone).max() <= 1e-9 * np.abs(alone).max()


@pytest.mark.parametrize("damped", [False, True])
def test_m53_safety_alone_is_the_whole_assessments(renault, damped):
    """The damping searches' M53 safety (the two largest torques synthesised by bound, the rule's
    bending held) against the whole assessment's governing safety (every section at every speed
    synthesised, run_m53_crank): equal to round-off, with and without a damper."""
    from fetorsion.design.methods import FATIGUE_METHODS, ConfigLoads

    crank, setup, fillets, scf = renault
    dampers = (Damper("rubber", "front", 0.0, 0.0057, 5.4e4, 0.0, 0.1),) if damped else ()
    loads = ConfigLoads(crank, None, setup, dampers, fillets, scf)
    m53 = FATIGUE_METHODS["iacs-m53"]
    assert m53.safety(loads) == pytest.approx(m53.answer(m53.assess(loads)).safety, rel=1e-12)


def test_the_utilisations_largest_value_from_the_group_maxima(renault):
    """The damper optimiser's objective: M53's utilisation at the pin and journal maxima alone
    equals its largest value over the speeds with every signal synthesised."""
    from fetorsion.design.m53 import m53_utilisation, run_m53_crank
    from fetorsion.response.forced import section_torques, solve_theta
    from fetorsion.response.synthesis import group_maxima, half_peak_to_peak

    crank, setup, fillets, scf = renault
    held = run_m53_crank(crank, fillets, np.zeros((1, len(fillets))), setup.rpm[:1], fe_scf=scf)
    utilisation = m53_utilisation(held, fillets, setup)
    z = section_torques(setup, solve_theta(setup, ())[0])
    whole = utilisation(half_peak_to_peak(z, setup.orders, setup.period)).max()
    assert utilisation(group_maxima(z, setup.orders, setup.period, utilisation.groups))[0] == pytest.approx(whole, rel=1e-12)


@pytest.mark.parametrize("power, offset, required", [(1.0, 0.0, 1.15), (0.4, 0.9, 1.4), (0.15, 1.5, 3.8)])
def test_the_flip_search_meets_the_analytic_root(power, offset, required):
    """safety(ζ) = offset + 2 (ζ/0.01)^power (a resonance alone: power 1; a bending share that
    damping does not move: an offset and a smaller power), from the default band's two points:
    the root ζ* = 0.01 ((required − offset)/2)^(1/power) within 2e-3 in ln ζ (the stop is a secant
    step under 1e-3, the step's own slope error at most as much again), in at most six more
    evaluations."""
    from fetorsion.design.crank_verdict import _flip

    calls = []

    def safety(z):
        calls.append(z)
        return offset + 2.0 * (z / 0.01) ** power

    band = {z: safety(z) for z in (1 / 120, 1 / 60)}
    calls.clear()
    flip = _flip(safety, required, band)
    root = 0.01 * ((required - offset) / 2.0) ** (1.0 / power)
    assert abs(math.log(flip.zeta / root)) < 2e-3
    assert len(calls) <= 6


def test_the_flip_search_says_where_it_ends():
    """A crank that passes at the bracket's low end, and one that fails at its high end."""
    from fetorsion.design.crank_verdict import FLIP_BRACKET, _flip

    passes = _flip(lambda z: 5.0 + z, 1.15, {0.01: 5.01})
    fails = _flip(lambda z: 0.5 + z, 1.15, {0.01: 0.51})
    assert passes.zeta is None and f"passes down to ζ = {FLIP_BRACKET[0]:g}" in passes.kind
    assert fails.zeta is None and f"fails up to ζ = {FLIP_BRACKET[1]:g}" in fails.kind
