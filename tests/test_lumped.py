"""Lumped torsional models against closed forms and the paper's equations (18)–(20)."""

import math

import numpy as np
import pytest

import fetorsion
from fetorsion.description.crank import parse_crank
from fetorsion.description.chain_model import Chain
from fetorsion.lumped_model.lumped import chain_matrices, partition_matrices, solve_chain
from fetorsion.lumped_model.parts import build_parts, oil_hole_inertia
from fetorsion.webs.classical import carter, ker_wilson
from fetorsion.webs.sections import effective_web_width
from fetorsion.solid.outline import mass_properties

from conftest import GEOMETRY, simple_crank_raw


def uniform_shaft(n, length=1.0, d=0.05, E=210e9, nu=0.3, rho=7850.0):
    """A free-free steel shaft cut into n equal pieces, one station at each piece centre."""
    G = E / (2 * (1 + nu))
    J = math.pi * d**4 / 32
    piece = length / n
    inertias = [rho * J * piece] * n
    springs = [G * J / piece] * (n - 1)
    c = math.sqrt(G / rho)
    return inertias, springs, c


def test_uniform_shaft_converges_to_free_free_torsion():
    # Exact: f_n = n c / (2 L). The chain's error falls as 1/N² (central differences).
    errors = []
    for n in (25, 50, 100, 200):
        inertias, springs, c = uniform_shaft(n)
        _, hz, _ = solve_chain(inertias, springs)
        exact = np.arange(1, 4) * c / 2.0
        errors.append(np.abs(hz[:3] / exact - 1))
    errors = np.array(errors)
    assert errors[-1].max() < 2e-4  # N = 200: (π n / 2N)²/24 ≈ 1.4e-4 for n = 3
    ratios = errors[:-1] / errors[1:]
    assert np.all((ratios > 3.8) & (ratios < 4.2))  # second-order convergence


def test_two_inertia_closed_form():
    I1, I2, k = 0.3, 0.05, 2.0e5
    rigid, hz, shapes = solve_chain([I1, I2], [k])
    assert abs(rigid) < 1e-3
    assert hz[0] == pytest.approx(math.sqrt(k * (I1 + I2) / (I1 * I2)) / (2 * math.pi), rel=1e-12)
    # Node position: amplitudes inversely proportional to inertia, opposite sign.
    assert shapes[0, 0] == pytest.approx(1.0)
    assert shapes[0, 1] == pytest.approx(-I1 / I2, rel=1e-10)


def test_five_dof_matrices_are_eq_18_to_20_term_by_term():
    crank = parse_crank(simple_crank_raw())
    rho, G, R = 8000.0, 200e9 / 2.5, 0.040
    d_e = 0.060
    J_e = math.pi * d_e**4 / 32

    def k_of(L_e):
        return G * J_e / L_e

    # Parts by hand (eq. 3–5, 14, 16).
    k_t = k_of(0.025)
    k_m = k_of(0.024 * (60 / 50) ** 4)
    k_b = k_of(carter(crank, 0, d_e))
    k_td = 1 / (1 / k_of(0.050 * (60 / 40) ** 4) + 1 / k_t)  # nose + journal 1
    k_tv = 1 / (1 / k_t + 1 / k_of(0.015 * (60 / 80) ** 4))  # journal 5 + flange
    I_t = math.pi / 32 * rho * 0.025 * 0.060**4
    I_m = math.pi / 4 * rho * 0.024 * (0.050**4 / 8 + 0.050**2 * R**2)
    I_b = mass_properties(crank.webs[0], R, rho)["polar_inertia"]
    I_td = math.pi / 32 * rho * 0.050 * 0.040**4 + I_t
    I_tv = I_t + math.pi / 32 * rho * 0.015 * 0.080**4
    expect_k = [
        1 / (1 / k_td + 1 / k_m + 2 / k_b + 1 / (2 * k_t)),
        1 / (1 / k_t + 1 / k_m + 2 / k_b),
        1 / (1 / k_t + 1 / k_m + 2 / k_b),
        1 / (1 / k_tv + 1 / k_m + 2 / k_b + 1 / (2 * k_t)),
    ]
    expect_i = [I_td + I_b + I_m / 2, I_m + I_t + 2 * I_b, I_m + I_t + 2 * I_b, I_m + I_t + 2 * I_b,
                I_tv + I_b + I_m / 2]
    inertias, springs, labels, _ = partition_matrices(build_parts(crank, "carter"), 5)
    assert labels == ["front", "J2", "J3", "J4", "rear"]
    np.testing.assert_allclose(springs, expect_k, rtol=1e-12)
    np.testing.assert_allclose(inertias, expect_i, rtol=1e-12)


def test_five_dof_attachments_follow_eq_20():
    raw = simple_crank_raw()
    raw["attachments"] = [
        {"name": "pulley", "at": "front", "polar_inertia_kgm2": 1e-3},
        {"name": "flywheel", "at": "rear", "polar_inertia_kgm2": 5e-2},
        {"name": "piston", "at": "pins", "polar_inertia_kgm2": 2e-3},
    ]
    bare = partition_matrices(build_parts(parse_crank(simple_crank_raw())), 5)[0]
    loaded = partition_matrices(build_parts(parse_crank(raw)), 5)[0]
    np.testing.assert_allclose(loaded - bare, [1e-3 + 1e-3, 2e-3, 2e-3, 2e-3, 5e-2 + 1e-3], rtol=1e-9)


@pytest.mark.parametrize("dof", fetorsion.PARTITIONS)
def test_partitions_conserve_inertia_and_give_paper_sizes(dof, renault_raw):
    crank = parse_crank(renault_raw)
    chain = build_parts(crank)
    inertias, springs, labels, anchors = partition_matrices(chain, dof)
    assert len(inertias) == dof == len(labels) and len(springs) == dof - 1
    total = sum(p.inertia + p.attached_inertia for p in chain.parts) + chain.front_inertia + chain.rear_inertia
    assert inertias.sum() == pytest.approx(total, rel=1e-12)
    # Springs in series over the whole shaft = compliance between the outermost anchors, summed
    # here part by part (each part's compliance spread uniformly along it), not by the model's
    # cumulative interpolation.
    assert np.all(np.diff(anchors) > 0)
    a0, a1 = anchors[0], anchors[-1]
    between = sum(p.compliance * max(0.0, min(p.x1, a1) - max(p.x0, a0)) / (p.x1 - p.x0) for p in chain.parts)
    assert np.sum(1.0 / springs) == pytest.approx(between, rel=1e-12)


def test_rigid_station_merge_stiffens_17_vs_19():
    # 17 DOF lumps nose and flange rigidly into the end journals; 19 DOF gives them their
    # own compliance, so its first frequency cannot be higher (Rayleigh: added flexibility).
    crank = fetorsion.load(str(GEOMETRY / "renault21.toml"))
    f17 = fetorsion.lumped(crank, 17).frequencies_hz[0]
    f19 = fetorsion.lumped(crank, 19).frequencies_hz[0]
    assert f19 <= f17


def test_chain_file_matches_equivalent_crank(tmp_path):
    crank = fetorsion.load(str(GEOMETRY / "renault21.toml"))
    res = fetorsion.lumped(crank, dof=5)
    text = "[chain]\nname = 'r21 5dof'\n"
    text += "inertias_kgm2 = [" + ", ".join(repr(float(v)) for v in res.inertias_kgm2) + "]\n"
    text += "stiffnesses_nm_per_rad = [" + ", ".join(repr(float(v)) for v in res.stiffnesses_nm_per_rad) + "]\n"
    (tmp_path / "c.toml").write_text(text)
    chain = fetorsion.load(tmp_path / "c.toml")
    assert isinstance(chain, Chain)
    M1, K1 = chain_matrices(res.inertias_kgm2, res.stiffnesses_nm_per_rad)
    M2, K2 = chain_matrices(chain.inertias, chain.stiffnesses)
    np.testing.assert_array_equal(M1, M2)
    np.testing.assert_array_equal(K1, K2)
    np.testing.assert_allclose(fetorsion.lumped(chain).frequencies_hz, res.frequencies_hz, rtol=1e-12)


def test_throw_methods_sum_to_published_throw_formula():
    crank = parse_crank(simple_crank_raw())
    d_e, l_j, l_p, D_p, h, R = 0.060, 0.025, 0.024, 0.050, 0.020, 0.040
    b = effective_web_width(crank.webs[0])
    ratio = (d_e / D_p) ** 4
    per_throw = l_j + l_p * ratio + carter(crank, 0, d_e) + carter(crank, 1, d_e)
    assert per_throw == pytest.approx(l_j + 0.8 * h + 0.75 * l_p * ratio + 1.5 * R * d_e**4 / (h * b**3), rel=1e-12)
    per_throw = l_j + l_p * ratio + ker_wilson(crank, 0, d_e) + ker_wilson(crank, 1, d_e)
    expect = (l_j + 0.4 * d_e) + (l_p + 0.4 * D_p) * ratio + (R - 0.2 * (d_e + D_p)) * d_e**4 / (h * b**3)
    assert per_throw == pytest.approx(expect, rel=1e-12)


def test_effective_web_width_eq7():
    crank = parse_crank(simple_crank_raw())
    b = effective_web_width(crank.webs[0])
    assert 1 / b**3 == pytest.approx(0.5 * (1 / 0.090**3 + 1 / 0.070**3), rel=1e-12)


def test_oil_hole_inertia_matches_eq17_and_corrected_eq15():
    from fetorsion.description.model import Cylinder
    rho, phi, D, R = 7850.0, 0.005, 0.060, 0.041
    eq17 = math.pi / 48 * rho * phi**2 * D * (3 * (phi / 2) ** 2 + D**2)
    assert oil_hole_inertia(Cylinder(D, 0.02), phi, rho) == pytest.approx(eq17, rel=1e-12)
    # Eq. (15) with the exact h²/12 (the paper prints h²/16).
    eq15 = math.pi / 4 * rho * phi**2 * D * (phi**2 / 16 + D**2 / 12 + R**2)
    assert oil_hole_inertia(Cylinder(D, 0.02), phi, rho, R) == pytest.approx(eq15, rel=1e-12)


def test_mode_shapes_as_paper_figs_13_14():
    # Seed 003: with a flywheel its end barely moves; crank alone, the flywheel end swings most.
    r21 = fetorsion.lumped(fetorsion.load(str(GEOMETRY / "renault21.toml")), 17)
    glx = fetorsion.lumped(fetorsion.load(str(GEOMETRY / "peugeot_glx.toml")), 17)
    assert r21.mode_shapes[0, 0] == pytest.approx(1.0) and glx.mode_shapes[0, 0] == pytest.approx(1.0)
    # Qualitative in the paper; "barely moves" read as under half the pulley-end swing.
    assert abs(r21.mode_shapes[0, -1]) < 0.5
    assert abs(glx.mode_shapes[0, -1]) >= np.abs(glx.mode_shapes[0]).max() - 1e-12


def test_mode_shapes_are_eigenvectors():
    res = fetorsion.lumped(fetorsion.load(str(GEOMETRY / "peugeot_glx.toml")), 21)
    M, K = chain_matrices(res.inertias_kgm2, res.stiffnesses_nm_per_rad)
    w2 = (2 * np.pi * res.frequencies_hz) ** 2
    resid = K @ res.mode_shapes.T - M @ res.mode_shapes.T * w2
    assert np.abs(resid).max() < 1e-8 * np.abs(K @ res.mode_shapes.T).max()
    assert np.all(np.diff(res.frequencies_hz) > 0)
