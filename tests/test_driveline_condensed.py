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
def condensed_renault(condensed_plain_renault):
    """The Renault 21 (no fillets or drillings) condensed at 30 mm with a cut at every fillet."""
    return condensed_plain_renault[2]


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
    own_setup = condensed_setup(condensed_renault, rpm=RPM)
    np.testing.assert_array_equal(setup.torsional_modes, own_setup.torsional_modes)  # a damper is tuned alike
    a = solve_response(setup)
    b = solve_response(own_setup)
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


@pytest.mark.fe
def test_a_driveline_at_another_damping_ratio_is_built_anew_at_it(condensed_renault, driveline):
    # The fatigue verdict's damping band re-damps the setup (response.coupled.with_damping_ratio): on a
    # driveline, ζ is on the whole assembly's modes and linear in ζ, so the re-damped setup equals one
    # built at that ratio (1e-9 of the largest damping entry).
    from fetorsion.response.coupled import with_damping_ratio

    a = with_damping_ratio(driveline_setup(driveline, condensed_renault, rpm=RPM, damping_ratio=0.02),
                           condensed_renault, "bearings", 0.05)
    b = driveline_setup(driveline, condensed_renault, rpm=RPM, damping_ratio=0.05)
    assert a.zeta == b.zeta == 0.05
    assert np.abs(a.C - b.C).max() < 1e-9 * np.abs(b.C).max()


def test_the_other_commands_ask_for_the_lumped_driveline_by_name(tmp_path, capsys):
    # campbell and transient do not take the condensed crank in a network yet: each says so in one
    # line and names the option that gives the lumped driveline, before any FE work; damper takes no
    # network at all, and says that (issue 56: it sent the user to --source lumped17, which refused).
    from fetorsion.cli.commands import main

    text = (ROOT / "examples" / "networks" / "renault21_driveline.toml").read_text()
    text = text.replace("dof = 17", 'dof = "condensed"').replace("../../geometry/renault21.toml",
                                                                  str(ROOT / "geometry" / "renault21.toml"))
    (tmp_path / "n.toml").write_text(text)
    for command in (["campbell"], ["transient", "--rpm", "2000"]):
        assert main([command[0], str(tmp_path / "n.toml"), *command[1:]]) == 2
        err = capsys.readouterr().err
        assert f"{command[0]}: " in err and "--source lumped17" in err
    assert main(["damper", str(tmp_path / "n.toml")]) == 2
    assert "'damper' does not take a network" in capsys.readouterr().err


@pytest.mark.slow
def test_fetorsion_run_of_a_driveline_on_the_condensed_crank(tmp_path):
    # `fetorsion run` of the Renault 21 driveline with dof = "condensed" (30 mm mesh, without the
    # studies and the time domain): the crank's report, its response, fatigue and verdict computed on
    # the driveline (the model named), and said so. Against the crank alone (its own condensed setup,
    # the same crank, SCFs and fillets): the soft clutch (860 N m/rad against a crank of some 1e5
    # N m/rad) moves the crank's modes by about 0.01 % (546.19 -> 546.25 Hz at 30 mm), so M53's
    # governing safety without a damper within 1 % of the crank alone's.
    from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run, step_measured, step_sensitivity, step_transient
    from fetorsion.design.crank_verdict import run_crank_verdict
    from fetorsion.design.stress import fillet_cuts, fillets_of
    from fetorsion.fe.store import stored_condensed
    from fetorsion.response.coupled import with_film_bearings

    text = (ROOT / "examples" / "networks" / "renault21_driveline.toml").read_text()
    text = text.replace("dof = 17", 'dof = "condensed"').replace("../../geometry/renault21.toml",
                                                                  str(ROOT / "geometry" / "renault21.toml"))
    # a section on the half-shafts makes it a shaft line whose TVC a condensed crank does not run yet: said so
    text = text.replace("stiffness_nm_per_rad = 1.2e4\nloss_factor = 0.05", "stiffness_nm_per_rad = 1.2e4\nloss_factor "
                        '= 0.05\ndiameter_m = 0.025\ntensile_strength_pa = 600e6\nfeature = "integral_flange"')
    (tmp_path / "n.toml").write_text(text)
    steps = tuple(s for s in DEFAULT_STEPS if s[2] not in (step_sensitivity, step_measured, step_transient))
    outcome = run(tmp_path / "n.toml", tmp_path / "rep", steps=steps, options=RunOptions(mesh_size=0.03, html=False))
    report = (tmp_path / "rep" / "report.md").read_text()
    assert outcome.driveline == "Renault 21 crank and driveline" and "In the driveline" in report
    assert "diameter_m" in text and "Not computed: the network's crank is its condensed FE crank" in report
    assert "network of 6 stations on the condensed crank" in outcome.fatigue.model
    crank = outcome.crank
    fillets = fillets_of(crank)
    cc = with_film_bearings(stored_condensed(crank, 0.03, fillet_cuts(crank, fillets)))
    alone = run_crank_verdict(crank, cc, condensed_setup(cc, section_labels=[f.label for f in fillets]), fillets,
                              outcome.fatigue.scf, misfire=False, fe_path=False)
    assert outcome.fatigue.verdict.configs[0].m53.governing.safety == pytest.approx(
        alone.configs[0].m53.governing.safety, rel=0.01)
    # `fetorsion report` reads the run back as the crank's report in its driveline (it took the network
    # for the crank and stopped on it before): report.md byte for byte, the Campbell picture drawn again
    import shutil

    from fetorsion.cli.commands import main

    copy = tmp_path / "copy"
    shutil.copytree(tmp_path / "rep", copy)
    (copy / "campbell.png").unlink()
    assert main(["report", str(copy)]) == 0
    assert (copy / "report.md").read_bytes() == (tmp_path / "rep" / "report.md").read_bytes()
    assert (copy / "campbell.png").read_bytes() == (tmp_path / "rep" / "campbell.png").read_bytes()


@pytest.mark.fe
@pytest.mark.parametrize("station", ["gearbox input", "differential"])
def test_a_network_damper_on_the_condensed_driveline_is_its_ring_written_out(condensed_renault, driveline, station):
    # A tuned damper (ring 0.004 kg m², 2e4 N m/rad, 3 N m s/rad) on a driveline station — the gearbox
    # input at the engine's speed, the differential at 0.1875 of it (its ring referred by f²) —
    # against the same ring written out as a station on a shaft there. The same equations when the
    # modal damping ratio is 0 (it is set on the assembly's modes: a written-out ring's mode would get
    # it, a damper's ring does not), the other damping the shafts' loss factors and the bearings':
    # the damper's solved exactly (Woodbury on the projected solve), the written ring's in the
    # projected basis: section torques within 1e-4 of the largest (the projected solve's truncation).
    from fetorsion.description.model import Damper

    damper = Damper("tuned", at=station, ring_inertia=0.004, stiffness=2.0e4, damping=3.0, name="tuned")
    damped = replace(driveline, dampers=(damper,))
    n = len(driveline.labels)
    written = replace(driveline, labels=driveline.labels + ("ring",), inertias=driveline.inertias + (0.004,),
                      shafts=driveline.shafts + (fetorsion.description.chain_model.Shaft(
                          driveline.labels.index(station), n, 2.0e4, 3.0),),
                      absolute_damping=driveline.absolute_damping + (0.0,) if driveline.absolute_damping else ())
    a = solve_response(driveline_setup(damped, condensed_renault, rpm=RPM, damping_ratio=0.0), damped.dampers)
    b = solve_response(driveline_setup(written, condensed_renault, rpm=RPM, damping_ratio=0.0))
    top = b.section_torque_nm.max()
    k = len(a.section_labels)  # b has the ring's shaft last
    assert b.section_labels[:k] == a.section_labels
    assert np.abs(a.section_torque_nm - b.section_torque_nm[:, :k]).max() < 1e-4 * top
    assert a.damper_power_w.max() > 0


def test_dampers_on_a_condensed_driveline_are_placed_or_refused_by_name(tmp_path):
    # A damper on an inner station of the condensed crank is refused when the file is read; `fetorsion
    # run` takes a network damper at the pulley ("front") only and refuses one elsewhere by name,
    # before any work (no report folder).
    from fetorsion.app.run import run

    text = (ROOT / "examples" / "networks" / "renault21_driveline.toml").read_text()
    text = text.replace("dof = 17", 'dof = "condensed"').replace("../../geometry/renault21.toml",
                                                                  str(ROOT / "geometry" / "renault21.toml"))
    tuned = '\n[[dampers]]\nname = "ring"\ntype = "tuned"\nat = "{}"\nring_inertia_kgm2 = 0.004\n' \
            'stiffness_nm_per_rad = 2.0e4\n'
    (tmp_path / "inner.toml").write_text(text + tuned.format("r21.P2"))
    with pytest.raises(fetorsion.errors.DescriptionError, match=r"dampers.1.at.*inner station"):
        fetorsion.load(tmp_path / "inner.toml")
    (tmp_path / "gear.toml").write_text(text + tuned.format("gearbox input"))
    assert fetorsion.load(tmp_path / "gear.toml").dampers[0].at == "gearbox input"
    with pytest.raises(fetorsion.errors.FetorsionError, match="ring away from the crank's pulley"):
        run(tmp_path / "gear.toml", tmp_path / "rep")
    assert not (tmp_path / "rep").exists()
