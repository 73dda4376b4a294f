"""The condensed crank's pin loads: each cylinder's rod force on its throw's pin as forces on the
masters (:func:`pin_load_map`), their complex amplitudes of each order with the firing phases
(:func:`master_loads`), and the mean load each main journal carries over the cycle
(:func:`journal_mean_loads`, for the oil film's coefficients)."""

from __future__ import annotations

import math

import numpy as np

from ..description.cylinders import pin_master_centre, rod_centre
from ..excitation.loads import cylinder_loads
from ..fe.condensed import CondensedCrank


def pin_load_map(cc: CondensedCrank) -> np.ndarray:
    """(cylinders, 2, 6·masters): master forces of a unit tangential and radial rod force of each
    cylinder on its throw's pin.

    Pin t at angle a_t: radial e_r = (0, cos a, sin a), tangential e_t = (0, −sin a, cos a) (a
    positive tangential force turns the crank in +θx). A big end at ``rod_offset`` d along the
    pin from its master (the pin's mid-length) adds the force's moment d e_x × e at the master.
    On a split pin each rod acts on its own half, at a_c = a_t + s_c, whose axis lies (Δy, Δz)
    off the throw's one master (:func:`~fetorsion.description.cylinders.pin_master_centre`): the
    force's moment about the master is (d, Δy, Δz) × e."""
    crank = cc.crank
    engine = crank.engine
    out = np.zeros((engine.cylinders, 2, cc.n_master_dofs))
    for c in range(engine.cylinders):
        t = engine.throw_of_cylinder(c)
        a, d = engine.pin_angle(c), engine.rod_offset(c)
        pin = f"P{t + 1}"
        dy, dz = rod_centre(engine, c) - pin_master_centre(engine, t, crank.pins[t].split_angle)
        for k, e in enumerate(((0.0, -math.sin(a), math.cos(a)), (0.0, math.cos(a), math.sin(a)))):
            out[c, k, [cc.dof(pin, "ty"), cc.dof(pin, "tz")]] = e[1], e[2]
            if d:  # d e_x × (0, e_y, e_z) = d (0, −e_z, e_y)
                out[c, k, [cc.dof(pin, "ry"), cc.dof(pin, "rz")]] = -d * e[2], d * e[1]
            out[c, k, cc.dof(pin, "rx")] = dy * e[2] - dz * e[1]  # (0, Δy, Δz) × e: 0 on an unsplit pin
    return out


def master_loads(cc: CondensedCrank, rpm: np.ndarray, orders: np.ndarray) -> np.ndarray:
    """Complex master-force amplitudes of each order: (speeds, orders, 6·masters), N; each
    cylinder's forces, over its own cycle, lag it by its firing angle φ_c (order q: the factor
    e^{−i q φ_c}): :class:`fetorsion.excitation.loads.CylinderLoads`."""
    loads = cylinder_loads(cc.crank)
    return np.einsum("sock,oc,ckd->sod", loads.pin_force_harmonics(rpm, orders), loads.phasors(orders),
                     pin_load_map(cc))


def journal_mean_loads(cc: CondensedCrank, rpm: float) -> np.ndarray:
    """Each main journal's mean load over the cycle at ``rpm``, in the bearing shell's (fixed)
    frame: (journals, 2) N, the force the crank puts on the bearing.

    The journals are held radially (and the flywheel master in twist, which takes the mean
    torque; the thrust journal, or the first, axially), and the static reactions to a unit
    tangential and radial force on each pin are solved once on the reduced model (static master
    loads are exact in a Craig–Bampton model). Over the cycle, cylinder c's pin forces are its
    own (:meth:`fetorsion.excitation.loads.CylinderLoads.pin_forces`) delayed by its firing angle φ_c; the reactions in the crank's frame are turned
    into the fixed frame, in which the cylinder reaches its top dead centre at θ = φ_c (pin c,
    at crank-frame angle a_c ≡ φ_c, turned back by θ), and averaged.
    """
    crank = cc.crank
    m = cc.n_master_dofs
    journals = [cc.labels.index(f"J{j + 1}") for j in range(len(crank.journals))]
    axial = 6 * journals[crank.main_bearings.thrust_journal] if crank.main_bearings.axial_stiffness > 0 else 6 * journals[0]
    held = np.array(sorted([6 * k + d for k in journals for d in (1, 2)] + [axial, cc.dof("rear", "rx")]))
    keep = np.setdiff1d(np.arange(cc.reduced.size), held)
    K = cc.reduced.K
    unit = np.zeros((cc.reduced.size, crank.engine.cylinders * 2))
    unit[:m] = pin_load_map(cc).reshape(-1, m).T  # columns: cylinder c tangential, radial
    z = np.zeros_like(unit)
    z[keep] = np.linalg.solve(K[np.ix_(keep, keep)], unit[keep])
    react = K[held] @ z - unit[held]  # (held, cylinders·2): the bearings' forces on the crank
    rows = [[list(held).index(6 * k + d) for d in (1, 2)] for k in journals]
    A = np.stack([react[r] for r in rows])  # (journals, 2 (y, z), cylinders·2)
    loads = cylinder_loads(crank)
    f = loads.pin_forces(rpm)
    theta, period, phi = f["theta"], loads.period, loads.firing
    forces = np.empty((len(theta), crank.engine.cylinders * 2))
    for c in range(crank.engine.cylinders):  # cylinder c's force at θ is its own cycle's at θ − φ_c
        for k, name in enumerate(("tangential", "radial")):
            forces[:, 2 * c + k] = np.interp(theta - phi[c], theta, f[name][c], period=period)
    on_crank = np.einsum("jdk,tk->tjd", A, forces)  # (angles, journals, y z), crank frame
    c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
    fixed = np.stack([c * on_crank[..., 0] + s * on_crank[..., 1], -s * on_crank[..., 0] + c * on_crank[..., 1]], -1)
    return -fixed.mean(axis=0)
