"""Lumped torsional models of the crank ([Seyedalian]): partitions, matrices, free-free modes.

A partition is a list of stations. Each station owns an axial interval [lo, hi) of the
crank and sits at an anchor point x_a. A station's inertia is the inertia of the metal in
its interval (each part's inertia spread uniformly along the part) plus the end-face
attachments inside it; the spring between two stations is the compliance of the shaft
between their anchors. The five partitions of the paper, for an N-cylinder crank with
N + 1 main journals (the paper's names are the inline-4 sizes):

========  =========  =============================================================
name      inline-4   stations
========  =========  =============================================================
5         N + 1      front end (anchor x = 0: nose, J1, W1, half P1, pulley);
                     journals 2..N (anchor at the journal centre, from mid-pin to
                     mid-pin); rear end (anchor x = L: half P_N, last web, last
                     journal, flange, flywheel). Exactly eq. (18)–(20).
6         N + 2      front end (x = 0: nose and half J1, pulley); one per throw
                     (anchor at the pin centre, from mid-journal to mid-journal);
                     rear end (x = L: half last journal, flange, flywheel).
17        4N + 1     one per journal, web and pin, anchored at its centre; the nose
                     and pulley are lumped into J1, the flange and flywheel into the
                     last journal.
19        4N + 3     as 17, plus a front station (x = 0: nose and pulley) and a rear
                     station (x = L: flange and flywheel).
21        4N + 5     as 19 with the nose and the flange each cut in two halves of
                     equal length: the outer half anchored at the end face (with the
                     pulley or flywheel), the inner half at its own centre.
========  =========  =============================================================
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg

from ..description.cylinders import per_cylinder
from ..description.model import Crank
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from ..modes import TorsionalModes
from ..results import from_fields
from .network import NetworkLayout, NetworkMatrices, network_matrices, network_modes, resolved
from .parts import PartChain, build_parts, partition_matrices, pin_weights
from ..description.defaults import DEFAULT_PARTITION, DEFAULT_WEB_METHOD
from ..description.model import PARTITIONS

if TYPE_CHECKING:
    from collections.abc import Sequence

#: Elastic modes a lumped model's table and mode-shape plot show.
MODES_SHOWN = 4



def chain_matrices(inertias: Sequence[float] | np.ndarray, stiffnesses: Sequence[float] | np.ndarray):
    """Diagonal mass and tridiagonal stiffness matrices of a free-free torsional chain."""
    k = np.asarray(stiffnesses, dtype=float)
    K = np.diag(np.concatenate([k, [0.0]]) + np.concatenate([[0.0], k])) - np.diag(k, 1) - np.diag(k, -1)
    return np.diag(np.asarray(inertias, dtype=float)), K


@dataclass
class LumpedResult:
    """Free-free natural frequencies and mode shapes of a lumped torsional chain.

    Attributes
    ----------
    name : str
        The crank or chain name.
    partition : int or None
        The paper's partition name (5, 6, 17, 19, 21) or None for a chain file.
    labels : list of str
        Station names, front (pulley end) first.
    positions_m : ndarray
        Anchor of each station along the axis from the front end, m (NaN for chains).
    inertias_kgm2, stiffnesses_nm_per_rad : ndarray
        The chain.
    frequencies_hz : ndarray
        Elastic natural frequencies, ascending, Hz.
    mode_shapes : ndarray, shape (modes, stations)
        Row j is the shape of ``frequencies_hz[j]``, 1 at the front station (the
        paper's normalisation) unless that station is a node, then ``max |θ| = 1``.
    rigid_body_hz : float
        The free-free rigid-body root (≈ 0; its size shows the round-off).
    pin_weights : ndarray, shape (cylinders, stations), or None
        Share of each crank pin in each station (None for a chain file): where the
        cylinder torques act.

    Examples
    --------
    >>> import fetorsion
    >>> res = fetorsion.lumped(fetorsion.load("geometry/renault21.toml"), dof=17)
    >>> res.labels[0], len(res.inertias_kgm2), len(res.stiffnesses_nm_per_rad)
    ('J1', 17, 16)
    >>> print(res.table().splitlines()[0])
    Renault 21 (F-type 1.7 L) crank + flywheel + pulley + pistons + rods: 17-DOF (carter webs) free-free torsional modes
    """

    name: str
    partition: int | None
    labels: list[str]
    positions_m: np.ndarray
    inertias_kgm2: np.ndarray
    stiffnesses_nm_per_rad: np.ndarray
    frequencies_hz: np.ndarray
    mode_shapes: np.ndarray
    rigid_body_hz: float
    inputs: dict[str, str] = field(default_factory=dict)
    pin_weights: np.ndarray | None = None
    #: A network's matrices (its labels, inertias and shapes are then in its reduced
    #: coordinates, one per gear group; its stiffnesses are its shafts'); None for a chain or crank.
    network: NetworkMatrices | NetworkLayout | None = None

    def matrices(self):
        """(M, K): the model's mass and stiffness matrices (a chain's tridiagonal, a network's reduced)."""
        if isinstance(self.network, NetworkLayout):
            return self.network.matrices()
        if self.network is not None:
            return self.network.M, self.network.K
        return chain_matrices(self.inertias_kgm2, self.stiffnesses_nm_per_rad)

    @property
    def dof(self) -> int:
        return len(self.inertias_kgm2)

    def to_dict(self) -> dict:
        """Plain JSON-ready dict (lists and floats, SI units in the key names)."""
        return {
            "name": self.name,
            "partition": self.partition,
            "dof": self.dof,
            "labels": list(self.labels),
            "positions_m": [None if np.isnan(x) else float(x) for x in self.positions_m],
            "frequencies_hz": self.frequencies_hz.tolist(),
            "rigid_body_hz": None if np.isnan(self.rigid_body_hz) else float(self.rigid_body_hz),
            "inertias_kgm2": self.inertias_kgm2.tolist(),
            "stiffnesses_nm_per_rad": self.stiffnesses_nm_per_rad.tolist(),
            "mode_shapes": self.mode_shapes.tolist(),
            **self.inputs,
            **({} if self.network is None else {
                "network": self.network.to_dict(),
                "station_mode_shapes": (self.network.station_mode_shapes if isinstance(self.network, NetworkLayout)
                                        else self.mode_shapes @ self.network.T.T).tolist()}),
        }

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "LumpedResult":
        """The result back from its :meth:`to_dict` (a network's with its
        :class:`~.network.NetworkLayout`: its matrices are not kept)."""
        known = {f.name for f in fields(cls)} | {"dof", "station_mode_shapes"}
        inputs = {k: v for k, v in d.items() if k not in known}
        network = NetworkLayout.from_dict(d["network"], d["station_mode_shapes"]) if "network" in d else None
        return from_fields(cls, d, inputs=inputs, network=network)

    def table(self) -> str:
        """Every elastic mode: frequency and the station of largest twist."""
        kind = f"{self.dof}-DOF ({self.inputs.get('stiffness_method')} webs)" if self.partition else "chain"
        support = "free-free"
        if self.network is not None:
            kind = f"network of {len(self.network.labels)} stations ({self.dof} coordinates after the gears)"
            support = "grounded" if self.network.grounded else "free-free"
        lines = [f"{self.name}: {kind} {support} torsional modes", f"{'mode':>4} {'f [Hz]':>10}  largest twist at"]
        lines += [f"{j + 1:>4} {f:10.1f}  {self.labels[int(np.abs(s).argmax())]}"
                  for j, (f, s) in enumerate(zip(self.frequencies_hz, self.mode_shapes))]
        return "\n".join(lines)

    def torsional_modes(self) -> TorsionalModes:
        """The modes in the form the Campbell analysis uses (needs the pin weights of a crank)."""
        if self.pin_weights is None:
            raise FetorsionError(f"{self.name}: the chain file does not say where the cylinders act "
                                 "(give [engine] and chain.cylinder_stations)")
        shapes = self.mode_shapes
        return TorsionalModes(
            source=lumped_modes_source(self),
            frequencies_hz=self.frequencies_hz,
            pin_amplitudes=shapes @ self.pin_weights.T,
            pulley_amplitude=shapes[:, 0],
            modal_inertia=np.einsum("js,s,js->j", shapes, self.inertias_kgm2, shapes),
        )

    def plot(self, modes: int = MODES_SHOWN, ax=None):
        """Mode shapes against station (unit at the pulley end, as in the paper's fig. 13–14).

        Returns the matplotlib Axes.
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4.5))
        x = np.arange(self.dof)
        for j in range(min(modes, len(self.frequencies_hz))):
            ax.plot(x, self.mode_shapes[j], marker="o", label=f"mode {j + 1}: {self.frequencies_hz[j]:.1f} Hz")
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set_xticks(x, self.labels, rotation=60, fontsize=7)
        ax.set_ylabel("relative twist angle")
        title = f"{self.name}: {self.dof}-DOF lumped model" if self.partition else f"{self.name}: chain"
        ax.set_title(title, wrap=True)
        ax.legend(fontsize=8)
        ax.figure.tight_layout()
        return ax


def lumped_modes_source(res: LumpedResult) -> str:
    """How a lumped result's modes are named (Campbell diagram, tables)."""
    if res.network is not None:
        return f"network of {len(res.network.labels)} stations ({res.dof} coordinates after the gears)"
    return (f"lumped {res.dof} DOF ({res.inputs.get('stiffness_method')})" if res.partition
            else f"chain of {res.dof} inertias")


def solve_chain(inertias, stiffnesses):
    """Free-free modes of a chain: (rigid-body Hz, elastic Hz ascending, shapes per row)."""
    M, K = chain_matrices(inertias, stiffnesses)
    # eigh returns eigenvalues ascending with eigenvectors in the same column order.
    lam, vec = scipy.linalg.eigh(K, M)
    if abs(lam[0]) > 1e-8 * abs(lam[-1]):
        raise FetorsionError(f"the free-free chain has no rigid-body root (smallest eigenvalue {lam[0]:.3g})")
    shapes = vec[:, 1:].T
    ref = shapes[:, 0]
    scale = np.where(np.abs(ref) > 1e-6 * np.abs(shapes).max(axis=1), ref,
                     shapes[np.arange(len(shapes)), np.abs(shapes).argmax(axis=1)])
    shapes = shapes / scale[:, None]
    hz = np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi)
    return float(hz[0]), hz[1:], shapes


def lumped(model: Crank | Chain | Network, dof: int = DEFAULT_PARTITION, stiffness: str = DEFAULT_WEB_METHOD,
           parts: PartChain | None = None) -> LumpedResult:
    """Free-free lumped torsional model of a crank (one partition) or of a chain file.

    Parameters
    ----------
    model : Crank or Chain
        From :func:`fetorsion.load`.
    dof : int
        Partition name for a crank, one of 5, 6, 17, 19, 21 (see module docs);
        ignored for a chain.
    stiffness : str
        Web stiffness method, a key of :data:`fetorsion.webs.methods.WEB_METHODS`: ``"carter"``,
        ``"ker-wilson"``, ``"beam"``, ``"fe"`` (static FE of each throw, cached), ``"fe-held"``
        (each throw's stiffness inside the whole crank in rigid bearings) or ``"chart"``.
    parts : PartChain, optional
        ``build_parts(model, stiffness)`` when the caller has it already (every partition of
        one crank and method comes from the same parts).

    Returns
    -------
    LumpedResult

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> res = fetorsion.lumped(crank, dof=17)
    >>> res.dof, bool(res.frequencies_hz[0] > 0)
    (17, True)
    """
    if isinstance(model, Network):
        return network_lumped(model)
    if isinstance(model, Chain):
        rigid, hz, shapes = solve_chain(model.inertias, model.stiffnesses)
        weights = None
        if model.cylinder_stations:
            # One-hot: each cylinder's torque acts wholly on the station the file names for it.
            weights = np.zeros((len(model.cylinder_stations), len(model.inertias)))
            weights[np.arange(len(model.cylinder_stations)), list(model.cylinder_stations)] = 1.0
        return LumpedResult(model.name, None, list(model.labels), np.full(len(model.inertias), np.nan),
                            np.array(model.inertias), np.array(model.stiffnesses), hz, shapes, rigid,
                            {"source": model.source}, weights)
    chain = build_parts(model, stiffness) if parts is None else parts
    inertias, springs, labels, anchors = partition_matrices(chain, dof)
    rigid, hz, shapes = solve_chain(inertias, springs)
    return LumpedResult(model.name, dof, labels, anchors, inertias, springs, hz, shapes, rigid,
                        {"stiffness_method": chain.web_method, "source": model.source},
                        per_cylinder(model.engine, pin_weights(chain, dof)))


def network_lumped(net: Network) -> LumpedResult:
    """Modes of a network (free-free, or grounded when a shaft goes to ground) in its reduced
    coordinates (:mod:`fetorsion.lumped_model.network`); the cylinders' weights are T's rows of
    their stations (a torque on a geared station does f times its work on the group's angle)."""
    net = resolved(net)
    mats = network_matrices(net)
    rigid, hz, shapes = network_modes(mats)
    weights = None
    if net.cylinder_weights:
        weights = np.array(net.cylinder_weights) @ mats.T
    elif net.cylinder_stations:
        weights = mats.T[list(net.cylinder_stations)]
    labels = [net.labels[m] for m in mats.masters]
    return LumpedResult(net.name, None, labels, np.full(len(labels), np.nan), np.diag(mats.M).copy(),
                        np.array([s.stiffness for s in net.linear_shafts]), hz, shapes, rigid, {"source": net.source},
                        weights, mats)


def stated_damping(model: Crank | Chain | Network, res: LumpedResult):
    """(C, H) of the dampers a chain or network file states, in the model's coordinates
    (zeros for a crank): viscous N·m·s/rad and hysteretic N·m/rad."""
    if res.network is not None:
        return res.network.C, res.network.H
    if isinstance(model, Chain):
        return chain_damping(res.dof, res.stiffnesses_nm_per_rad, model.absolute_damping, model.relative_damping,
                             model.loss_factors)
    return np.zeros((res.dof, res.dof)), np.zeros((res.dof, res.dof))


def chain_damping(n: int, stiffnesses: Sequence[float] | np.ndarray, absolute: Sequence[float] | np.ndarray = (),
                  relative: Sequence[float] | np.ndarray = (), loss_factors: Sequence[float] | np.ndarray = ()):
    """Damping matrices of a chain of ``n`` inertias as engineers state it.

    Parameters
    ----------
    n : int
        Number of inertias.
    stiffnesses : array_like
        Spring stiffnesses, N·m/rad (n − 1).
    absolute : array_like, optional
        Viscous dampers to ground, N·m·s/rad, one per inertia.
    relative : array_like, optional
        Viscous dampers across each spring, N·m·s/rad.
    loss_factors : array_like, optional
        Hysteretic loss factor η of each spring (-).

    Returns
    -------
    C : ndarray (n, n)
        Viscous damping matrix, N·m·s/rad.
    H : ndarray (n, n)
        Hysteretic matrix, N·m/rad: the imaginary part of the complex stiffness K + iH,
        H assembled from the springs η_i k_i (independent of frequency).
    """
    C = np.diag(np.zeros(n) if len(absolute) == 0 else np.asarray(absolute, dtype=float))
    if len(relative):
        C = C + chain_matrices(np.zeros(n), relative)[1]
    eta = np.zeros(n - 1) if len(loss_factors) == 0 else np.asarray(loss_factors, dtype=float)
    H = chain_matrices(np.zeros(n), eta * np.asarray(stiffnesses, dtype=float))[1]
    return C, H


def modal_damping_ratios(frequencies_hz: np.ndarray, shapes: np.ndarray, inertias: np.ndarray, C: np.ndarray,
                         H: np.ndarray) -> np.ndarray:
    """Equivalent damping ratio of each mode from stated dampers (modal diagonal, coupling ignored).

    At resonance ω_j the mode dissipates as 2 ζ_j ω_j m_j = φ_jᵀ C φ_j + φ_jᵀ H φ_j / ω_j, so
    ζ_j = (ω_j φᵀCφ + φᵀHφ) / (2 ω_j² m_j), m_j = φᵀ M φ.
    """
    omega = 2 * np.pi * np.asarray(frequencies_hz, dtype=float)
    m = np.einsum("js,s,js->j", shapes, inertias, shapes)
    c = np.einsum("js,st,jt->j", shapes, C, shapes)
    h = np.einsum("js,st,jt->j", shapes, H, shapes)
    return (omega * c + h) / (2 * omega**2 * m)
