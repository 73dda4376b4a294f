"""The condensed FE crank as a part of a network (issue 43): the driveline's forced response on the
engine model of ``fetorsion run``."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg

import fetorsion
from fetorsion.response.coupled import condensed_setup
from fetorsion.response.driveline import driveline_setup
from fetorsion.response.forced import solve_response

from conftest import ROOT, plain

RPM = np.linspace(1000.0, 6000.0, 21)


@pytest.fixture(scope="module")
def condensed_renault():
    """The Renault 21 (no fillets or drillings) condensed at 30 mm with a cut at every fillet."""
    from fetorsion.design.stress import fillet_cuts, fillets_of
    from fetorsion.fe.condensed import run_condensed

    crank = plain("renault21.toml")
    return run_condensed(crank, 0.03, cuts=fillet_cuts(crank, fillets_of(crank)))


@pytest.fixture(scope="module")
def driveline():
    """The Renault 21 driveline example with its crank part as the condensed crank."""
    net = fetorsion.load(ROOT / "examples" / "networks" / "renault21_driveline.toml")
    return replace(net, cranks=tuple(replace(c, condensed=True) for c in net.cranks))


def crank_alone(net):
    """The network without its driveline: the crank part's stations only (the crank with its flywheel)."""
    n = len(net.cranks[0].labels)
    return replace(net, labels=net.labels[:n], inertias=net.inertias[:n], shafts=(), gears=(), nonlinear=(),
                   absolute_damping=net.absolute_damping[:n] if net.absolute_damping else ())


@pytest.mark.fe
def test_the_crank_alone_as_a_network_is_the_condensed_crank(condensed_renault, driveline):
    # The done-when: a network holding only the condensed crank has the crank's own condensed modes
    # (rtol 1e-6: two assemblies of one matrix, round-off apart), and its crank section torques are
    # those of `fetorsion run`'s setup (condensed_setup in the bearings, the same damping on the same
    # modes) within 0.1 %.
    alone = crank_alone(driveline)
    setup = driveline_setup(alone, condensed_renault, rpm=RPM)
    lam = scipy.linalg.eigvalsh(np.real(setup.K), setup.M)
    own = condensed_renault.modes("bearings")
    free = own.free_motions
    elastic = np.sqrt(np.clip(lam[free:free + 12], 0, None)) / (2 * np.pi)
    assert elastic == pytest.approx(own.frequencies_hz[:12], rel=1e-6)
    a = solve_response(setup)
    b = solve_response(condensed_setup(condensed_renault, rpm=RPM))
    assert a.section_labels == b.section_labels
    assert np.abs(a.section_torque_nm / b.section_torque_nm - 1).max() < 1e-3


@pytest.mark.fe
def test_the_renault_driveline_runs_on_the_condensed_crank(condensed_renault, driveline):
    # (1) Below the crank's own modes (546 Hz in its bearings) the crank turns as one body, so the
    # driveline's modes (7.4, 63.0 Hz) are those of the lumped network with the same driveline:
    # within 0.5 % (the crank's inertia from the FE solid and from the lumped parts of one geometry,
    # and the crank's compliance, (63/546)² of a share of the mode's strain energy).
    # (2) The projected solve (modes below 3 ω_max with a static correction, the loss factors of the
    # clutch and half-shafts projected on them, the Coriolis term) against a direct dense solve of the
    # same assembled matrices at every speed and order: section torques within 1e-4 of the largest.
    setup = driveline_setup(driveline, condensed_renault, rpm=RPM)
    lam = scipy.linalg.eigvalsh(np.real(setup.K), setup.M)
    hz = np.sqrt(np.clip(lam, 0, None)) / (2 * np.pi)
    low = hz[(hz > 1.0) & (hz < 200.0)]
    lumped = fetorsion.lumped(fetorsion.load(ROOT / "examples" / "networks" / "renault21_driveline.toml"))
    assert low == pytest.approx(lumped.frequencies_hz[:2], rel=5e-3)
    res = solve_response(setup)
    om = setup.orders[None, :] * setup.rpm[:, None] * np.pi / 30
    spin = setup.rpm[:, None] * np.pi / 30 * np.ones_like(om)
    A = (setup.K[None, None] - om[..., None, None] ** 2 * setup.M + 1j * om[..., None, None] * setup.C
         + 1j * (om * spin)[..., None, None] * setup.gyroscopic)
    theta = np.linalg.solve(A, setup.forces[..., None])[..., 0]
    direct = np.abs(theta @ setup.section_rows.T)  # (speeds, orders, sections)
    projected = np.abs(res.theta @ setup.section_rows.T)
    assert np.abs(projected - direct).max() < 1e-4 * direct.max()
    # the crank's cuts come first, then the network's shafts
    assert res.section_labels[-2:] == ["r21.J5-gearbox input", "differential-vehicle"]


def test_a_condensed_crank_offers_only_its_ends(tmp_path):
    # Its inner lumped stations are not the FE model's masters: a shaft to one is refused by name
    # when the file is read, before any FE work.
    src = (ROOT / "examples" / "networks" / "renault21_driveline.toml").read_text()
    text = src.replace("dof = 17", 'dof = "condensed"').replace("../../geometry/renault21.toml",
                                                                  str(ROOT / "geometry" / "renault21.toml"))
    text += '\n[[chain.shafts]]\nbetween = ["r21.P2", "vehicle"]\nstiffness_nm_per_rad = 1.0e3\n'
    (tmp_path / "n.toml").write_text(text)
    with pytest.raises(fetorsion.errors.DescriptionError, match=r"chain.cranks.1.dof.*r21.P2"):
        fetorsion.load(tmp_path / "n.toml")


@pytest.mark.slow
def test_fetorsion_response_of_the_crank_alone_network_is_the_cranks(tmp_path):
    # End to end on the command line, the run's mesh (10 mm, the store's condensed crank with its
    # fillet cuts and oil films): a network file holding only the Renault 21 as a condensed part
    # answers as `fetorsion response` on the crank description itself: every fillet's torque at
    # every speed within the 0.1 %.
    import json

    from fetorsion.cli.commands import main

    (tmp_path / "n.toml").write_text('[chain]\nname = "Renault 21 alone"\n\n[[chain.cranks]]\nname = "r21"\n'
                                     f'file = "{ROOT / "geometry" / "renault21.toml"}"\ndof = "condensed"\n')
    assert main(["response", str(tmp_path / "n.toml"), "--steps", "12", "--json", str(tmp_path / "a.json")]) == 0
    assert main(["response", str(ROOT / "geometry" / "renault21.toml"), "--steps", "12",
                 "--json", str(tmp_path / "b.json")]) == 0
    a, b = (json.loads((tmp_path / f"{x}.json").read_text()) for x in "ab")
    assert a["sections"] == b["sections"] and "network" in a["model"] and "condensed" in a["model"]
    assert np.abs(np.array(a["section_torque_nm"]) / np.array(b["section_torque_nm"]) - 1).max() < 1e-3
