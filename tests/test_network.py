"""Geared and branched networks in chain files (issue 29): reading, the gear constraint, the
referred (one-speed) form, modes against printed and closed-form values, and the forced
response of a network against its referred chain."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

import fetorsion
from conftest import ROOT
from fetorsion.description.chain import parse_chain
from fetorsion.description.network import parse_network
from fetorsion.description.chain_model import Chain, GearPair, Network, Shaft
from fetorsion.errors import DescriptionError
from fetorsion.lumped_model.network import gear_constraint, network_matrices, referred, speed_factors
from fetorsion.response.forced import run_response

NETWORKS = ROOT / "examples" / "networks"


def test_chain_files_still_read_as_chains():
    chain = fetorsion.load(ROOT / "examples" / "mendes2008" / "mwm6_chain.toml")
    assert isinstance(chain, Chain) and len(chain.inertias) == 9


def test_friswell_example_9_6_3_to_its_printed_digits():
    # Printed 10.304, 20.479, 24.423 Hz (Friswell et al. 2010 ex. 9.6.3 as openTorsion's tests
    # transcribe it, examples/networks/friswell_9_6_3.toml): rounded to the printed 3 decimals.
    res = fetorsion.lumped(fetorsion.load(NETWORKS / "friswell_9_6_3.toml"))
    assert np.round(res.frequencies_hz, 3).tolist() == [10.304, 20.479, 24.423]
    assert abs(res.rigid_body_hz) < 1e-3


def test_gunter_chen_marine_propulsion_line_to_its_printed_digits():
    # Issue 57's published propulsion line: Gunter & Chen 2001 example 8.1 as openTorsion's
    # example transcribes it (examples/networks/gunter_chen_8_1_marine_turbine.toml): a propeller, a
    # bull gear and two turbine branches of two reductions each, its pinions of no inertia of their
    # own; printed 177.7, 220.2 and 1282.6 cycles per minute, to the printed digit (the file's
    # 7-digit SI values move them by about 1e-7).
    net = fetorsion.load(NETWORKS / "gunter_chen_8_1_marine_turbine.toml")
    res = fetorsion.lumped(net)
    assert np.round(60 * res.frequencies_hz[:3], 1).tolist() == [177.7, 220.2, 1282.6]
    assert abs(res.rigid_body_hz) < 1e-3 and len(res.frequencies_hz) == 5  # 10 stations, 4 meshes: 6 masters


def test_a_station_without_inertia_needs_a_gear_mate_with_some():
    # A pinion whose inertia its mate carries is a station of inertia 0; a group of gears with no
    # inertia at all has no mass to move and is refused, naming its stations.
    def without(text, *names):
        for name in names:
            text = text.replace(f'name = "{name}"\ninertia_kgm2 = 1.0', f'name = "{name}"\ninertia_kgm2 = 0.0')
        return text

    geared = NET + '[[chain.gears]]\nbetween = ["b", "c"]\nratio = 3.0\n'  # a -k- b =gear= c
    assert len(fetorsion.lumped(read(without(geared, "c"))).frequencies_hz) == 1  # b and c: one coordinate
    with pytest.raises(DescriptionError, match=r"'b'.*'c'.*no inertia"):
        read(without(geared, "b", "c"))
    with pytest.raises(DescriptionError, match=r"'a'.*no inertia"):
        read(without(geared, "a"))




def test_friswell_gear_branch_example_to_its_printed_digits():
    # openTorsion's "friswell_pagex" (Friswell et al. 2010, ch. 9): a motor, a 1:1 gear pair whose
    # driving gear also carries a branch, two rotors; printed 425.4, 634.1, 3247.2 Hz.
    Im, Ir, Ig, km, kR = 400e-6, 700e-6, 25e-6, 1.0e4, 5.0e3
    net = Network("pagex", ("motor", "gear 1", "gear 2", "rotor A", "rotor B"), (Im, Ig, Ig, Ir, Ir),
                  (Shaft(0, 1, km), Shaft(2, 3, kR), Shaft(1, 4, kR)), (GearPair(1, 2, 1.0),))
    assert np.round(fetorsion.lumped(net).frequencies_hz, 1).tolist() == [425.4, 634.1, 3247.2]


def test_two_inertias_through_a_gear_closed_form():
    # J1 —k— J2 =gear n= J3: the gear group's inertia is J2 + n² J3 at J2's angle, so the one
    # elastic root is ω² = k (1/J1 + 1/(J2 + n² J3)) (derived here, a 2-DOF chain).
    J1, J2, J3, k, n = 2.0, 0.1, 0.5, 1.0e5, 3.0
    net = Network("two", ("a", "b", "c"), (J1, J2, J3), (Shaft(0, 1, k),), (GearPair(1, 2, n),))
    f = fetorsion.lumped(net).frequencies_hz
    expected = math.sqrt(k * (1 / J1 + 1 / (J2 + n**2 * J3))) / (2 * math.pi)
    assert f.shape == (1,) and f[0] == pytest.approx(expected, rel=1e-12)


def test_ground_springs_closed_form():
    # One disc on a ground spring: ω² = k/J; a geared disc on it: ω² = k/(J1 + n² J2).
    one = Network("g", ("a", "b"), (0.5, 0.2), (Shaft(0, -1, 2.0e4),), (GearPair(0, 1, 2.0),))
    res = fetorsion.lumped(one)
    assert np.isnan(res.rigid_body_hz)
    assert res.frequencies_hz[0] == pytest.approx(math.sqrt(2.0e4 / (0.5 + 4 * 0.2)) / (2 * math.pi), rel=1e-12)


def line_network(n=0.4):
    """Engine-side chain, a gear pair, a driven chain: one line, so its referred form is a chain."""
    return Network("line", ("p", "c1", "fw", "pinion", "wheel", "load"), (0.01, 0.02, 0.3, 0.004, 0.08, 1.2),
                   (Shaft(0, 1, 4e5, 0.0, 0.03), Shaft(1, 2, 5e5, 0.0, 0.03), Shaft(2, 3, 4e3, 0.0, 0.1),
                    Shaft(4, 5, 6e4, 0.0, 0.03)), (GearPair(3, 4, n),))


def test_branch_equals_its_chain_referred_to_one_speed():
    n = 0.4
    net = line_network(n)
    # referred by hand: pinion + wheel merged (J_p + n² J_w), the load J n², the propeller shaft k n²
    chain = Chain("ref", (0.01, 0.02, 0.3, 0.004 + n**2 * 0.08, n**2 * 1.2), (4e5, 5e5, 4e3, n**2 * 6e4),
                  ("p", "c1", "fw", "gears", "load"))
    a, b = fetorsion.lumped(net).frequencies_hz, fetorsion.lumped(chain).frequencies_hz
    assert np.max(np.abs(a / b - 1)) < 1e-9
    # the constraint form TᵀKT and the referred network are the same matrices (angles scaled by f)
    mats, ref = network_matrices(net), network_matrices(referred(net))
    f = speed_factors(net)[mats.masters]
    S = np.diag(f)  # q = S q'
    assert np.allclose(S @ mats.K @ S, ref.K, rtol=1e-12, atol=1e-9 * np.abs(ref.K).max())
    assert np.allclose(S @ mats.M @ S, ref.M, rtol=1e-12, atol=0)


def test_branched_network_equals_its_referred_network():
    net = fetorsion.load(NETWORKS / "geared_engine.toml")
    a = fetorsion.lumped(net).frequencies_hz
    b = fetorsion.lumped(referred(net)).frequencies_hz
    assert np.max(np.abs(a / b - 1)) < 1e-9


def test_gear_constraint_rows_are_speed_factors():
    T, masters = gear_constraint(4, [GearPair(0, 1, 2.0), GearPair(1, 2, 0.5)])
    assert masters.tolist() == [0, 3]
    assert T[:, 0].tolist() == [1.0, 2.0, 1.0, 0.0] and T[:, 1].tolist() == [0, 0, 0, 1.0]


def test_network_response_equals_its_referred_chain():
    # The forced response of the geared line (constraint form, physical angles) and of the chain
    # referred to the engine's speed: a referred shaft carries f × the physical torque, f = n on
    # the driven side; the whole solve agrees to round-off (1e-9).
    n = 0.4
    engine = fetorsion.load(NETWORKS / "geared_engine.toml")
    net = line_network(n)
    from dataclasses import replace

    net = replace(net, cylinder_stations=(1, 1, 1, 1), engine=engine.engine, excitation=engine.excitation)
    chain = Chain("ref", (0.01, 0.02, 0.3, 0.004 + n**2 * 0.08, n**2 * 1.2), (4e5, 5e5, 4e3, n**2 * 6e4),
                  ("p", "c1", "fw", "gears", "load"), loss_factors=(0.03, 0.03, 0.1, 0.03), cylinder_stations=(1, 1, 1, 1),
                  engine=engine.engine, excitation=engine.excitation)
    rpm = np.linspace(900, 4000, 40)
    a, b = run_response(net, rpm=rpm), run_response(chain, rpm=rpm)
    scale = np.array([1, 1, 1, n])  # referred torque / physical torque
    assert np.max(np.abs(a.section_torque_peak_nm * scale / b.section_torque_peak_nm - 1)) < 1e-9
    assert np.max(np.abs(a.pulley_angle_deg / b.pulley_angle_deg - 1)) < 1e-9


def test_network_campbell_and_response_run():
    net = fetorsion.load(NETWORKS / "geared_engine.toml")
    from fetorsion.excitation.campbell import run_campbell

    res = run_campbell(net)
    assert res.crossings and all(c.rpm > 0 for c in res.crossings)
    r = run_response(net, rpm=[1000.0, 2000.0])
    assert r.section_torque_nm.shape == (2, len(net.shafts))
    assert r.to_dict()["sections"][-1] == "pump gear-pump"


@pytest.mark.parametrize("at", ["front", "wheel"])
def test_campbell_of_a_network_with_a_damper_is_the_network_with_its_ring(at, tmp_path):
    """The Campbell diagram's modes of a geared line with a rubber damper (on the crank's pulley, or
    on the wheel at 1/3.5 of the engine's speed) equal the network's own modes, by its assembler
    (validated against the published networks above), with the damper written as what it is
    undamped: its hub added to the station, its ring a station on a shaft of the damper's
    stiffness (1e-9). They once came from a serial chain of the network's springs in list order
    with no gear referral (the medium line's 56.1 Hz mode read 31.6 Hz)."""
    from fetorsion.excitation.campbell import run_campbell
    from fetorsion.lumped_model.lumped import lumped

    text = (NETWORKS / "propulsion_line_medium_speed.toml").read_text(encoding="utf-8")
    start = text.index("[[dampers]]")
    end = text.index("\n[", start + 1)
    rubber = (f'[[dampers]]\ntype = "rubber"\nat = "{at}"\nhub_inertia_kgm2 = 2.0\nring_inertia_kgm2 = 30.0\n'
              "stiffness_nm_per_rad = 2.0e6\nloss_factor = 0.2\n")
    damped = tmp_path / "damped.toml"
    damped.write_text(text[:start] + rubber + text[end:], encoding="utf-8")
    station = "pulley" if at == "front" else "wheel"
    inertia = {"pulley": "4.469", "wheel": "740.2"}[station]
    plain_text = text[:start] + text[end:]
    head = f'name = "{station}"\ninertia_kgm2 = {inertia}'
    assert head in plain_text
    plain_text = plain_text.replace(head, f'name = "{station}"\ninertia_kgm2 = {float(inertia) + 2.0!r}', 1)
    plain_text += (f'\n[[chain.stations]]\nname = "ring"\ninertia_kgm2 = 30.0\n'
                   f'[[chain.shafts]]\nbetween = ["{station}", "ring"]\nstiffness_nm_per_rad = 2.0e6\n')
    plain = tmp_path / "plain.toml"
    plain.write_text(plain_text, encoding="utf-8")
    got = run_campbell(fetorsion.load(damped)).frequencies_hz
    want = lumped(fetorsion.load(plain)).frequencies_hz[:len(got)]
    assert got == pytest.approx(want, rel=1e-9)


NET = """
[chain]
name = "n"
[[chain.stations]]
name = "a"
inertia_kgm2 = 1.0
[[chain.stations]]
name = "b"
inertia_kgm2 = 1.0
[[chain.stations]]
name = "c"
inertia_kgm2 = 1.0
[[chain.shafts]]
between = ["a", "b"]
stiffness_nm_per_rad = 1.0e4
"""


def read(text: str):
    import tomllib

    return parse_network(tomllib.loads(text))


@pytest.mark.parametrize("extra, field, rule", [
    ("", "chain.stations", "not joined"),
    ('[[chain.gears]]\nbetween = ["b", "x"]\nratio = 2.0\n', "chain.gears.1.between", "two different stations"),
    ('[[chain.gears]]\nbetween = ["b", "c"]\nratio = -2.0\n', "chain.gears.1.ratio", "> 0"),
    ('[[chain.gears]]\nbetween = ["b", "c"]\nratio = 2.0\n[[chain.gears]]\nbetween = ["c", "b"]\nratio = 0.5\n',
     "chain.gears", "loop"),
    ('[[chain.gears]]\nbetween = ["b", "ground"]\nratio = 2.0\n', "chain.gears.1.between", "two different"),
])
def test_bad_network_is_refused_by_field(extra, field, rule):
    with pytest.raises(DescriptionError) as err:
        read(NET + extra)
    assert any(p.field == field and rule in p.rule for p in err.value.problems), err.value.problems


def test_network_ground_shaft_reads():
    net = read(NET + '[[chain.shafts]]\nbetween = ["ground", "c"]\nstiffness_nm_per_rad = 1.0e3\n'
               '[[chain.gears]]\nbetween = ["b", "c"]\nratio = 2.0\n')
    assert net.shafts[-1] == Shaft(2, -1, 1.0e3)
    assert network_matrices(net).grounded


def test_chain_lists_are_refused_in_a_network():
    with pytest.raises(DescriptionError) as err:
        read(NET.replace('name = "n"', 'name = "n"\ninertias_kgm2 = [1.0, 2.0]'))
    assert any(p.field == "chain.inertias_kgm2" for p in err.value.problems)


def test_parse_chain_unchanged_for_list_form():
    import tomllib

    c = parse_chain(tomllib.loads('[chain]\ninertias_kgm2 = [0.1, 0.2]\nstiffnesses_nm_per_rad = [1e4]\n'))
    assert isinstance(c, Chain) and c.stiffnesses == (1e4,)


def test_a_locked_loop_of_shafts_and_gears_is_named():
    """a -shaft- b =gear 0.8= c -shaft- d -shaft- a: round the loop the speed ratio is 0.8, so the
    loop cannot turn as one (before: "the free network has no rigid-body root", naming neither the
    file nor the loop). With a ratio of 1 the same loop reads and turns freely (a rigid root)."""
    loop = NET.replace('[[chain.shafts]]\nbetween = ["a", "b"]', '[[chain.stations]]\nname = "d"\ninertia_kgm2 = 1.0\n'
                       '[[chain.shafts]]\nbetween = ["a", "b"]') + (
        '[[chain.gears]]\nbetween = ["b", "c"]\nratio = {r}\n[[chain.shafts]]\nbetween = ["c", "d"]\n'
        'stiffness_nm_per_rad = 1.0e4\n[[chain.shafts]]\nbetween = ["d", "a"]\nstiffness_nm_per_rad = 1.0e4\n')
    with pytest.raises(DescriptionError) as err:
        read(loop.format(r=0.8))
    (p,) = err.value.problems
    assert p.field == "chain" and sorted(p.value) == ["a", "b", "c", "d"] and "multiply to 0.8, not 1" in p.rule
    res = fetorsion.lumped(read(loop.format(r=1.0)))
    assert abs(res.rigid_body_hz) < 1e-3 and len(res.frequencies_hz) == 2  # 4 stations, one gear


def test_one_station_on_a_ground_spring_is_a_network():
    """One disc on a ground shaft, ω² = k/J (before: refused, "needs at least 2 stations"); one
    free disc alone has no elastic mode and is refused saying so."""
    one = ('[chain]\nname = "one"\n[[chain.stations]]\nname = "a"\ninertia_kgm2 = 0.5\n'
           '[[chain.shafts]]\nbetween = ["a", "ground"]\nstiffness_nm_per_rad = 2.0e4\n')
    f = fetorsion.lumped(read(one)).frequencies_hz
    assert f.shape == (1,) and f[0] == pytest.approx(math.sqrt(2.0e4 / 0.5) / (2 * math.pi), rel=1e-12)
    free = one.replace('"ground"', '"a"')
    with pytest.raises(DescriptionError):
        read(free)


TUNED = ('\n[[dampers]]\ntype = "tuned"\nat = "front"\nring_inertia_kgm2 = 0.004\nstiffness_nm_per_rad = 2.0e4\n'
         'damping_nms_per_rad = 3.0\n')


def test_a_network_reads_dampers_as_their_rings_on_shafts():
    """[[dampers]] in a network: a tuned damper at the front (the first station) gives the response
    of the same network with the ring written out as a station on a shaft of the damper's stiffness
    and damping (the same equations: 1e-9 on every common section and the pulley angle); and the time
    domain's steady peaks of the damped network equal its order synthesis within 1 % (as for a chain)."""
    from dataclasses import replace

    from fetorsion.response.transient import run_transient

    import tomllib

    text = (NETWORKS / "geared_engine.toml").read_text()
    damped = parse_network(tomllib.loads(text + TUNED), str(NETWORKS / "geared_engine.toml"))
    ring = text.replace("[[chain.shafts]]", '[[chain.stations]]\nname = "ring"\ninertia_kgm2 = 0.004\n\n'
                        '[[chain.shafts]]\nbetween = ["pulley", "ring"]\nstiffness_nm_per_rad = 2.0e4\n'
                        'damping_nms_per_rad = 3.0\n\n[[chain.shafts]]', 1)
    written = parse_network(tomllib.loads(ring), str(NETWORKS / "geared_engine.toml"))
    assert len(damped.dampers) == 1 and damped.dampers[0].at == "front"
    rpm = np.linspace(1000.0, 4000.0, 31)
    a, b = run_response(damped, rpm=rpm), run_response(written, rpm=rpm)
    np.testing.assert_allclose(a.pulley_angle_deg, b.pulley_angle_deg, rtol=1e-9)
    common = [s for s in a.section_labels if s in b.section_labels]
    assert len(common) == len(a.section_labels) >= 8
    for s in common:
        np.testing.assert_allclose(a.section_torque_nm[:, a.section_labels.index(s)],
                                   b.section_torque_nm[:, b.section_labels.index(s)], rtol=1e-9, atol=1e-9)



@pytest.mark.slow
def test_a_damped_networks_time_domain_equals_its_order_synthesis():
    """The network of the previous test with its tuned damper, loss factors off (both domains then
    solve the same viscous equations): the time domain's steady peaks equal the synthesis of
    orders 0.5-24 within 1 %, as for a chain (30 s: the ring's light damping settles slowly)."""
    import tomllib
    from dataclasses import replace

    from fetorsion.response.transient import run_transient

    text = (NETWORKS / "geared_engine.toml").read_text()
    damped = parse_network(tomllib.loads(text + TUNED), str(NETWORKS / "geared_engine.toml"))
    viscous = replace(damped, shafts=tuple(replace(s, loss_factor=0.0) for s in damped.shafts))
    tr = run_transient(viscous, rpm=2000.0)
    fr = run_response(viscous, rpm=[2000.0], orders=np.arange(1, 49) * 0.5)
    assert np.abs(tr.steady_peak_nm()[:len(fr.section_labels)] / fr.section_torque_peak_nm[0] - 1).max() < 0.01


def test_a_network_damper_on_a_named_station_is_its_ring_on_that_station():
    """`at` may name any station: a tuned damper at "flywheel" equals its ring written out on a
    shaft from the flywheel (1e-9); one on the propeller (geared to 0.4 of the engine's speed) is
    its ring referred to the coordinate by f² and equals its ring written out on a shaft from the
    propeller (1e-9), its heat too; a station that no table names is refused by name."""
    import tomllib

    from fetorsion.errors import FetorsionError

    text = (NETWORKS / "geared_engine.toml").read_text()
    src = str(NETWORKS / "geared_engine.toml")
    damped = parse_network(tomllib.loads(text + TUNED.replace('at = "front"', 'at = "flywheel"')), src)
    ring = text.replace("[[chain.shafts]]", '[[chain.stations]]\nname = "ring"\ninertia_kgm2 = 0.004\n\n'
                        '[[chain.shafts]]\nbetween = ["flywheel", "ring"]\nstiffness_nm_per_rad = 2.0e4\n'
                        'damping_nms_per_rad = 3.0\n\n[[chain.shafts]]', 1)
    written = parse_network(tomllib.loads(ring), src)
    rpm = np.linspace(1000.0, 4000.0, 31)
    a, b = run_response(damped, rpm=rpm), run_response(written, rpm=rpm)
    np.testing.assert_allclose(a.pulley_angle_deg, b.pulley_angle_deg, rtol=1e-9)
    for s in a.section_labels:
        np.testing.assert_allclose(a.section_torque_nm[:, a.section_labels.index(s)],
                                   b.section_torque_nm[:, b.section_labels.index(s)], rtol=1e-9, atol=1e-9)
    geared = parse_network(tomllib.loads(text + TUNED.replace('at = "front"', 'at = "propeller"')), src)
    ring = text.replace("[[chain.shafts]]", '[[chain.stations]]\nname = "ring"\ninertia_kgm2 = 0.004\n\n'
                        '[[chain.shafts]]\nbetween = ["propeller", "ring"]\nstiffness_nm_per_rad = 2.0e4\n'
                        'damping_nms_per_rad = 3.0\n\n[[chain.shafts]]', 1)
    written = parse_network(tomllib.loads(ring), src)
    a, b = run_response(geared, rpm=rpm), run_response(written, rpm=rpm)
    np.testing.assert_allclose(a.pulley_angle_deg, b.pulley_angle_deg, rtol=1e-9)
    for s in a.section_labels:
        np.testing.assert_allclose(a.section_torque_nm[:, a.section_labels.index(s)],
                                   b.section_torque_nm[:, b.section_labels.index(s)], rtol=1e-9, atol=1e-9)
    # its heat: the written-out ring's dashpot, ½ ω² c |θ_propeller − θ_ring|² over the orders, in the
    # stations' own angles (θ = T q)
    from fetorsion.lumped_model.network import network_matrices

    T = network_matrices(written).T
    station = b.theta @ T.T  # (speeds, orders, stations)
    p, r = written.labels.index("propeller"), written.labels.index("ring")
    om = b.orders[None, :] * rpm[:, None] * np.pi / 30
    heat = 0.5 * om**2 * 3.0 * np.abs(station[..., p] - station[..., r]) ** 2
    np.testing.assert_allclose(a.damper_power_w[:, 0, :], heat, rtol=1e-9, atol=1e-12 * heat.max())
    # and the time domain takes the referred ring as well: a run-up's block peaks, same to 1e-9
    from fetorsion.response.transient import run_transient

    ta, tb = (run_transient(m, run=(1500.0, 2500.0), rate_rpm_per_s=500.0) for m in (geared, written))
    for s in ta.section_labels:
        np.testing.assert_allclose(ta.block_peak_nm[:, ta.section_labels.index(s)],
                                   tb.block_peak_nm[:, tb.section_labels.index(s)], rtol=1e-9)
    with pytest.raises(DescriptionError) as err:
        parse_network(tomllib.loads(text + TUNED.replace('at = "front"', 'at = "nowhere"')), src)
    assert any(p.field == "dampers.1.at" for p in err.value.problems)
