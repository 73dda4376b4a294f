"""Geared and branched torsional networks: matrices in the stations' own angles, the gear
constraint that removes the driven gear of every mesh, and the same network referred to one speed.

A network (:class:`~fetorsion.description.chain_model.Network`) has n stations with angles θ (rad,
each in its own shaft's rotation), shafts (springs, optionally to ground) and rigid gear pairs
θ_j = n_g θ_i. Assembled without the gears, M = diag(J), K = Σ k (e_i − e_j)(e_i − e_j)ᵀ, C
likewise (absolute dampers on the diagonal), H = Σ η k (…) the hysteretic part. The gears are
constraints θ = T q: q holds one angle per gear group (the group's first station, its
"master"), and row s of T holds the speed factor f_s of station s relative to its master. Then

    M_r = Tᵀ M T,   K_r = Tᵀ K T,   C_r = Tᵀ C T,   H_r = Tᵀ H T,   F_r = Tᵀ F

(the virtual work of the constraint forces vanishes; the form [OpenTorsion] assembles and
[Friswell] ch. 9 states, the book not read here). M_r stays diagonal
(each station belongs to one group): Σ J_s f_s² per group. Referring every station to the
speed of station 1 instead (θ'_s = θ_s / f_s with f_s its speed over station 1's, J' = J f²,
k' = k f², gear pairs merged) gives the same eigenvalues: :func:`referred` builds that form,
the textbook's "equivalent system"; the tests check the two agree to 1e-9.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg

from ..description.chain_model import Network, Shaft
from ..description.network import speed_walk
from ..errors import FetorsionError
from .parts import build_parts, partition_matrices, pin_weights

if TYPE_CHECKING:
    from collections.abc import Sequence
    from ..description.chain_model import GearPair


def spring_matrix(n: int, i: Sequence[int] | np.ndarray, j: Sequence[int] | np.ndarray,
                  values: Sequence[float] | np.ndarray) -> np.ndarray:
    """Σ v (e_i − e_j)(e_i − e_j)ᵀ over springs i–j (j = -1: to ground), shape (n, n).

    Parameters
    ----------
    n : int
        Stations.
    i, j : array_like of int
        0-based ends of each spring; j = -1 joins i to ground.
    values : array_like
        Stiffness (N·m/rad) or damping (N·m·s/rad) of each spring.
    """
    i, j, v = np.asarray(i, int), np.asarray(j, int), np.asarray(values, float)
    A = np.zeros((n, n))
    np.add.at(A, (i, i), v)
    free = j >= 0
    np.add.at(A, (j[free], j[free]), v[free])
    np.add.at(A, (i[free], j[free]), -v[free])
    np.add.at(A, (j[free], i[free]), -v[free])
    return A


def gear_constraint(n: int, gears: Sequence[GearPair]) -> tuple[np.ndarray, np.ndarray]:
    """The constraint matrix T (n × r) of the gear pairs and the master station of each column.

    Parameters
    ----------
    n : int
        Stations.
    gears : sequence of GearPair
        θ_j = ratio θ_i for each (loops of gears are refused when the file is read).

    Returns
    -------
    T : ndarray (n, r)
        θ = T q; row s holds station s's speed factor against its group's master.
    masters : ndarray (r,) of int
        The station whose angle is column q_k (the group's lowest-numbered station).
    """
    factor = np.ones(n)
    group = np.arange(n)
    links = {s: [] for s in range(n)}
    for g in gears:
        links[g.i].append((g.j, g.ratio))
        links[g.j].append((g.i, 1.0 / g.ratio))
    seen = np.zeros(n, bool)
    for s in range(n):  # breadth-first from the lowest station of each group: it is the master
        if seen[s]:
            continue
        seen[s], queue = True, [s]
        while queue:
            a = queue.pop()
            for b, r in links[a]:
                if not seen[b]:
                    seen[b], factor[b], group[b] = True, factor[a] * r, s
                    queue.append(b)
    masters = np.unique(group)
    T = np.zeros((n, masters.size))
    T[np.arange(n), np.searchsorted(masters, group)] = factor
    return T, masters


def group_place(T: np.ndarray, station: int) -> tuple[int, float]:
    """(the column of ``station``'s gear group in the constraint T of :func:`gear_constraint`, f²):
    f its speed against that column's master, the factor by which a damper on it is referred."""
    col = int(np.flatnonzero(T[station])[0])
    return col, float(T[station, col]) ** 2


@dataclass(frozen=True)
class NetworkMatrices:
    """A network's matrices in the reduced coordinates q (one angle per gear group).

    ``M, K, C, H`` (r × r): inertia kg·m², stiffness N·m/rad, stated viscous damping
    N·m·s/rad, hysteretic part N·m/rad; ``T`` (n × r) maps q to the stations' angles;
    ``masters`` the station of each q; ``section_rows`` (shafts × r) the elastic torque
    k (θ_i − θ_j) of each shaft per unit q (N·m/rad); ``section_labels`` their names;
    ``grounded``: some shaft goes to ground (no rigid-body mode).
    """

    M: np.ndarray
    K: np.ndarray
    C: np.ndarray
    H: np.ndarray
    T: np.ndarray
    masters: np.ndarray
    labels: tuple
    section_rows: np.ndarray
    section_labels: tuple
    grounded: bool

    def to_dict(self) -> dict:
        return {"stations": list(self.labels), "coordinates": [self.labels[m] for m in self.masters],
                "speed_factors": self.T.sum(axis=1).tolist(), "sections": list(self.section_labels),
                "grounded": self.grounded}


@dataclass(frozen=True)
class NetworkLayout:
    """A network's :meth:`NetworkMatrices.to_dict` read back: its stations, the station of each
    coordinate, each station's speed against its coordinate's, its shafts, whether it is grounded,
    and the mode shapes at the stations (``station_mode_shapes``, modes × stations). What a
    report presents of a network; the matrices are not kept (:meth:`matrices` refuses)."""

    labels: tuple
    coordinates: tuple
    speed_factors: np.ndarray
    section_labels: tuple
    grounded: bool
    station_mode_shapes: np.ndarray

    @classmethod
    def from_dict(cls, d: dict, station_mode_shapes) -> "NetworkLayout":
        """The layout of a network's lumped result's ``to_dict()``: its ``network`` entry ``d``
        and its ``station_mode_shapes``."""
        return cls(tuple(d["stations"]), tuple(d["coordinates"]), np.asarray(d["speed_factors"], dtype=float),
                   tuple(d["sections"]), bool(d["grounded"]), np.asarray(station_mode_shapes, dtype=float))

    def to_dict(self) -> dict:
        return {"stations": list(self.labels), "coordinates": list(self.coordinates),
                "speed_factors": self.speed_factors.tolist(), "sections": list(self.section_labels),
                "grounded": self.grounded}

    def matrices(self):
        from ..errors import FetorsionError

        raise FetorsionError("a network's lumped result read back keeps its layout and modes, not its matrices "
                             "(lumped() on the description gives them)")


@functools.lru_cache(maxsize=16)
def resolved(net: Network) -> Network:
    """The network with each of its ``[[chain.cranks]]`` replaced by the crank's lumped model: the
    partition's station inertias (kg·m²) in the crank's stations, the springs between them (N·m/rad)
    as shafts ahead of the file's, and, when the crank's engine drives, its pins' weights on those
    stations (:func:`~fetorsion.lumped_model.parts.pin_weights`, as the crank's own lumped model
    spreads them). A network without cranks is returned as it is; the result has none.

    Parameters
    ----------
    net : Network
        As read (:func:`fetorsion.load`).

    Returns
    -------
    Network
    """
    if not net.cranks:
        return net
    inertias, inside, weights = list(net.inertias), [], net.cylinder_weights
    for c in net.cranks:
        parts = build_parts(c.crank, c.web_method)
        J, k, _, _ = partition_matrices(parts, c.partition)
        inertias[c.first:c.first + len(J)] = J.tolist()
        inside += [Shaft(c.first + s, c.first + s + 1, float(v)) for s, v in enumerate(k)]
        if c.drives:
            from ..description.cylinders import per_cylinder

            W = np.zeros((c.crank.engine.cylinders, len(inertias)))
            W[:, c.first:c.first + len(J)] = per_cylinder(c.crank.engine, pin_weights(parts, c.partition))
            weights = tuple(map(tuple, W.tolist()))
    return replace(net, inertias=tuple(inertias), shafts=tuple(inside) + net.shafts, cranks=(),
                   cylinder_weights=weights)


def network_matrices(net: Network) -> NetworkMatrices:
    """The constraint form of a network (module docs): M_r = TᵀMT, K_r = TᵀKT, … (a crank in it
    resolved to its lumped model first, :func:`resolved`)."""
    net = resolved(net)
    n = len(net.inertias)
    sh = net.linear_shafts  # the nonlinear elements last, at their operating stiffness
    i, j = [s.i for s in sh], [s.j for s in sh]
    k = np.array([s.stiffness for s in sh])
    K = spring_matrix(n, i, j, k)
    C = spring_matrix(n, i, j, [s.damping for s in sh])
    if net.absolute_damping:
        C += np.diag(net.absolute_damping)
    H = spring_matrix(n, i, j, k * np.array([s.loss_factor for s in sh]))
    T, masters = gear_constraint(n, net.gears)
    rows = np.zeros((len(sh), n))
    rows[np.arange(len(sh)), i] = k
    free = np.flatnonzero(np.array(j) >= 0)
    rows[free, np.array(j)[free]] = -k[free]
    names = tuple(f"{net.labels[s.i]}-{net.labels[s.j] if s.j >= 0 else 'ground'}" for s in sh)
    names = names[:len(net.shafts)] + tuple(e.name or n for e, n in zip(net.nonlinear, names[len(net.shafts):]))
    red = lambda A: T.T @ A @ T  # noqa: E731
    return NetworkMatrices(red(np.diag(net.inertias)), red(K), red(C), red(H), T, masters, tuple(net.labels),
                           rows @ T, names, any(s.j < 0 for s in sh))


def speed_factors(net: Network) -> np.ndarray:
    """Each station's speed over station 1's (shafts keep the speed, a gear multiplies it by its ratio)."""
    net = resolved(net)
    return speed_walk(len(net.inertias), net.linear_shafts, net.gears)[0]


def rear_coordinate(net: Network, masters: np.ndarray) -> int:
    """The index among ``masters`` (the coordinates' stations) of the last coordinate that turns at
    the engine's speed (factor 1): a damper's ``rear``, the station the pulley twist is read against."""
    f = speed_factors(net)[masters]
    return int(np.flatnonzero(np.isclose(f, 1.0))[-1])


def referred(net: Network) -> Network:
    """The same network referred to the speed of station 1, with no gears: each station's J f²,
    each shaft's k f² and c f² (f: :func:`speed_factors`), the two stations of a gear pair
    merged into one (labels joined by '+'). Exact for rigid gears; the textbook's equivalent
    system. Its angles are θ_s / f_s. Absolute dampers are referred as the shafts' (c f²)."""
    net = resolved(net)
    f = speed_factors(net)
    T, masters = gear_constraint(len(net.inertias), net.gears)
    col = np.argmax(T != 0, axis=1)  # the merged station of each station
    J = np.zeros(masters.size)
    np.add.at(J, col, np.asarray(net.inertias) * f**2)
    ca = np.zeros(masters.size)
    if net.absolute_damping:
        np.add.at(ca, col, np.asarray(net.absolute_damping) * f**2)
    labels = tuple("+".join(net.labels[s] for s in np.flatnonzero(col == c)) for c in range(masters.size))
    shafts = tuple(Shaft(int(col[s.i]), int(col[s.j]) if s.j >= 0 else -1, s.stiffness * f[s.i] ** 2,
                         s.damping * f[s.i] ** 2, s.loss_factor) for s in net.linear_shafts)
    stations = tuple(int(col[c]) for c in net.cylinder_stations)
    weights = ()
    if net.cylinder_weights:  # a torque T on station s does T f_s of work per unit referred angle θ_s / f_s
        W = np.zeros((len(net.cylinder_weights), masters.size))
        for c, row in enumerate(net.cylinder_weights):
            np.add.at(W[c], col, np.asarray(row) * f)
        weights = tuple(map(tuple, W.tolist()))
    # the same description, its stations referred: gears, dampers, nonlinear elements and parts gone
    return replace(net, name=f"{net.name} (referred to station 1's speed)", labels=labels, inertias=tuple(J.tolist()),
                   shafts=shafts, gears=(), absolute_damping=tuple(ca.tolist()) if net.absolute_damping else (),
                   cylinder_stations=stations, dampers=(), uncertainty=(), distributions=(), nonlinear=(), cranks=(),
                   cylinder_weights=weights)


def network_modes(mats: NetworkMatrices):
    """Natural frequencies and shapes of a network in its reduced coordinates.

    Returns (rigid-body Hz or nan when grounded, elastic Hz ascending, shapes (modes × r), one
    row per elastic mode, 1 at the first coordinate unless it is a node, then max |q| = 1).
    """
    lam, vec = scipy.linalg.eigh(mats.K, mats.M)
    rigid = np.nan
    if not mats.grounded:
        if abs(lam[0]) > 1e-8 * abs(lam[-1]):
            raise FetorsionError(f"the free network has no rigid-body root (smallest eigenvalue {lam[0]:.3g})")
        rigid, lam, vec = float(np.sqrt(abs(lam[0])) / (2 * np.pi)), lam[1:], vec[:, 1:]
    shapes = vec.T
    ref = shapes[:, 0]
    scale = np.where(np.abs(ref) > 1e-6 * np.abs(shapes).max(axis=1), ref,
                     shapes[np.arange(len(shapes)), np.abs(shapes).argmax(axis=1)])
    return rigid, np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi), shapes / scale[:, None]


def network_damper_dof(net: Network, matrices: NetworkMatrices, flywheel: int) -> tuple[dict, dict]:
    """Where a network's dampers act and how they are referred, on its ``matrices``: ({at: coordinate}, {at: f²}).
    ``front`` is the first coordinate, ``rear`` the last one at the engine's speed
    (``flywheel``), a station's name its gear group's coordinate; a station that turns f times
    as fast as that coordinate (row T of the gear constraint) carries the damper referred by f²
    (:func:`fetorsion.lumped_model.damped.referred_damper`)."""
    out, scale = {"front": 0, "rear": flywheel}, {}
    for d in getattr(net, "dampers", ()):
        if d.at in out:
            continue
        out[d.at], scale[d.at] = group_place(matrices.T, list(matrices.labels).index(d.at))
    return out, scale
