"""The load cycle at the fillet sections and the fatigue assessment built on it (issue 27)."""

import math

import numpy as np
import pytest
from conftest import GEOMETRY, assert_picture, plain

import fetorsion
from fetorsion.design.assessment import run_assessment, section_modulus_factor
from fetorsion.design.fatigue import m53_equivalent_fillet, m53_fatigue_strength
from fetorsion.design.scfset import SCFSet
from fetorsion.design.stress import Fillet, fillet_cuts, fillets_of
from fetorsion.response.cycle import LoadCycle


@pytest.mark.fe
def test_simply_supported_throw_carries_the_beam_bending_moment():
    """A single throw on two rigid journal bearings (held radially, free to rotate: simply
    supported) under a static radial pin force F: statics gives the bending moment at any
    section, M(x) = R1 (x − x_J1) left of the pin, R1 = F (x_J2 − x_P) / (x_J2 − x_J1); the
    condensed crank's fillet cuts must give it within 1 % (issue 27), about the throw-plane
    normal, with no torque."""
    from fetorsion.fe.condensed import run_condensed
    from fetorsion.response.coupled import pin_load_map
    from fetorsion.response.cycle import cut_throw_angles, static_solution
    from fetorsion.webs.throwfe import throw_of

    throw = throw_of(plain("renault21.toml"), 0)
    fillets = fillets_of(throw)
    cc = run_condensed(throw, mesh_size=0.015, cuts=fillet_cuts(throw, fillets))
    F = 1.0e4
    z = static_solution(cc, F * pin_load_map(cc)[0, 1])
    res = np.einsum("cjr,r->cj", cc.cut_rows, z)
    a = cut_throw_angles(cc)
    xj1, xp, xj2 = (cc.positions[cc.labels.index(k)][0] for k in ("J1", "P1", "J2"))
    r1 = F * (xj2 - xp) / (xj2 - xj1)
    for k, f in enumerate(fillets):
        beam = r1 * (f.x - xj1) - (F * (f.x - xp) if f.x > xp else 0.0)
        in_plane = -math.sin(a[k]) * res[k, 4] + math.cos(a[k]) * res[k, 5]
        assert abs(in_plane) == pytest.approx(abs(beam), rel=1e-2), f.label
        # no torque from a radial force: what is left comes from the coupling's edge ring of nodes
        # on the cut plane (its forces split between the sides), a fraction of the ring's share
        assert abs(res[k, 3]) < 2e-2 * abs(beam)


@pytest.mark.fe
def test_mean_torque_through_the_crank_is_the_sum_of_the_cylinders_mean_torques():
    """Order 0 in bearings, the flywheel end reacting the load torque: the mean torque through
    the section behind cylinder c is the sum of the mean torques R·F̄_t of cylinders 1 … c
    (statics; every cylinder's mean is the same), at every speed, within 1 %: the reduction
    is a Ritz approximation whose constraint modes take one fixed-point step (their static
    error is the step's contraction, a few 1e-3 at most), the same 1 % as the beam check."""
    from fetorsion.excitation.torque import cylinder_pin_forces
    from fetorsion.fe.condensed import run_condensed
    from fetorsion.response.cycle import mean_master_loads, static_solution

    crank = fetorsion.with_values(fetorsion.load(GEOMETRY / "renault21.toml"), {}, details=False)
    fillets = fillets_of(crank)
    cc = run_condensed(crank, mesh_size=0.025, cuts=fillet_cuts(crank, fillets))
    rpm = np.array([2000.0, 6000.0])
    z = static_solution(cc, mean_master_loads(cc, rpm))
    torque = np.einsum("cr,sr->sc", cc.cut_rows[:, 3], z)
    one = np.array([crank.engine.crank_radius * cylinder_pin_forces(crank, n)["tangential"].mean() for n in rpm])
    for k, f in enumerate(fillets):
        if f.kind != "journal" or f.index == 0:
            continue
        # a journal fillet behind pin f.index - 1 ... or ahead of pin f.index: cylinders ahead of it
        ahead = sum(1 for c in range(crank.throws) if cc.positions[cc.labels.index(f"P{c + 1}")][0] < f.x)
        np.testing.assert_allclose(np.abs(torque[:, k]), ahead * np.abs(one), rtol=1e-2)


def _cycle(bending, torque, fillets, my=None):
    """A LoadCycle with the given moments about z (in-plane for a throw at angle 0), torques and
    moments about y (speeds, cuts, angles)."""
    s, c, n = bending.shape
    history = np.zeros((s, c, 6, n))
    history[:, :, 5] = bending  # about z = e_t for a throw at angle 0
    history[:, :, 3] = torque
    if my is not None:
        history[:, :, 4] = my
    return LoadCycle("made up", np.linspace(1000, 3000, s), np.linspace(0, 4 * np.pi, n, endpoint=False),
                     [f.label for f in fillets], history.mean(axis=3), history, np.zeros(c))


def test_assessment_equals_a_hand_evaluation_of_the_m53_formulas(tmp_path):
    """Made-up histories on two fillets: nominal stresses from the section, × SCF, halves of the
    range, M53's equivalent stress and strength (written out here) give Q to 1e-9."""
    crank = fetorsion.load(GEOMETRY / "renault21.toml")
    fillets = [Fillet("pin", 0, 0.1, 0.048, 0.0), Fillet("journal", 1, 0.2, 0.0548, 0.01)]
    th = np.linspace(0, 4 * np.pi, 720, endpoint=False)
    speeds = np.array([1.0, 1.7])[:, None, None]
    bending = speeds * np.array([300.0, 120.0])[None, :, None] * (0.4 + np.sin(2 * th))[None, None, :]
    torque = speeds * np.array([150.0, 400.0])[None, :, None] * (0.1 + np.cos(th + 0.3))[None, None, :]
    my = speeds * np.array([-200.0, 250.0])[None, :, None] * (0.2 + np.cos(3 * th + 1.0))[None, None, :]
    scf = {"pin": 1.6, "journal": 1.4, "pin_bending": 2.6, "journal_bending": 2.1, "pin_oil_bore_bending": 1.9,
           "pin_oil_bore_torsion": 3.6, "journal_oil_bore_bending": 2.2, "journal_oil_bore_torsion": 3.3,
           "source": "made up"}
    res = run_assessment(crank, _cycle(bending, torque, fillets, my), fillets, SCFSet.from_dict(scf), "m53-criterion")
    # the Renault 21 drills pins and journals: one oil bore per drilled section here (P1, J2), its
    # nominal stresses those of its section (one fillet cut each here)
    assert res.labels == [f.label for f in fillets] + ["P1 oil bore", "J2 oil bore"]
    mat = res.worst.material
    for j, f in enumerate(fillets):
        w = f.diameter / (math.pi * (f.diameter**4 - f.bore**4))
        kb, kt = scf[f"{f.kind}_bending"], scf[f.kind]
        r = crank.fillets.pin if f.kind == "pin" else crank.fillets.journal
        for s in range(2):
            sa = kb * 0.5 * np.ptp(32 * w * bending[s, j])
            ta = kt * 0.5 * np.ptp(16 * w * torque[s, j])
            sv = math.sqrt(sa**2 + 3 * ta**2)
            dw = m53_fatigue_strength(mat.tensile_strength, f.diameter, r, mat.process, f"{f.kind}-fillet")
            assert res.safety[s, j] == pytest.approx(dw / sv, rel=1e-9)
            assert float(m53_equivalent_fillet(sa, ta)) == pytest.approx(sv, rel=1e-12)
        assert res.worst_rpm[j] == res.rpm[1]  # the larger loads govern
        # the oil bore of the same section, radius d/2: at the bore's edge both loads give a normal
        # stress along the edge, σ = γ_B σ_b ± γ_T τ (the sign with the larger range), no shear, so
        # M53's σ_V = σ/3 (1 + 2 √(1 + 0)) = σ; the drilling runs along throw a's tangent, so its
        # exits see the moment about e_r(a)
        a = crank.engine.crank_angles[f.index]
        m_r = math.cos(a) * my[1, j] + math.sin(a) * bending[1, j]
        part = (crank.pins if f.kind == "pin" else crank.journals)[f.index]  # the drilled section's own
        wb = part.diameter / (math.pi * (part.diameter**4 - part.bore**4))
        gb, gt = scf[f"{f.kind}_oil_bore_bending"], scf[f"{f.kind}_oil_bore_torsion"]
        sv = 0.5 * max(np.ptp(gb * 32 * wb * m_r + gt * 16 * wb * torque[1, j]),
                       np.ptp(gb * 32 * wb * m_r - gt * 16 * wb * torque[1, j]))
        dw = m53_fatigue_strength(mat.tensile_strength, f.diameter, 0.5 * crank.oil_holes.diameter, mat.process, "oil-bore")
        assert res.safety[1, 2 + j] == pytest.approx(dw / sv, rel=1e-9)
    assert section_modulus_factor(0.048, 0.0) == pytest.approx(0.048 / (math.pi * 0.048**4), rel=1e-15)
    assert res.safety.min(axis=0)[res.governing] == res.safety.min()
    # [limits] additional_bending_pa: M53's σ_add joins the fillets' alternating bending,
    # σ_V = √((σ_B + σ_add)² + 3τ²); the oil bores' equivalent has no such term
    from dataclasses import replace

    from fetorsion.description.model import Limits

    added = replace(crank, limits=Limits(source="test", additional_bending=10e6))
    res2 = run_assessment(added, _cycle(bending, torque, fillets, my), fillets, SCFSet.from_dict(scf), "m53-criterion")
    for j, f in enumerate(fillets):
        w = f.diameter / (math.pi * (f.diameter**4 - f.bore**4))
        sa = scf[f"{f.kind}_bending"] * 0.5 * np.ptp(32 * w * bending[1, j])
        ta = scf[f.kind] * 0.5 * np.ptp(16 * w * torque[1, j])
        r = crank.fillets.pin if f.kind == "pin" else crank.fillets.journal
        dw = m53_fatigue_strength(mat.tensile_strength, f.diameter, r, mat.process, f"{f.kind}-fillet")
        assert res2.safety[1, j] == pytest.approx(dw / math.sqrt((sa + 10e6) ** 2 + 3 * ta**2), rel=1e-9)
    np.testing.assert_array_equal(res2.safety[:, 2:], res.safety[:, 2:])
    for name, ax in (("haigh", res.haigh()), ("safety", res.plot())):  # the report's pictures show something
        ax.figure.savefig(tmp_path / f"{name}.png")
        assert_picture(tmp_path / f"{name}.png")


@pytest.mark.fe
def test_centrifugal_mean_load_is_balanced_by_the_bearings():
    """The crank's own centrifugal load at Ω (order 0, ``CondensedCrank.centrifugal``) on a single
    throw, unbalanced: the bearing reactions' sum equals minus Ω² times the first moment of mass
    about the axis, Σ mᵢ (yᵢ, zᵢ) over the full mesh's nodal masses (statics; the reduction keeps
    rigid translations exactly): within 1e-6 of the largest."""
    from fetorsion.fe.condensed import run_condensed
    from fetorsion.fe.cranksystem import build_system
    from fetorsion.response.cycle import static_solution
    from fetorsion.webs.throwfe import throw_of

    throw = throw_of(plain("renault21.toml"), 0)
    sys_ = build_system(throw, 0.015)
    cc = run_condensed(throw, system=sys_)
    omega = 6000 * 2 * math.pi / 60
    F = omega**2 * cc.centrifugal
    z = static_solution(cc, F)
    K = cc.reduced.K.copy()
    m = cc.n_master_dofs
    K[:m, :m] += cc.support_terms("bearings")[0]
    reaction = K @ z - F  # nonzero only where the supports hold
    # ∫ρ (y, z) dV of the FE mass itself: 1ᵀ m y with the consistent scalar mass (exact for the P2 field y)
    first = np.array([np.sum(sys_.node_mass_matrix @ sys_.xyz[:, k]) for k in (1, 2)])
    total = np.array([sum(reaction[cc.dof(lb, d)] for lb in cc.labels) for d in ("ty", "tz")])
    np.testing.assert_allclose(total, -omega**2 * first, rtol=1e-6, atol=1e-6 * omega**2 * np.abs(first).max())
    assert np.abs(first).max() > 0  # the throw is unbalanced: the check is not 0 = 0
