"""Vee and opposed engines (issue 53): the description, the firing, the order sums, the rods'
forces on a shared pin, M53's superposition; each against a closed form or a hand calculation."""

import math

import numpy as np
import pytest

from fetorsion.description.crank import parse_crank
from fetorsion.errors import DescriptionError
from fetorsion.excitation.campbell import major_orders, order_sums
from fetorsion.description.cylinders import cylinder_throws, cylinders_per_throw
from fetorsion.excitation.cylinders import throw_rods
from fetorsion.excitation.torque import firing_angles

from conftest import simple_crank_raw

SYNTHETIC = {"reciprocating_mass_kg": 0.6, "rotating_mass_kg": 0.5, "speed_range_rpm": [1000.0, 6000.0],
             "compression_ratio": 10.0, "imep_pa": 10.0e5}


def v8(numbering="alternate", bank=-90.0, firing=(1, 8, 4, 3, 6, 5, 7, 2), **engine):
    """A cross-plane 90° V8 on the simple test crank's four throws. GM's small block: cylinders
    numbered alternately (odd: left bank, from the front), 1-8-4-3-6-5-7-2, the right bank's
    cylinder on a throw reaching TDC 90° before the left's; the throws' TDC lags 0, 270, 90, 180."""
    raw = simple_crank_raw(4)
    raw["engine"].update(cylinders=8, layout="vee", bank_angle_deg=bank, numbering=numbering, rods="side-by-side",
                         rod_spacing=12.0, crank_angles_deg=[0.0, 270.0, 90.0, 180.0], firing_order=list(firing),
                         bore=100.0, **engine)
    return raw


def problems_of(raw):
    with pytest.raises(DescriptionError) as info:
        parse_crank(raw, source="v.toml")
    return str(info.value)


@pytest.mark.parametrize("numbering, bank, firing", [
    ("alternate", -90.0, (1, 8, 4, 3, 6, 5, 7, 2)),  # GM small block
    ("by-bank", 90.0, (1, 5, 4, 2, 6, 3, 7, 8)),      # Ford 5.0 (1-4 right bank, 5-8 left)
])
def test_cross_plane_v8_fires_evenly_and_its_orders_sum_as_the_textbook_says(numbering, bank, firing):
    """Two published V8 firing orders on the same cross-plane crank fire every 90°; on a rigid
    crank the orders 4, 8, 12 add fully (|Σ e^{−iqφ}| = 8 = z) and 0.5 … 3.5 cancel: the vector
    sum of eight unit phasors 90°·k apart (turn5-leads: multiples of z/2 for an even-firing z)."""
    crank = parse_crank(v8(numbering, bank, firing))
    assert crank.throws == 4 and crank.engine.cylinders == 8
    assert list(cylinders_per_throw(crank.engine)) == [2, 2, 2, 2]
    phi = np.sort(np.degrees(firing_angles(crank.engine)))
    assert phi == pytest.approx(np.arange(8) * 90.0)
    orders = np.arange(1, 25) * 0.5
    sums = order_sums(crank.engine, np.ones(8), orders)[0]
    textbook = np.abs(np.exp(-1j * orders[:, None] * np.radians(np.arange(8) * 90.0)).sum(axis=1)) / 8
    assert sums == pytest.approx(textbook, abs=1e-12)
    for q in (4.0, 8.0, 12.0):
        assert sums[orders == q][0] == pytest.approx(1.0, abs=1e-12)
    for q in (0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5):
        assert sums[orders == q][0] == pytest.approx(0.0, abs=1e-12)
    assert list(major_orders(crank.engine)) == [4.0, 8.0, 12.0]


def test_numbering_puts_each_cylinder_on_its_throw_and_bank():
    alt = parse_crank(v8("alternate")).engine
    assert list(cylinder_throws(alt)) == [0, 0, 1, 1, 2, 2, 3, 3]
    assert [round(math.degrees(b)) for b in alt.bank_angles] == [0, -90, 0, -90, 0, -90, 0, -90]
    assert list(alt.rod_offsets) == pytest.approx([-0.006, 0.006] * 4)  # first bank's rod in front
    ford = parse_crank(v8("by-bank", 90.0, (1, 5, 4, 2, 6, 3, 7, 8))).engine
    assert list(cylinder_throws(ford)) == [0, 1, 2, 3, 0, 1, 2, 3]


def test_flat_four_boxer_fires_every_180_degrees():
    """An opposed four (Subaru EJ layout: throws 0/180/180/0, cylinders alternating between the two
    banks along the crank, 1-3-2-4): cylinder 2 shares cylinder 1's throw angle, 180° across."""
    raw = simple_crank_raw(4)
    raw["engine"].update(layout="opposed", crank_angles_deg=[0.0, 180.0, 180.0, 0.0], firing_order=[1, 3, 2, 4])
    engine = parse_crank(raw).engine
    assert np.degrees(firing_angles(engine)) == pytest.approx([0.0, 360.0, 180.0, 540.0])
    assert list(major_orders(engine)) == [2.0, 4.0, 6.0, 8.0, 10.0, 12.0]


@pytest.mark.parametrize("change, field, words", [
    (dict(rods="articulated"), "engine.knuckle_radius", "required"),  # master and articulated: its knuckle
    (dict(cylinders=7, firing_order=[1, 2, 3, 4, 5, 6, 7]), "engine.cylinders", "must be even"),
    (dict(crank_angles_deg=[0.0, 90.0, 180.0, 270.0, 0.0, 90.0, 180.0, 270.0]), "engine.crank_angles_deg",
     "one angle per throw"),
    (dict(rod_spacing=30.0), "engine.rod_spacing", "must sit on the pin"),
    (dict(bank_angle_deg=0.0), "engine.bank_angle_deg", "in-line"),
    (dict(firing_order=[1, 2, 3, 4, 5, 6, 7, 8]), "engine.firing_order", "cannot be fired"),
])
def test_bad_vee_fields_are_refused_by_name(change, field, words):
    raw = v8()
    raw["engine"].update(change)
    message = problems_of(raw)
    assert field in message and words in message, message


def test_vee_fields_on_an_in_line_engine_are_refused():
    raw = simple_crank_raw(4)
    raw["engine"]["bank_angle_deg"] = 60.0
    assert "belongs to layout" in problems_of(raw)


def test_two_rods_on_a_pin_against_the_vector_slider_crank():
    """Each rod's radial and tangential force on a shared pin (throw frame), from the reader's
    phases, against an independent vector model: the pin turned by the engine angle, each
    cylinder's axis at its bank's angle, the rod a two-force member from piston to pin carrying the
    piston force; the cylinder's pressure phase from its firing angle. Equal to round-off."""
    from fetorsion.excitation.torque import cylinder_pin_forces, cylinder_pressure, cycle_angle
    from fetorsion.excitation.kinematics import piston_acceleration

    raw = v8()
    raw["excitation"] = SYNTHETIC
    crank = parse_crank(raw)
    e, ex = crank.engine, crank.excitation
    rpm = 4000.0
    one = cylinder_pin_forces(crank, rpm)
    theta = one["theta"]
    R, l, omega = e.crank_radius, e.rod_length, rpm * 2 * math.pi / 60
    _, p = cylinder_pressure(crank, rpm)
    piston = math.pi / 4 * e.bore**2 * (p - ex.intake_pressure) + ex.reciprocating_mass * piston_acceleration(
        theta, R, l, omega)  # cylinder 1's piston force over its cycle, towards the crank
    period = cycle_angle(e)
    phi = firing_angles(e)
    for throw in range(e.throws):
        rods = throw_rods(crank, one, throw)
        engine_angle = theta + phi[rods["cylinders"][0]]
        for r, c in enumerate(rods["cylinders"]):
            g = -e.crank_angles[throw]  # the pin's place, against the lag convention
            axis = (e.bank_angles[c] if e.bank_angles else 0.0)  # the cylinder's axis
            local = engine_angle + g - axis + e.crank_angles[0]  # crank angle from this cylinder's TDC
            force = np.interp(engine_angle - phi[c], theta, piston, period=period)
            pin = R * np.stack([np.cos(local), np.sin(local)])
            x_piston = R * np.cos(local) + np.sqrt(l**2 - (R * np.sin(local)) ** 2)
            u = (np.stack([x_piston, np.zeros_like(local)]) - pin) / l  # unit vector pin → piston
            f_pin = -(force / u[0]) * u  # the rod pushes the pin away from the piston
            radial = (f_pin * np.stack([np.cos(local), np.sin(local)])).sum(0)
            tangential = (f_pin * np.stack([-np.sin(local), np.cos(local)])).sum(0)
            scale = np.abs(force).max()
            assert rods["radial"][r] - ex.rotating_mass * R * omega**2 == pytest.approx(radial, abs=1e-9 * scale)
            assert rods["tangential"][r] == pytest.approx(tangential, abs=1e-9 * scale)


def test_m53_throw_loads_superpose_two_rods_by_hand():
    """Two rod forces on a simply supported throw (spans 0.2 m, pin centre 0.1 m, webs' centres
    0.05 m from each support), at ±10 mm from the pin centre: the reactions and moments by
    statics, by hand: front reaction Σ F (L3 − s)/L3, moment at x = sum of the loads left of x."""
    from fetorsion.design.m53 import ThrowSpans, throw_loads

    spans = ThrowSpans((0.05, 0.05), 0.10, 0.20)
    F = np.array([[1000.0], [-400.0]])  # radial, one angle
    T = np.array([[300.0], [500.0]])
    s = np.array([0.09, 0.11])
    loads = throw_loads(spans, F, T, s - 0.10)
    front = (1000.0 * (0.2 - 0.09) + -400.0 * (0.2 - 0.11)) / 0.2
    rear = (1000.0 * 0.09 + -400.0 * 0.11) / 0.2
    assert loads["Q_RF"][:, 0] == pytest.approx([front, rear])
    assert loads["M_BRF"][:, 0] == pytest.approx([front * 0.05, rear * 0.05])
    # at the pin centre (0.10): the front reaction's moment less the first rod's (0.01 m to its left)
    assert loads["M_BRO"][0] == pytest.approx(front * 0.10 - 1000.0 * 0.01)
    t_front = (300.0 * 0.11 + 500.0 * 0.09) / 0.2
    assert loads["M_BTO"][0] == pytest.approx(t_front * 0.10 - 300.0 * 0.01)
    one = throw_loads(spans, F[0], T[0])  # one rod at mid-pin: the rule's triangle
    assert one["M_BRO"][0] == pytest.approx(1000.0 * 0.5 * 0.10)


@pytest.mark.parametrize("name, interval", [("v8_petrol", 90.0), ("v12_diesel", 60.0), ("flat4_boxer", 180.0),
                                            ("v6_split_pin", 120.0)])
def test_shipped_vee_and_opposed_cranks_fire_evenly(name, interval):
    """The example files fire every 720°/z, and their major orders are the multiples of z/2 up to
    12 (turn5-leads: an even-firing four-stroke of z cylinders)."""
    import fetorsion

    from conftest import GEOMETRY

    crank = fetorsion.load(GEOMETRY / f"{name}.toml")
    z = crank.engine.cylinders
    assert np.sort(np.degrees(firing_angles(crank.engine))) == pytest.approx(np.arange(z) * interval)
    assert list(major_orders(crank.engine)) == list(np.arange(z / 2, 12.0 + 1e-9, z / 2))


def test_each_rod_loads_its_pin_master_with_its_offset_moment():
    """`pin_load_map` on the V8: each cylinder's unit tangential and radial force lands on its throw's
    pin master in the throw's frame, with the moment r × F of its big end's axial offset r = d e_x
    (numpy's cross product); the two rods of a throw, ±d apart, give opposite moments for equal
    forces. A stand-in for the condensed crank carries only what the map reads (the masters' DOF
    numbering, in fetorsion.fe.couplings.DOF_NAMES order tx ty tz rx ry rz)."""
    from types import SimpleNamespace

    from fetorsion.response.coupled import pin_load_map

    crank = parse_crank(v8())
    labels = ["front"] + [x for t in range(4) for x in (f"J{t + 1}", f"P{t + 1}")] + ["J5", "rear"]
    names = ("tx", "ty", "tz", "rx", "ry", "rz")
    cc = SimpleNamespace(crank=crank, n_master_dofs=6 * len(labels),
                         dof=lambda label, name: 6 * labels.index(label) + names.index(name))
    load = pin_load_map(cc)
    e = crank.engine
    assert load.shape == (8, 2, 6 * len(labels))
    for c in range(8):
        t = e.throw_of_cylinder(c)
        a = e.crank_angles[t]
        block = load[c].reshape(2, len(labels), 6)
        k = labels.index(f"P{t + 1}")
        assert np.count_nonzero(np.delete(block, k, axis=1)) == 0  # nothing on another master
        for row, force in zip(block[:, k], ([0.0, -math.sin(a), math.cos(a)], [0.0, math.cos(a), math.sin(a)])):
            assert row[:3] == pytest.approx(force, abs=1e-15)
            assert row[3:] == pytest.approx(np.cross([e.rod_offset(c), 0.0, 0.0], force), abs=1e-15)
    # cylinders 1 and 2 share throw 1 at -6 and +6 mm: equal forces, opposite moments
    assert (load[0] + load[1]).reshape(2, -1, 6)[:, :, 3:] == pytest.approx(0.0, abs=1e-15)
