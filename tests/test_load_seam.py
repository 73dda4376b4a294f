"""The one load seam (fetorsion/excitation/loads.py, issue 53): every consumer reads the cylinders'
loads through CylinderLoads, with the numbers the one-cylinder functions gave before, and a load
written there once (here a made-up per-cylinder scale) reaches the forced response, Campbell, the
time domain's torque table, the load cycle and M53 alike. No FE: lumped chains, and a stand-in for
the condensed crank that carries only what its pin-load map reads (as tests/test_vee.py)."""

from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import fetorsion
from fetorsion.excitation.loads import CylinderLoads, cylinder_loads
from fetorsion.excitation.torque import cycle_angle, cylinder_pin_forces, cylinder_torque, firing_angles, harmonics

GEOMETRY = Path(__file__).resolve().parents[1] / "geometry"
DOF = ("tx", "ty", "tz", "rx", "ry", "rz")


def load(name):
    return fetorsion.load(GEOMETRY / f"{name}.toml")


def stand_in(crank):
    """What pin_load_map, master_loads and mean_master_loads read of a condensed crank."""
    labels = ["front"] + [x for t in range(crank.throws) for x in (f"J{t + 1}", f"P{t + 1}")] + \
        [f"J{crank.throws + 1}", "rear"]
    return SimpleNamespace(crank=crank, n_master_dofs=6 * len(labels), labels=labels,
                           dof=lambda label, name: 6 * labels.index(label) + DOF.index(name))


def close(a, b, rel=1e-12):
    """Equal to ``rel`` of the larger array's largest entry (sums over cylinders round differently)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    assert np.abs(a - b).max() <= rel * max(np.abs(a).max(), np.abs(b).max(), 1e-300)


@pytest.mark.parametrize("name", ["renault21", "v8_petrol"])
def test_the_forced_response_and_campbell_keep_the_one_cylinder_numbers(name):
    """response_setup's forces (and a misfire's) and Campbell's order torques and severities against
    cylinder 1's harmonics with the firing phases, as they were computed before the seam."""
    from fetorsion.excitation.campbell import lumped_modes, run_campbell
    from fetorsion.response.forced import misfire_harmonics, response_setup

    crank = load(name)
    rpm = np.linspace(*crank.excitation.checked_range, 5)
    setup = response_setup(crank, rpm=rpm)
    period, phi = cycle_angle(crank.engine), firing_angles(crank.engine)
    one = np.array([harmonics(cylinder_torque(crank, n).total, period).at(setup.orders) for n in rpm])
    phasors = np.exp(-1j * setup.orders[:, None] * phi[None, :])
    W = setup.load_map[:, 0, :]
    close(setup.forces, one[:, :, None] * (phasors @ W)[None])
    motored = np.array([harmonics(cylinder_torque(crank, n, misfire=True).total, period).at(setup.orders) for n in rpm])
    assert np.array_equal(misfire_harmonics(crank, setup)[:, :, 2, 0], motored)
    close(response_setup(crank, rpm=rpm, misfire=2).forces,
          setup.forces + (motored - one)[:, :, None] * phasors[None, :, 2, None] * W[2])
    res = run_campbell(crank, n_modes=3)
    modes = lumped_modes(crank)
    for c in res.crossings:
        t = harmonics(cylinder_torque(crank, c.rpm).total, period).at([c.order])[0]
        assert c.torque_harmonic_nm == pytest.approx(abs(t), rel=1e-14)  # np.abs and abs round apart
        a = modes.pin_amplitudes[c.mode - 1]
        S = abs(a @ np.exp(-1j * c.order * phi))
        theta = abs(modes.pulley_amplitude[c.mode - 1]) * abs(t) * S / (
            2 * res.damping_ratio * (2 * np.pi * c.frequency_hz) ** 2 * modes.modal_inertia[c.mode - 1])
        assert np.degrees(theta) == pytest.approx(c.severity, rel=1e-12, abs=1e-12 * max(x.severity for x in res.crossings))


@pytest.mark.parametrize("name", ["renault21", "v8_petrol", "v6_split_pin"])
def test_tables_pin_loads_and_throws_keep_the_one_cylinder_numbers(name):
    """The time domain's torque table (every cylinder's row), the condensed crank's master loads
    and load-cycle mean (on the map alone) and each throw's rods, against cylinder 1's functions."""
    from fetorsion.excitation.cylinders import throw_rods
    from fetorsion.response.cycle import mean_master_loads
    from fetorsion.response.pin_loads import master_loads, pin_load_map
    from fetorsion.response.transient_load import torque_table

    crank = load(name)
    grid, step, table = torque_table(crank, 1000.0, 1100.0, part="gas", misfire=1)
    theta = np.arange(table.shape[-1]) * step
    for c in range(crank.engine.cylinders):
        one = np.array([cylinder_torque(crank, r, theta, misfire=c == 1).gas for r in grid])
        assert np.array_equal(table[c], one - one.mean(axis=1, keepdims=True))
    cc, rpm, orders = stand_in(crank), np.array([1500.0, 4000.0]), np.arange(1, 13) * 0.5
    period, phi = cycle_angle(crank.engine), firing_angles(crank.engine)
    forces = [cylinder_pin_forces(crank, n) for n in rpm]
    h = np.array([[harmonics(f[k], period).at(orders) for k in ("tangential", "radial")] for f in forces])
    close(master_loads(cc, rpm, orders),
          np.einsum("sko,oc,ckd->sod", h, np.exp(-1j * np.outer(orders, phi)), pin_load_map(cc)))
    mean = np.array([[f["tangential"].mean(), f["radial"].mean()] for f in forces])
    close(mean_master_loads(cc, rpm), np.einsum("sk,ckd->sd", mean, pin_load_map(cc)))
    loads = cylinder_loads(crank)
    for t in range(crank.throws):
        old, new = throw_rods(crank, forces[1], t), loads.rods_of_throw(rpm[1], t)
        for k in ("cylinders", "radial", "tangential", "phase", "offset"):
            assert np.array_equal(old[k], new[k]), k


SCALED, FACTOR = 2, 1.5  # the made-up load: cylinder 3 (0-based 2) pushes 1.5 times as hard


def scaled_cylinder(monkeypatch):
    """Add a load kind at the seam, and there only: cylinder SCALED's torque and rod force (fired
    and motored) times FACTOR."""
    torque, pins = CylinderLoads.cylinder_torque, CylinderLoads.cylinder_pin_forces

    def cylinder_torque_(self, cylinder, rpm, theta=None, misfire=False):
        t = torque(self, cylinder, rpm, theta, misfire)
        if cylinder != SCALED:
            return t
        return replace(t, **{k: FACTOR * getattr(t, k) for k in ("total", "gas", "inertia")})

    def cylinder_pin_forces_(self, cylinder, rpm, misfire=False):
        f = pins(self, cylinder, rpm, misfire)
        return f if cylinder != SCALED else {**f, "tangential": FACTOR * f["tangential"], "radial": FACTOR * f["radial"]}

    monkeypatch.setattr(CylinderLoads, "cylinder_torque", cylinder_torque_)
    monkeypatch.setattr(CylinderLoads, "cylinder_pin_forces", cylinder_pin_forces_)
    # the harmonic tables kept by the engine's and excitation's content were made by the seam
    # as it was; a new load kind is new code, which a process would not have kept them from
    from collections import OrderedDict

    import fetorsion.excitation.loads as seam

    monkeypatch.setattr(seam, "_TABLES", OrderedDict())


def consumers(crank):
    """What each consumer makes of the cylinders' loads on the Renault (lumped, shipped SCFs)."""
    from fetorsion.design.crank_verdict import fillet_torque_amplitude, verdict_scfs
    from fetorsion.design.m53 import run_m53_crank
    from fetorsion.design.stress import fillets_of
    from fetorsion.excitation.campbell import run_campbell
    from fetorsion.response.cycle import mean_master_loads
    from fetorsion.response.forced import response_setup, solve_response
    from fetorsion.response.pin_loads import pin_load_map
    from fetorsion.response.transient_load import torque_table

    setup = response_setup(crank, rpm=np.linspace(*crank.excitation.checked_range, 6))
    fillets = fillets_of(crank)
    m53 = run_m53_crank(crank, fillets, fillet_torque_amplitude(setup, solve_response(setup, ()), fillets), setup.rpm,
                        fe_scf=verdict_scfs(crank))
    cc = stand_in(crank)
    return {"setup": setup, "campbell": run_campbell(crank, n_modes=2), "table": torque_table(crank, 1000.0, 1100.0)[2],
            "cycle": mean_master_loads(cc, [3000.0]), "map": pin_load_map(cc), "m53": m53,
            "rods": cylinder_loads(crank).rods_of_throw(m53.rated_rpm, crank.engine.throw_of_cylinder(SCALED))}


def test_a_load_added_at_the_seam_reaches_every_consumer(monkeypatch):
    """The issue's failure: a load added in one consumer and missing in the others. Added once at
    the seam, it is in every one, each in its own way: the forced response's forces gain exactly
    that cylinder's share, Campbell's largest order torque grows by the factor, the time domain's
    table has that cylinder's row scaled and the others kept, the load cycle's mean gains that
    cylinder's share, and M53 makes that cylinder's throw a variant of its own with the larger
    bending."""
    crank = load("renault21")
    base = consumers(crank)
    scaled_cylinder(monkeypatch)
    new = consumers(crank)
    s = base["setup"]
    share = (FACTOR - 1) * s.cylinder_harmonics[:, :, SCALED, 0, None] * s.phasors[None, :, SCALED, None] * \
        s.load_map[SCALED, 0][None, None]
    close(new["setup"].forces, s.forces + share)
    assert new["setup"].cylinder_harmonics[:, :, SCALED] == pytest.approx(FACTOR * s.cylinder_harmonics[:, :, SCALED])
    for a, b in zip(base["campbell"].crossings, new["campbell"].crossings):
        assert b.torque_harmonic_nm == pytest.approx(FACTOR * a.torque_harmonic_nm, rel=1e-12)
    assert any(abs(b.severity - a.severity) > 1e-6 * a.severity
               for a, b in zip(base["campbell"].crossings, new["campbell"].crossings))
    others = [c for c in range(crank.engine.cylinders) if c != SCALED]
    assert np.array_equal(new["table"][others], base["table"][others])
    close(new["table"][SCALED], FACTOR * base["table"][SCALED])
    from fetorsion.excitation.torque import cylinder_pin_forces as one

    f = one(crank, 3000.0)
    mean = np.array([f["tangential"].mean(), f["radial"].mean()])
    close(new["cycle"], base["cycle"] + (FACTOR - 1) * np.einsum("k,kd->d", mean, base["map"][SCALED])[None])
    rod = list(base["rods"]["cylinders"]).index(SCALED)
    close(new["rods"]["radial"][rod], FACTOR * base["rods"]["radial"][rod])
    throw = crank.engine.throw_of_cylinder(SCALED) + 1
    assert len(base["m53"].nominal) == 1 and f"throw {throw}" in new["m53"].nominal
    bending = {a.name: a.bending for a in new["m53"].locations}
    own = [v for k, v in bending.items() if k.startswith(f"throw {throw}:")]
    rest = [v for k, v in bending.items() if not k.startswith(f"throw {throw}:")]
    assert max(own) > max(rest)
