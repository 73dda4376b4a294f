"""Chain files with [engine] and [excitation] (issue 18): order analysis and forced response."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import fetorsion
from conftest import GEOMETRY, ROOT
from fetorsion.description.chain import parse_chain
from fetorsion.errors import DescriptionError
from fetorsion.excitation.campbell import run_campbell
from fetorsion.excitation.torque import cylinder_torque, harmonics
from fetorsion.lumped_model.lumped import chain_damping, chain_matrices, lumped, modal_damping_ratios
from fetorsion.response.forced import compare_curve, run_response

RPM = np.linspace(1000.0, 6000.0, 41)


def chain_of(crank, dof=17, **extra):
    """The chain a crank's lumped model gives, with the crank's own [engine] and [excitation] tables."""
    res = lumped(crank, dof)
    assert set(np.unique(res.pin_weights)) <= {0.0, 1.0}  # each pin wholly inside one station
    data = {"units": copy.deepcopy(crank.raw["units"]), "engine": copy.deepcopy(crank.raw["engine"]),
            "excitation": copy.deepcopy(crank.raw["excitation"]),
            "chain": {"inertias_kgm2": res.inertias_kgm2.tolist(),
                      "stiffnesses_nm_per_rad": res.stiffnesses_nm_per_rad.tolist(), "labels": res.labels,
                      "cylinder_stations": [int(np.argmax(w)) + 1 for w in res.pin_weights], **extra}}
    return parse_chain(data, crank.source)


@pytest.fixture(scope="module")
def renault():
    return fetorsion.load(GEOMETRY / "renault21.toml")


def test_chain_equals_its_crank_campbell(renault):
    # Same matrices, stations and excitation tables: identical arithmetic, so round-off only (1e-12).
    a, b = run_campbell(renault), run_campbell(chain_of(renault))
    for x, y in zip(a.crossings, b.crossings):
        assert (x.mode, x.order, x.in_range) == (y.mode, y.order, y.in_range)
        assert y.rpm == pytest.approx(x.rpm, rel=1e-12)
        assert y.severity == pytest.approx(x.severity, rel=1e-9)


@pytest.mark.parametrize("dof", [6, 17])
def test_chain_equals_its_crank_response(renault, dof):
    # A second, independent path to the same matrices (the file, not the partition); round-off only.
    ra = run_response(renault, dof, rpm=RPM)
    rb = run_response(chain_of(renault, dof), rpm=RPM)
    scale = ra.section_torque_nm.max()
    assert np.abs(ra.section_torque_nm - rb.section_torque_nm).max() <= 1e-9 * scale
    assert np.allclose(ra.pulley_angle_deg, rb.pulley_angle_deg, rtol=1e-9, atol=0)


def two_inertia(eta, J1=0.2, J2=1.0, k=2.0e5):
    data = {"units": {"length": "mm"},
            "engine": {"cylinders": 1, "cycle_strokes": 4, "stroke": 90.0, "rod_length": 150.0, "bore": 85.0,
                       "crank_angles_deg": [0.0], "firing_order": [1]},
            "excitation": {"reciprocating_mass_kg": 0.6, "speed_range_rpm": [500.0, 6000.0],
                           "compression_ratio": 16.0, "imep_pa": 1.0e6},
            "chain": {"inertias_kgm2": [J1, J2], "stiffnesses_nm_per_rad": [k], "loss_factors": [eta],
                      "cylinder_stations": [1]}}
    return parse_chain(data, "<two>")


def test_hysteretic_two_inertia_closed_form():
    # One order q on inertia 1, spring k(1+iη): the twist is φ = T_q / (k(1+iη)(1 + J1/J2) − ω²J1),
    # so the spring torque is k|φ|. One order, one harmonic: the half peak-to-peak is |k φ| exactly.
    J1, J2, k, eta, q = 0.2, 1.0, 2.0e5, 0.05, 2.0
    chain = two_inertia(eta, J1, J2, k)
    assert chain.excitation.modal_damping_ratio == 0.0  # stated damping only, not counted twice
    f_n = np.sqrt(k * (J1 + J2) / (J1 * J2)) / (2 * np.pi)
    rpm = np.linspace(0.7, 1.3, 61) * 60 * f_n / q
    res = run_response(chain, rpm=rpm, orders=[q])
    w = q * rpm * 2 * np.pi / 60
    Tq = np.array([abs(harmonics(cylinder_torque(chain, n).total, 4 * np.pi).at([q])[0]) for n in rpm])
    closed = k * Tq / np.abs(k * (1 + 1j * eta) * (1 + J1 / J2) - w**2 * J1)
    # The response takes the half peak-to-peak on 720 samples of the 4π cycle (π/180 apart): a sample can
    # miss the crest of order 2 by half a step, π/180 of phase, so it reads low by at most 1 − cos(π/180) = 1.52e-4.
    assert np.all(res.section_torque_nm[:, 0] <= closed * (1 + 1e-12))
    assert np.allclose(res.section_torque_nm[:, 0], closed, rtol=1.53e-4, atol=0)
    # At resonance the closed form reduces to T J2 / (η (J1 + J2)): the loss factor alone limits it.
    peak = closed.max() / Tq[closed.argmax()]
    assert peak == pytest.approx(J2 / (eta * (J1 + J2)), rel=2e-3)  # 2e-3: the 1 % speed grid misses ω_n


def test_modal_ratio_of_a_loss_factor_is_half_eta():
    # Uniform η on every spring: φᵀHφ = η φᵀKφ = η ω² m, so ζ = η / 2 on every mode (textbook).
    k = [1e5, 2e5, 3e5]
    M, _ = chain_matrices([1.0, 2.0, 1.5, 0.5], k)
    res = lumped(parse_chain({"chain": {"inertias_kgm2": [1.0, 2.0, 1.5, 0.5], "stiffnesses_nm_per_rad": k}}))
    C, H = chain_damping(4, k, loss_factors=[0.04] * 3)
    z = modal_damping_ratios(res.frequencies_hz, res.mode_shapes, res.inertias_kgm2, C, H)
    assert np.allclose(z, 0.02, rtol=1e-10)


def test_chain_without_stations_is_refused_clearly():
    chain = parse_chain({"chain": {"inertias_kgm2": [1.0, 2.0], "stiffnesses_nm_per_rad": [1e4]}})
    with pytest.raises(fetorsion.errors.FetorsionError, match="no \\[excitation\\]"):
        run_response(chain)
    with pytest.raises(DescriptionError, match="cylinder_stations"):
        parse_chain({"units": {"length": "mm"}, "engine": two_inertia(0.1).raw["engine"],
                     "chain": {"inertias_kgm2": [1.0, 2.0], "stiffnesses_nm_per_rad": [1e4]}})


def test_compare_reports_the_peaks(renault):
    res = run_response(renault, rpm=RPM)
    s = int(np.argmax(res.section_torque_nm.max(axis=0)))
    # The model's own curve, halved, compared with itself: the peak is at the same speed and +100 %.
    c = compare_curve(res, RPM, res.section_torque_nm[:, s] / 2, "half of itself", "N m")
    assert c["model_peak_rpm"] == c["curve_peak_rpm"]
    assert c["peak_difference_percent"] == pytest.approx(100.0, rel=1e-12)
    assert "half of itself" in res.table()


def test_cli_run_and_response_of_a_chain(tmp_path, capsys):
    from fetorsion.cli import main

    chain = str(ROOT / "examples/mendes2008/mwm6_chain.toml")
    out = tmp_path / "report"
    assert main(["run", chain, "--out", str(out)]) == 0  # no --no-fe needed: a chain has no FE step
    text = (out / "report.md").read_text()
    assert "Torsional chain" in text and "Campbell diagram and forced response" in text and "3D FE" not in text
    plot = tmp_path / "r.png"
    curve = tmp_path / "fig31.csv"  # a few points of a published curve, as a user would give them
    curve.write_text("# name = Mendes et al. 2008, Fig. 31\n# unit = N m\n1000, 3900\n2000, 6000\n2149, 9477\n2400, 3000\n")
    assert main(["response", chain, "--steps", "40", "--compare", str(curve),
                 "--compare-section", "8", "--plot", str(plot), "--json", str(tmp_path / "r.json")]) == 0
    printed = capsys.readouterr().out
    assert "compared with Mendes et al. 2008, Fig. 31" in printed and "cyl 6-flywheel" in printed
    assert plot.stat().st_size > 10_000
