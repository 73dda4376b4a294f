"""The network's fetorsion crank against IACS UR M53 in the TVC (:mod:`fetorsion.design.tvc_crank`):
a network that is the crank alone judges it exactly as the crank's own lumped model does (the
fillets' torques found by the network's station names against the crank's positions), and a
crank description in a driveline gets its M53 in every configuration, the driveline's torques
moving its Q."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from conftest import ROOT
import fetorsion
from fetorsion.design.m53 import run_m53_crank
from fetorsion.design.stress import fillet_sections, fillets_of
from fetorsion.design.tvc_crank import crank_m53
from fetorsion.response.forced import response_setup, solve_response

CRANK = ROOT / "geometry/renault21.toml"


def network_of(tmp_path, extra: str = "") -> fetorsion.description.chain_model.Network:
    path = tmp_path / "net.toml"
    path.write_text(f'[chain]\nname = "r21 as a network"\n[[chain.cranks]]\nname = "r21"\nfile = "{CRANK}"\n'
                    f'dof = 17\nstiffness = "carter"\n{extra}')
    return fetorsion.load(path)


def test_a_network_that_is_the_crank_alone_judges_it_as_the_crank_does(tmp_path):
    net, crank = network_of(tmp_path), fetorsion.load(CRANK)
    alone = solve_response(response_setup(crank, 17, web_method="carter"))
    fillets = fillets_of(crank)
    own = run_m53_crank(crank, fillets, alone.section_torque_nm[:, fillet_sections(fillets, alone)], alone.rpm)
    (name, got), = crank_m53([SimpleNamespace(network=net, response=solve_response(response_setup(net)),
                                              name="alone")])[0]
    # the same chain, damping and loads solved by the two paths: every place's Q to round-off
    assert [a.safety for a in got.locations] == pytest.approx([a.safety for a in own.locations], rel=1e-12)
    assert got.governing.torque_section == own.governing.torque_section


def test_a_driveline_moves_the_cranks_torques_and_its_m53(tmp_path):
    # the crank joined to a heavy load through a soft spring: its first mode and so its fillet torques move
    net = network_of(tmp_path, '[[chain.stations]]\nname = "load"\ninertia_kgm2 = 2.0\n'
                     '[[chain.shafts]]\nbetween = ["r21.flywheel", "load"]\nstiffness_nm_per_rad = 2000.0\n')
    alone = network_of(tmp_path)
    q = [crank_m53([SimpleNamespace(network=n, response=solve_response(response_setup(n)), name="n")])[0][0][1]
         for n in (alone, net)]
    assert q[0].governing.safety != pytest.approx(q[1].governing.safety, rel=1e-6)
    assert crank_m53([]) == ([], "")


def test_a_crank_that_does_not_drive_the_network_is_not_judged(tmp_path):
    # the network's own [engine] puts the cylinders on stations of its choosing: the crank's rod forces
    # are not what loads it, so its M53 is refused by name rather than mixed
    path = tmp_path / "driven.toml"
    path.write_text(f'[chain]\nname = "r21 driven"\ncylinder_stations = ["r21.P1", "r21.P2", "r21.P3", "r21.P4"]\n'
                    f'[[chain.cranks]]\nname = "r21"\nfile = "{CRANK}"\ndof = 17\nstiffness = "carter"\n'
                    '[units]\nlength = "mm"\n[engine]\ncylinders = 4\ncycle_strokes = 4\nbore = 81.0\nstroke = 83.5\n'
                    'rod_length = 149.1\ncrank_angles_deg = [0.0, 180.0, 180.0, 0.0]\nfiring_order = [1, 3, 4, 2]\n'
                    '[excitation]\nreciprocating_mass_kg = 0.5\nspeed_range_rpm = [1000.0, 5000.0]\nimep_pa = 1.0e6\n'
                    'compression_ratio = 9.0\n')
    net = fetorsion.load(path)
    assert not net.cranks[0].drives
    results, note = crank_m53([SimpleNamespace(network=net, response=solve_response(response_setup(net)), name="n")])
    assert results == [] and "drive it" in note
