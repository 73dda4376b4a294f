"""A crank description as one part of a network (issue 29, ``[[chain.cranks]]``): the network of
the crank alone against the crank's own lumped model, the crank joined to a driveline against the
same system written out by hand as a plain network, and a geared driveline behind the crank
against its chain referred to one speed (written out by hand, not by :func:`referred`)."""

from __future__ import annotations

import numpy as np
import pytest

import fetorsion
from conftest import GEOMETRY, ROOT
from fetorsion.description.files import load
from fetorsion.description.chain import parse_chain
from fetorsion.description.network import parse_network
from fetorsion.description.model import WEB_METHOD_NAMES, partition_labels
from fetorsion.description.reader import read_toml
from fetorsion.lumped_model.network import resolved
from fetorsion.response.forced import run_response
from fetorsion.webs.methods import WEB_METHODS

RENAULT = GEOMETRY / "renault21.toml"
DRIVELINE = ROOT / "examples" / "networks" / "renault21_driveline.toml"
# Every comparison below is between two assemblies of the same matrices (the crank's partition
# copied into stations, or referred by hand), so only round-off separates them: 1e-9 relative.
EXACT = 1e-9


def crank_network(dof=17, stiffness="carter", extra: dict | None = None) -> dict:
    """A network file (as read) whose crank part is the Renault 21."""
    chain = {"name": "crank network", "cranks": [{"name": "r21", "file": str(RENAULT), "dof": dof,
                                                   "stiffness": stiffness}]}
    chain.update(extra or {})
    return {"chain": chain}


def test_web_method_names_are_the_registry():
    assert tuple(WEB_METHODS) == WEB_METHOD_NAMES


@pytest.mark.parametrize("dof", fetorsion.PARTITIONS)
def test_partition_labels_are_the_lumped_models(dof):
    crank = load(RENAULT)
    assert list(partition_labels(crank.throws, dof)) == fetorsion.lumped(crank, dof).labels


@pytest.mark.parametrize("dof,stiffness", [(17, "carter"), (5, "ker-wilson"), (21, "beam")])
def test_crank_alone_as_a_network_is_the_cranks_lumped_model(dof, stiffness):
    # The network of the crank alone: its frequencies and its forced response (every section's
    # torque) are the crank's own lumped model's. The 5-DOF model splits each pin over two
    # stations: the network's cylinder weights must spread the torque the same way.
    crank = load(RENAULT)
    net = parse_network(crank_network(dof, stiffness), source=str(ROOT / "n.toml"))
    own, ours = fetorsion.lumped(crank, dof, stiffness), fetorsion.lumped(net)
    assert ours.labels == [f"r21.{lb}" for lb in own.labels]
    np.testing.assert_allclose(ours.frequencies_hz, own.frequencies_hz, rtol=EXACT)
    a, b = run_response(crank, dof, web_method=stiffness), run_response(net)
    scale = a.section_torque_nm.max()
    assert np.abs(b.section_torque_nm - a.section_torque_nm).max() < EXACT * scale
    assert np.abs(b.pulley_angle_deg - a.pulley_angle_deg).max() < EXACT * a.pulley_angle_deg.max()


def by_hand(crank, extra_stations, extra_shafts, gears=()):
    """The crank's 17-DOF carter model copied into stations of a plain network file, then the
    driveline; cylinders on the pins' stations (the 17-DOF model holds each pin in one station)."""
    own = fetorsion.lumped(crank, 17, "carter")
    names = [f"r21.{lb}" for lb in own.labels]
    raw = read_toml(RENAULT)
    return {"units": raw["units"], "engine": raw["engine"], "excitation": raw["excitation"], "chain": {
        "name": "by hand", "cylinder_stations": [f"r21.P{c + 1}" for c in range(crank.engine.cylinders)],
        "stations": [{"name": n, "inertia_kgm2": float(J)} for n, J in zip(names, own.inertias_kgm2)] + extra_stations,
        "shafts": [{"between": [a, b], "stiffness_nm_per_rad": float(k)}
                   for a, b, k in zip(names, names[1:], own.stiffnesses_nm_per_rad)] + extra_shafts,
        "gears": list(gears)}}


DRIVE_STATIONS = [{"name": "gearbox", "inertia_kgm2": 0.01}, {"name": "vehicle", "inertia_kgm2": 20.0}]


def drive_shafts(flywheel):
    return [{"between": [flywheel, "gearbox"], "stiffness_nm_per_rad": 900.0, "loss_factor": 0.1},
            {"between": ["gearbox", "vehicle"], "stiffness_nm_per_rad": 3.0e3}]


def test_crank_and_driveline_equal_the_same_network_by_hand():
    crank = load(RENAULT)
    net = parse_network(crank_network(extra={"stations": DRIVE_STATIONS, "shafts": drive_shafts("r21.flywheel")}),
                        source=str(ROOT / "n.toml"))
    hand = parse_network(by_hand(crank, DRIVE_STATIONS, drive_shafts("r21.J5")), source=str(RENAULT))
    a, b = fetorsion.lumped(net), fetorsion.lumped(hand)
    assert a.labels == b.labels
    np.testing.assert_allclose(a.frequencies_hz, b.frequencies_hz, rtol=EXACT)
    ra, rb = run_response(net), run_response(hand)
    assert ra.section_labels == rb.section_labels
    assert np.abs(ra.section_torque_nm - rb.section_torque_nm).max() < EXACT * rb.section_torque_nm.max()
    assert np.abs(ra.section_torque_peak_nm - rb.section_torque_peak_nm).max() < EXACT * rb.section_torque_peak_nm.max()


def test_geared_driveline_behind_the_crank_equals_its_referred_chain():
    # Behind the flywheel: clutch (k1) to a gearbox input J_i, a gear pair of ratio n to the output J_o,
    # a shaft (k2) to the vehicle J_v. Referred to the crank's speed by hand (θ' = θ/n): the gear
    # pair is one station J_i + n² J_o, the shaft k2 n², the vehicle J_v n²; the driven shaft's own
    # torque is its referred torque over n (k2 (θ_o − θ_v) = k2 n² (θ'_o − θ'_v) / n).
    n, Ji, Jo, Jv, k1, k2 = 0.3, 0.004, 0.02, 40.0, 900.0, 1.5e4
    crank = load(RENAULT)
    net = parse_network(crank_network(extra={
        "stations": [{"name": "in", "inertia_kgm2": Ji}, {"name": "out", "inertia_kgm2": Jo},
                     {"name": "vehicle", "inertia_kgm2": Jv}],
        "shafts": [{"between": ["r21.flywheel", "in"], "stiffness_nm_per_rad": k1},
                   {"between": ["out", "vehicle"], "stiffness_nm_per_rad": k2}],
        "gears": [{"between": ["in", "out"], "ratio": n}]}), source=str(ROOT / "n.toml"))
    own = fetorsion.lumped(crank, 17, "carter")
    raw = read_toml(RENAULT)
    chain = parse_chain({"units": raw["units"], "engine": raw["engine"], "excitation": raw["excitation"], "chain": {
        "name": "referred", "inertias_kgm2": own.inertias_kgm2.tolist() + [Ji + n**2 * Jo, n**2 * Jv],
        "stiffnesses_nm_per_rad": own.stiffnesses_nm_per_rad.tolist() + [k1, k2 * n**2],
        "cylinder_stations": [own.labels.index(f"P{c + 1}") + 1 for c in range(crank.engine.cylinders)]}})
    np.testing.assert_allclose(fetorsion.lumped(net).frequencies_hz, fetorsion.lumped(chain).frequencies_hz, rtol=EXACT)
    a, b = run_response(net), run_response(chain)
    expected = b.section_torque_nm.copy()
    expected[:, -1] /= n
    assert np.abs(a.section_torque_nm - expected).max() < EXACT * expected.max()


def test_the_cranks_engine_and_excitation_drive_its_pins():
    net = load(DRIVELINE)
    crank = load(RENAULT)
    assert net.engine == crank.engine and net.excitation == crank.excitation
    assert net.labels[0] == "r21.J1" and net.labels[16] == "r21.J5" and "vehicle" in net.labels
    assert np.isnan(net.inertias[0])  # unresolved: the crank's inertias come from its lumped model
    full = resolved(net)
    assert not full.cranks and np.all(np.isfinite(full.inertias))
    W = np.array(full.cylinder_weights)
    # the 17-DOF model holds each pin in its own station, wholly
    assert W.shape == (4, len(full.labels)) and np.allclose(W.sum(axis=1), 1.0)
    assert [full.labels[i] for i in W.argmax(axis=1)] == ["r21.P1", "r21.P2", "r21.P3", "r21.P4"]


def test_a_chain_files_own_engine_places_the_cylinders():
    raw = read_toml(RENAULT)
    data = crank_network(extra={"cylinder_stations": ["r21.J1"] * 4})
    data.update(units=raw["units"], engine=raw["engine"], excitation=raw["excitation"])
    net = parse_network(data, source=str(ROOT / "n.toml"))
    assert not net.cranks[0].drives and net.cylinder_stations == (0, 0, 0, 0)
    assert resolved(net).cylinder_weights == ()
