"""Gear hammering of a propulsion line: at every gear mesh, the synthesised vibratory torque the mesh
transmits against the mean torque it transmits (docs/propulsion-tvc.md).

A mesh whose vibratory torque amplitude exceeds the mean torque it carries reverses its torque once
a cycle: the teeth leave their flanks and strike the other side (gear hammer, "rattle"). A class TVC
lists the speeds where that can happen.

**The mesh torque.** The network's gears are rigid constraints θ_j = r θ_i (:mod:`fetorsion.lumped_model.
network`); the torque the mesh puts on a station is its constraint torque, the part of the station's
equilibrium no element supplies. For each order of frequency ω, on a station x of the mesh (the
driven gear j where no external load, damper or second mesh sits on it, else the driving gear i),

    Λ_x = −ω² J_x θ_x + iω c_x θ_x − Σ_shafts at x (k (1 + iη) + iω c) (θ_other − θ_x),

J_x and c_x the station's inertia and absolute damping, the shafts with their stated hysteretic and
viscous damping. The modal damping ratio of the response is a matrix on the reduced coordinates,
no station's own: it is not in Λ (it stands for small distributed losses). The orders are
synthesised as the response's are (:func:`fetorsion.response.synthesis.grouped_extremes`), and the
vibratory torque is the half-range amplitude.

**The mean torque.** The propeller law Q_p(ω_p) of each propeller on the load side of the mesh (the
side that does not hold station 1, the engine's), referred to station x by the power it absorbs,
lossless: T_mean,x = Σ_p Q_p(f_p Ω) f_p / f_x, f the stations' speeds over station 1's.

Hammering is possible where the vibratory torque exceeds the mean (ratio > 1); the ranges' ends are
the linear crossings between the speeds (:func:`fetorsion.design.verdict.barred_ranges`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..description.chain_model import Network
from ..description.marine import law_torque
from ..errors import FetorsionError
from ..lumped_model.network import network_matrices, resolved, speed_factors
from ..response.forced import ResponseSetup
from ..response.synthesis import grouped_extremes
from ..results import from_fields
from .verdict import barred_ranges


@dataclass
class MeshHammering:
    """One gear mesh over the speed range: ``vibratory_nm`` (the half-range synthesised mesh torque)
    and ``mean_nm`` at station ``station`` (N·m, on that gear's shaft), and the ``ranges`` where the
    vibratory exceeds the mean ({from_rpm, to_rpm, peak (vibratory/mean), peak_rpm})."""

    label: str
    station: str
    vibratory_nm: np.ndarray
    mean_nm: np.ndarray
    ranges: list[dict[str, float]] = field(default_factory=list)

    @property
    def ratio(self) -> np.ndarray:
        """Vibratory over mean torque at each speed (NaN where no mean torque is known)."""
        return np.divide(self.vibratory_nm, self.mean_nm, out=np.full(len(self.mean_nm), np.nan), where=self.mean_nm > 0)


@dataclass
class GearHammering:
    """Every gear mesh of a network against hammering over station 1's speeds ``rpm``."""

    name: str
    rpm: np.ndarray
    meshes: list[MeshHammering]
    notes: list[str] = field(default_factory=list)

    @property
    def verdict(self) -> str:
        """"no hammering", or "hammering possible" where some mesh's vibratory torque exceeds its mean."""
        return "hammering possible" if any(m.ranges for m in self.meshes) else "no hammering"

    def to_dict(self) -> dict:
        """JSON-ready: speeds (rpm), each mesh's torques (N·m) and ranges, the verdict."""
        return {"name": self.name, "rpm": self.rpm.tolist(), "verdict": self.verdict, "notes": self.notes,
                "meshes": [{"label": m.label, "station": m.station, "vibratory_nm": m.vibratory_nm.tolist(),
                            "mean_nm": m.mean_nm.tolist(), "ranges": m.ranges} for m in self.meshes]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "GearHammering":
        """The result back from its :meth:`to_dict`."""
        return from_fields(cls, d)

    def table(self) -> str:
        """Each mesh's largest vibratory/mean ratio and its hammering ranges."""
        lines = [f"{self.name}: gear hammering (vibratory against mean mesh torque)"]
        for m in self.meshes:
            if not np.isfinite(m.ratio).any():
                lines.append(f"  {m.label} (at {m.station}): no propeller on its load side, no mean torque: not judged")
                continue
            k = int(np.nanargmax(m.ratio))
            lines.append(f"  {m.label} (at {m.station}): largest vibratory/mean {m.ratio[k]:.3f} at {self.rpm[k]:.1f} "
                         f"rpm ({m.vibratory_nm[k]:.4g} against {m.mean_nm[k]:.4g} N m)")
            lines += [f"  hammering possible {r['from_rpm']:.1f}-{r['to_rpm']:.1f} rpm (peak {r['peak']:.2f} × mean at "
                      f"{r['peak_rpm']:.1f} rpm)" for r in m.ranges]
        return "\n".join(lines + [f"  verdict: {self.verdict}"] + [f"  note: {n}" for n in self.notes])

    def plot(self, ax=None):
        """Each mesh's vibratory (solid) and mean (dashed) torque over speed, kN m, the hammering
        ranges shaded. Returns the Axes."""
        import matplotlib.pyplot as plt

        ax = ax if ax is not None else plt.figure(figsize=(9, 5)).add_subplot()
        for k, m in enumerate(self.meshes):
            ax.plot(self.rpm, m.vibratory_nm / 1e3, color=f"C{k % 10}", label=f"vibratory {m.label}")
            ax.plot(self.rpm, m.mean_nm / 1e3, color=f"C{k % 10}", ls="--", lw=0.9, label=f"mean {m.label}")
            for r in m.ranges:
                ax.axvspan(r["from_rpm"], r["to_rpm"], color="crimson", alpha=0.15, lw=0)
        ax.set(xlabel="engine speed, station 1 (rpm)", ylabel="mesh torque (kN m)",
               title=f"{self.name}: gear hammering ({self.verdict})")
        ax.legend(fontsize=7)
        return ax


def loaded_stations(net: Network) -> set[int]:
    """Stations an external load, a damper or a cylinder acts on (0-based, of the resolved network)."""
    f = speed_factors(net)
    out = {p.station for p in net.propellers} | set(net.cylinder_stations)
    out |= {s for row in net.cylinder_weights for s, w in enumerate(row) if w}
    for d in net.dampers:
        out.add(0 if d.at == "front" else int(np.flatnonzero(np.isclose(f, 1.0))[-1]) if d.at == "rear"
                else net.labels.index(d.at))
    return out


def mesh_station(net: Network, mesh: int) -> int:
    """The station whose equilibrium gives mesh ``mesh``'s torque: the driven gear, else the driving
    one, whichever carries no load (:func:`loaded_stations`) and no other mesh."""
    g, loaded = net.gears[mesh], loaded_stations(net)
    for x in (g.j, g.i):
        if x not in loaded and sum(x in (h.i, h.j) for h in net.gears) == 1:
            return x
    raise FetorsionError(f"{net.name}: gear {net.labels[g.i]}-{net.labels[g.j]}: both gears carry a load or a "
                         "second mesh; the mesh torque is not resolved")


def load_side(net: Network, mesh: int) -> set[int]:
    """The stations on the side of mesh ``mesh`` away from station 1 (the mesh cut)."""
    links: dict[int, set[int]] = {s: set() for s in range(len(net.labels))}
    pairs = [(s.i, s.j) for s in net.linear_shafts if s.j >= 0]
    pairs += [(h.i, h.j) for k, h in enumerate(net.gears) if k != mesh]
    for a, b in pairs:
        links[a].add(b)
        links[b].add(a)
    seen, todo = {0}, [0]
    while todo:
        for b in links[todo.pop()] - seen:
            seen.add(b)
            todo.append(b)
    g = net.gears[mesh]
    if g.i in seen and g.j in seen:
        raise FetorsionError(f"{net.name}: gear {net.labels[g.i]}-{net.labels[g.j]} closes a loop; no load side")
    return set(range(len(net.labels))) - seen


def mean_mesh_torque(net: Network, mesh: int, station: int, rpm: np.ndarray) -> np.ndarray:
    """T_mean at ``station`` (N·m) of mesh ``mesh`` at station 1's speeds ``rpm``: the propeller law of
    every propeller on the load side, referred by power (module docs)."""
    f, side = speed_factors(net), load_side(net, mesh)
    out = np.zeros(len(rpm))
    for p in (p for p in net.propellers if p.station in side):
        omega = f[p.station] * np.asarray(rpm, float) * math.pi / 30.0
        out += law_torque(p.rated_torque, p.rated_speed, omega, p.exponent) * f[p.station] / f[station]
    return out


def mesh_torque(net: Network, station: int, stations_theta: np.ndarray, omegas: np.ndarray) -> np.ndarray:
    """Λ_x, the mesh's constraint torque on ``station`` (module docs), (speeds, orders) complex N·m.

    Parameters
    ----------
    net : Network
        Resolved (no crank parts).
    station : int
        x, 0-based.
    stations_theta : ndarray (speeds, orders, stations), complex
        Every station's angle, rad.
    omegas : ndarray (speeds, orders)
        Each order's frequency, rad/s.
    """
    th = stations_theta
    c = net.absolute_damping[station] if net.absolute_damping else 0.0
    out = (-omegas**2 * net.inertias[station] + 1j * omegas * c) * th[..., station]
    for s in net.linear_shafts:
        if station not in (s.i, s.j):
            continue
        other = s.j if s.i == station else s.i
        far = th[..., other] if other >= 0 else 0.0
        out = out - (s.stiffness * (1 + 1j * s.loss_factor) + 1j * omegas * s.damping) * (far - th[..., station])
    return out


def gear_hammering(net: Network, setup: ResponseSetup, theta: np.ndarray) -> GearHammering:
    """Every gear mesh of ``net`` against hammering (module docs).

    Parameters
    ----------
    net : Network
        With gears and propellers (their law gives the mean torque).
    setup : ResponseSetup
        The forced-response setup of ``net`` (its orders, speeds and synthesis).
    theta : ndarray (speeds, orders, DOF), complex
        The response's angles in the network's coordinates (``ResponseResult.theta``), rad.
    """
    net = resolved(net)
    if not net.gears or not net.propellers:
        raise FetorsionError(f"{net.name}: gear hammering needs a gear mesh and a propeller (its mean torque)")
    T = network_matrices(net).T
    stations_theta = theta[:, :, :T.shape[1]] @ T.T
    omegas = setup.orders[None, :] * setup.rpm[:, None] * math.pi / 30.0
    meshes = []
    for k, g in enumerate(net.gears):
        x = mesh_station(net, k)
        top, bottom = grouped_extremes(mesh_torque(net, x, stations_theta, omegas), setup.orders, setup.period,
                                       setup.order_groups)
        vib, mean = 0.5 * (top - bottom), mean_mesh_torque(net, k, x, setup.rpm)
        mesh = MeshHammering(f"{net.labels[g.i]}-{net.labels[g.j]}", net.labels[x], vib, mean)
        mesh.ranges = barred_ranges(setup.rpm, mesh.ratio, 1.0) if mean.any() else []
        meshes.append(mesh)
    notes = ["mesh torque from the gear's equilibrium (inertia, its shafts' springs and stated damping); the modal "
             "damping ratio is not a station's and is left out", "mean torque: the propeller law on the mesh's load "
             "side, referred by power without gear losses"]
    return GearHammering(net.name, np.asarray(setup.rpm, float), meshes, notes)
