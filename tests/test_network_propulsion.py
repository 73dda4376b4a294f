"""A network file's propulsion components (``[[chain.propellers]]``, ``[[chain.couplings]]``, the
shaft sections of ``[[chain.shafts]]``): what the network takes from them, by hand, and every
field refused with its name."""

from __future__ import annotations

import copy
import math

import pytest

from fetorsion.description.network import parse_network
from fetorsion.errors import DescriptionError

LINE = {
    "chain": {
        "name": "a propulsion line",
        "stations": [{"name": "engine", "inertia_kgm2": 400.0}, {"name": "gear", "inertia_kgm2": 50.0},
                     {"name": "propeller", "inertia_kgm2": 2000.0}],
        # a RATO-type sheet (the numbers), its temperatures illustrative
        "couplings": [{"between": ["engine", "gear"], "stiffness_nm_per_rad": 262.5e3, "relative_damping": 1.13,
                       "temperature_c": 20.0, "warm_stiffness_nm_per_rad": 183.75e3, "warm_relative_damping": 0.79,
                       "warm_temperature_c": 80.0, "operating_temperature_c": 65.0, "permissible_power_w": 620.0,
                       "ambient_c": 50.0, "permissible_vibratory_torque_nm": 4000.0}],
        "shafts": [{"between": ["gear", "propeller"], "stiffness_nm_per_rad": 5.0e6, "diameter_m": 0.25,
                    "bore_m": 0.1, "tensile_strength_pa": 600e6, "feature": "keyway_tapered"}],
        "propellers": [{"station": "propeller", "blades": 4, "entrained_water_share": 0.25, "rated_torque_nm": 100e3,
                        "rated_speed_rpm": 200.0, "damping_speed_rpm": 150.0, "blade_order_shares": [0.05, 0.01]}],
    }
}


def test_the_network_takes_the_propeller_coupling_and_section_by_hand():
    net = parse_network(copy.deepcopy(LINE))
    # propeller: 2000 · 1.25 = 2500 kg m²; c = 2 Q/ω at 150 rpm, Q = 100e3 · (150/200)² = 56 250 N m
    assert net.inertias[2] == pytest.approx(2500.0, rel=1e-15)
    assert net.absolute_damping[2] == pytest.approx(2 * 56250.0 / (150 * math.pi / 30), rel=1e-12)  # 7161.97
    orders, torques = net.propellers[0].excitation(200 * math.pi / 30)
    assert orders == (4, 8) and torques == pytest.approx((5000.0, 1000.0), rel=1e-12)
    # coupling at 65 °C, 3/4 of the way from 20 to 80 °C: C = 262.5e3 − 0.75 · 78.75e3 = 203 437.5 N m/rad,
    # ψ = 1.13 − 0.75 · 0.34 = 0.875, η = 0.875/2π
    coupling = next(s for s in net.shafts if (s.i, s.j) == (0, 1))
    assert coupling.stiffness == pytest.approx(203437.5, rel=1e-12)
    assert coupling.loss_factor == pytest.approx(0.875 / (2 * math.pi), rel=1e-12)
    assert net.couplings[0].permissible_power == 620.0 and net.couplings[0].permissible_torque == 4000.0
    # the section: τ = 16 T d/(π (d⁴ − d_i⁴)) = 16 · 1000 · 0.25/(π · (0.25⁴ − 0.1⁴)) for 1 kN m
    section = next(s for s in net.shafts if s.section is not None).section
    assert section.ck == 0.6
    assert section.stress(1000.0) == pytest.approx(16 * 1000 * 0.25 / (math.pi * (0.25**4 - 0.1**4)), rel=1e-12)
    assert net.has_dampers


def _broken(path: tuple, value) -> dict:
    data = copy.deepcopy(LINE)
    table = data["chain"][path[0]][0]
    if value is None:
        del table[path[1]]
    else:
        table[path[1]] = value
    return data


@pytest.mark.parametrize("path, value, field", [
    (("propellers", "station"), "engine room", "chain.propellers.1.station"),
    (("propellers", "blades"), 1, "chain.propellers.1.blades"),
    (("propellers", "entrained_water_share"), None, "chain.propellers.1.entrained_water_share"),
    (("propellers", "damping_model"), "frahm", "chain.propellers.1.damping_model"),
    (("propellers", "rated_torque_nm"), -1.0, "chain.propellers.1.rated_torque_nm"),
    (("propellers", "damping_speed_rpm"), 0.0, "chain.propellers.1.damping_speed_rpm"),
    (("propellers", "blade_order_shares"), [-0.1], "chain.propellers.1.blade_order_shares"),
    (("couplings", "relative_damping"), -0.5, "chain.couplings.1.relative_damping"),
    (("couplings", "warm_temperature_c"), 10.0, "chain.couplings.1.warm_temperature_c"),
    (("couplings", "warm_relative_damping"), None, "chain.couplings.1.warm_relative_damping"),
    (("couplings", "permissible_power_w"), None, "chain.couplings.1.ambient_c"),
    (("couplings", "stiffnes_nm_per_rad"), 1.0, "chain.couplings.1.stiffnes_nm_per_rad"),
    (("shafts", "feature"), "spline", "chain.shafts.1.feature"),
    (("shafts", "bore_m"), 0.3, "chain.shafts.1.bore_m"),
    (("shafts", "diameter_m"), 0.0, "chain.shafts.1.diameter_m"),
    (("shafts", "tensile_strength_pa"), None, "chain.shafts.1.tensile_strength_pa"),
    (("shafts", "material"), "bronze", "chain.shafts.1.material"),
])
def test_every_field_is_refused_by_its_name(path, value, field):
    with pytest.raises(DescriptionError) as exc:
        parse_network(_broken(path, value))
    assert field in str(exc.value)
