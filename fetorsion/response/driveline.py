"""The condensed FE crank as a part of a network: the driveline's forced response on the engine
model of ``fetorsion run``.

A network whose ``[[chain.cranks]]`` says ``dof = "condensed"`` is solved with the crank as its
condensed model in its bearings (:func:`fetorsion.response.coupled.condensed_setup`: masters with
six DOF, interior modes, bearings, attachments, the pins' slider-crank forces, the Coriolis term of
the rotating frame) and the rest of the network as its stations, shafts and gears
(:mod:`fetorsion.lumped_model.network`). The two meet at the crank's ends: the network's
``<crank>.pulley`` is the front master's θx, ``<crank>.flywheel`` the rear master's; the crank's
other lumped stations take no part (nothing may join them). In the coordinates
z = (the crank's free reduced DOF, the network's other coordinates after its gear constraint),
with S (stations × z) the stations' angles (T of the gear constraint, its crank-end columns
pointing at the two masters' θx):

    M = M_crank ⊕ 0 + Sᵀ J S,   K = K_crank ⊕ 0 + Sᵀ (K_s + i H_s) S,   C = C_ζ + C_bearings + Sᵀ C_s S,

J the stations' inertias (the crank's own zero: its inertia is the FE crank's), K_s, H_s, C_s
the shafts' stiffness, loss factors and dampers. The modal damping ratio ζ is set on the modes of
the whole assembly (as the lumped network's response sets it on its whole network), so a network
of the crank alone has exactly the crank's own damping and response.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..description.model import CRANK_END_ALIASES
from ..description.chain_model import Network
from ..description.network import joined_inside, speed_walk
from ..errors import FetorsionError
from ..fe.condensed import CondensedCrank
from ..lumped_model.network import gear_constraint, group_place, spring_matrix
from ..modes import modal_damping


def condensed_part(net: Network):
    """The network's crank part that is condensed, or None."""
    return next((c for c in net.cranks if c.condensed), None)


def _crank_stations(net: Network, part) -> tuple[int, int, range]:
    """(front station, rear station, every station of the crank part) of ``part`` in ``net``."""
    inside = range(part.first, part.first + len(part.labels))
    return inside[0], inside[-1], inside


#: A mode of the driveline is the crank's own (a damper on the crank is tuned on it) when at least
#: this share of its strain energy is the crank's: the driveline's modes turn the crank as one body.
CRANK_STRAIN_SHARE = 0.5


def crank_torsional_modes(cc: CondensedCrank, keep, K_crank, lam, Phi_crank) -> np.ndarray:
    """Indices (ascending undamped modes) of the assembly's modes in which the crank itself twists:
    at least :data:`CRANK_STRAIN_SHARE` of the mode's strain energy in the crank and, by the
    journals' kinetic energy, torsional (:meth:`~fetorsion.fe.condensed.CondensedCrank.classify`)."""
    strain = np.einsum("ij,ik,kj->j", Phi_crank, K_crank, Phi_crank)
    elastic = lam > 1e-8 * np.abs(lam).max()  # the free motions (rotation; axial without a thrust bearing) are not
    share = np.where(elastic, strain / np.where(elastic, lam, 1.0), 0.0)
    full = np.zeros((cc.reduced.size, Phi_crank.shape[1]))
    full[keep] = Phi_crank
    _, kinds = cc.classify(full)
    return np.array([j for j, k in enumerate(kinds) if k == "torsional" and share[j] >= CRANK_STRAIN_SHARE], int)


def driveline_setup(net: Network, cc: CondensedCrank, rpm: Sequence[float] | np.ndarray | None = None,
                    orders: Sequence[float] | np.ndarray | None = None, damping_ratio: float | None = None,
                    section_labels: Sequence[str] | None = None):
    """The network with its crank as the condensed FE crank ``cc`` in its bearings, as a
    :class:`~fetorsion.response.forced.ResponseSetup` (module docs).

    Parameters
    ----------
    net : Network
        With one ``[[chain.cranks]]`` of ``dof = "condensed"`` (unresolved: as read).
    cc : CondensedCrank
        That crank condensed (:func:`fetorsion.fe.store.condensed_crank`, the run's: fillet cuts and
        its bearings).
    rpm, orders : array_like, optional
        Speeds, rpm, and orders (the condensed setup's defaults).
    damping_ratio : float, optional
        Modal damping ratio on the whole assembly's modes (default the crank's description's).
    section_labels : list of str, optional
        Names of the crank's cuts (its fillets; default ``cut 1`` …).

    Returns
    -------
    ResponseSetup
        DOF: the crank's free reduced coordinates, then the network's other coordinates; sections:
        the crank's cuts, then the network's shafts (their file order, as the lumped network names them).
    """
    import dataclasses

    from .coupled import assembly_modes, condensed_setup, supported_damping

    part = _checked_part(net, cc)
    base = condensed_setup(cc, "bearings", rpm, orders, damping_ratio, section_labels)
    zeta = base.zeta
    R = len(base.labels)
    front, rear, inside = _crank_stations(net, part)
    n = len(net.labels)
    T, masters = gear_constraint(n, net.gears)
    others = [c for c, m in enumerate(masters) if m not in inside]
    S_cols = np.zeros((masters.size, R + len(others)))  # each reduced network coordinate in z
    for c, m in enumerate(masters):
        if m == front:
            S_cols[c, base.pulley] = 1.0
        elif m == rear:
            S_cols[c, base.flywheel] = 1.0
    S_cols[others, R + np.arange(len(others))] = 1.0
    S = T @ S_cols  # (stations, z)
    J = np.array([0.0 if s in inside else v for s, v in enumerate(net.inertias)])
    Ks, Hs, Cs = _shaft_matrices(net, inside)

    def pad(A):
        out = np.zeros((R + len(others),) * 2, A.dtype)
        out[:R, :R] = A
        return out

    M = pad(base.M) + S.T @ np.diag(J) @ S
    K = pad(base.K) + S.T @ Ks @ S
    # ζ on the modes of the whole assembly (M-orthonormal), then the crank's bearings' dampers and the shafts' own
    lam, Phi = assembly_modes(M, K)
    _, _, C_bearings, keep = supported_damping(cc, "bearings", 0.0, 0.0)
    C = modal_damping(M, Phi, np.sqrt(np.clip(lam, 0.0, None)), zeta) + pad(C_bearings) + S.T @ Cs @ S
    torsional = crank_torsional_modes(cc, keep, base.K, lam, Phi[:R])
    Kc = K + 1j * (S.T @ Hs @ S) if np.any(Hs) else K
    rows, names = _shaft_sections(net)
    section_rows = np.vstack([np.pad(base.section_rows, ((0, 0), (0, len(others)))), rows @ S])
    extra = lambda A: np.pad(A, [(0, 0)] * (A.ndim - 1) + [(0, len(others))])  # noqa: E731
    G = None if base.gyroscopic is None else pad(base.gyroscopic)
    places, scale = _damper_places(net, base, T, S_cols, front, rear, inside)
    return dataclasses.replace(
        base, name=net.name, labels=list(base.labels) + [net.labels[masters[c]] for c in others], M=M, K=Kc, C=C,
        forces=extra(base.forces), load_map=extra(base.load_map), section_rows=section_rows,
        section_labels=list(base.section_labels) + names,
        section_x=None if base.section_x is None else np.concatenate([base.section_x, np.full(len(names), np.nan)]),
        stated="stated dampers of the network" if np.any(Cs) or np.any(Hs) else "",
        torsional_modes=torsional, gyroscopic=G, crank_dofs=R, damper_dof=places, damper_scale=scale or None,
        model=f"network of {n - len(inside) + 2} stations on the {base.model}")


def _checked_part(net: Network, cc: CondensedCrank):
    """The network's condensed crank part, checked against ``cc`` and for joints inside it."""
    part = condensed_part(net)
    if part is None:
        raise FetorsionError(f"{net.source or net.name}: no [[chain.cranks]] with dof = \"condensed\"")
    if part.crank.name != cc.crank.name:
        raise FetorsionError(f"{net.source or net.name}: the condensed crank given is {cc.crank.name!r}, the "
                             f"network's part is {part.crank.name!r}")
    bad = [net.labels[s] for s in joined_inside(part, net.shafts, net.gears, net.nonlinear)]
    if bad:
        raise FetorsionError(f"{net.source or net.name}: {', '.join(bad)}: a condensed crank offers only its "
                             f"{' and '.join(f'{part.name}.{a}' for a in CRANK_END_ALIASES)} to the network")
    return part


def _shaft_matrices(net: Network, inside) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(K_s, H_s, C_s) of the network's linear shafts on its stations, the absolute dampers outside the crank."""
    n = len(net.labels)
    shafts = net.linear_shafts
    i, j = [s.i for s in shafts], [s.j for s in shafts]
    k = np.array([s.stiffness for s in shafts], float)
    Ks = spring_matrix(n, i, j, k)
    Hs = spring_matrix(n, i, j, k * np.array([s.loss_factor for s in shafts]))
    Cs = spring_matrix(n, i, j, [s.damping for s in shafts])
    if net.absolute_damping:
        Cs += np.diag([0.0 if s in inside else c for s, c in enumerate(net.absolute_damping)])
    return Ks, Hs, Cs


def _shaft_sections(net: Network) -> tuple[np.ndarray, list]:
    """(torque per unit station angle (shafts, stations), names) of the network's linear shafts."""
    shafts = net.linear_shafts
    i, j = [s.i for s in shafts], [s.j for s in shafts]
    k = np.array([s.stiffness for s in shafts], float)
    rows = np.zeros((len(shafts), len(net.labels)))
    rows[np.arange(len(shafts)), i] = k
    free = np.flatnonzero(np.array(j, int) >= 0)
    rows[free, np.array(j, int)[free]] = -k[free]
    names = [f"{net.labels[s.i]}-{net.labels[s.j] if s.j >= 0 else 'ground'}" for s in shafts]
    names = names[:len(net.shafts)] + [e.name or m for e, m in zip(net.nonlinear, names[len(net.shafts):])]
    return rows, names


def _damper_places(net: Network, base, T, S_cols, front: int, rear: int, inside) -> tuple[dict, dict]:
    """({at: coordinate in z}, {at: f²}) of the network's [[dampers]]."""
    # front and rear on the crank's masters, a named station on its coordinate in z, referred by
    # f² where it turns f times as fast (as in a lumped network)
    places, scale = dict(base.damper_dof), {}
    n = len(net.labels)
    speed = speed_walk(n, net.linear_shafts, net.gears)[0]
    outer = [s for s in range(n) if s not in inside or s in (front, rear)]
    for d in net.dampers:
        if d.at == "front":
            continue
        # "rear": the last station at the engine's speed, as a lumped network reads it
        s = max(x for x in outer if np.isclose(speed[x], 1.0)) if d.at == "rear" else net.labels.index(d.at)
        col, scale[d.at] = group_place(T, s)
        places[d.at] = int(np.flatnonzero(S_cols[col])[0])
    return places, scale
