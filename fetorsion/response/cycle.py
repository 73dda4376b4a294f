"""The load cycle at every fillet section: mean and vibratory, over crank angle.

At each operating speed the condensed crank in its bearings carries

* the **mean** (order 0) of the cylinders' gas and inertia pin forces, solved statically: the
  bearings take the radial loads and the flywheel end takes the mean torque (the driveline's
  steady load torque), holding the last master's θx (and its axial motion when no thrust
  bearing holds it);
* the **vibratory** orders 0.5 … of the same forces, the forced response of
  :func:`fetorsion.response.forced.solve_theta` (dampers, Coriolis and all).

Every fillet cut's six resultants (axial force, two shears, torque, two bending moments about
the cut's centre, in the crank's own frame: x along the axis, y and z turning with it) are
the rows ``cc.cut_rows`` times the reduced solution; their sum over orders, synthesised on a
crank-angle grid over one cycle, is the section's load history. A throw's plane is spanned by
the axis and its pin direction e_r = (0, cos a, sin a); the bending moment **in** that plane is
the component about e_t = (0, −sin a, cos a), the one that bends the pin fillets open and shut
under the radial gas and inertia forces.

The mean also carries the centrifugal load of the crank's own mass (Ω² times
``CondensedCrank.centrifugal``: counterweights, webs, pins) and that of the rods' rotating big
ends, ``[excitation] rotating_mass_kg``, which the radial pin forces carry (a pin's attachment
gives the vibration its inertia, not its force).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..excitation.loads import cylinder_loads
from ..excitation.torque import cycle_angle
from ..fe.condensed import CondensedCrank

if TYPE_CHECKING:
    from ..description.model import Damper
    from .forced import ResponseSetup

#: The six resultants of a cut, in the order of ``CondensedCrank.cut_rows``.
COMPONENTS = ("axial force", "shear y", "shear z", "torque", "moment y", "moment z")
#: Crank-angle samples per cycle of a load history (a 4-stroke cycle: 1° steps).
CYCLE_SAMPLES = 720


def mean_master_loads(cc: CondensedCrank, rpm) -> np.ndarray:
    """(speeds, 6·masters): the cycle mean of every cylinder's tangential and radial pin force on
    the pin masters, N (each cylinder's own mean: the mean has no firing phase)."""
    from .coupled import pin_load_map

    loads = cylinder_loads(cc.crank)
    mean = np.array([[[f["tangential"][c].mean(), f["radial"][c].mean()] for c in range(loads.cylinders)]
                     for f in (loads.pin_forces(float(n)) for n in np.atleast_1d(rpm))])  # (speeds, cylinders, 2)
    return np.einsum("sck,ckd->sd", mean, pin_load_map(cc))


def static_solution(cc: CondensedCrank, loads: np.ndarray, support: str = "bearings") -> np.ndarray:
    """Reduced coordinates (..., r) under static loads on the master DOF (..., 6·masters; N and
    N·m) or on every reduced coordinate (..., r).

    What ``support`` leaves free is held at the last master (the flywheel end): its θx (the load
    torque the driveline reacts) and, if the crank can still slide, its axial motion; every
    other free motion would make the loads unbalanced and is refused.
    """
    from ..errors import FetorsionError

    Dk, _, held = cc.support_terms(support)
    r, m = cc.reduced.size, cc.n_master_dofs
    K = cc.reduced.K.copy()
    K[:m, :m] += Dk
    last = cc.labels[-1]
    held = list(held)
    for name in ("rx", "tx"):
        keep = np.setdiff1d(np.arange(r), held)
        w = np.linalg.eigvalsh(K[np.ix_(keep, keep)] / np.abs(K).max())
        if w[0] > 1e-10:
            break
        held.append(cc.dof(last, name))
    keep = np.setdiff1d(np.arange(r), held)
    Kk = K[np.ix_(keep, keep)]
    if np.linalg.eigvalsh(Kk / np.abs(K).max())[0] <= 1e-10:
        raise FetorsionError(f"{cc.crank.name}: the crank is not held against every rigid motion in {support}")
    F = np.zeros(loads.shape[:-1] + (r,))
    F[..., :loads.shape[-1]] = loads
    z = np.zeros_like(F)
    z[..., keep] = np.linalg.solve(Kk, F[..., keep].T).T
    return z


@dataclass
class LoadCycle:
    """Section loads at the fillet cuts over one engine cycle, at each speed.

    Attributes
    ----------
    rpm : ndarray (speeds,)
    angles : ndarray (angles,)
        Crank angle from cylinder 1's firing TDC, rad, over one cycle.
    labels : list of str
        The cuts (fillets).
    mean : ndarray (speeds, cuts, 6)
        Order-0 resultants (:data:`COMPONENTS`), N and N·m.
    history : ndarray (speeds, cuts, 6, angles)
        Mean plus vibratory resultants over the cycle, N and N·m.
    throw_angle : ndarray (cuts,)
        Angle a of the throw plane each cut's bending is resolved in, rad.
    """

    name: str
    rpm: np.ndarray
    angles: np.ndarray
    labels: list
    mean: np.ndarray
    history: np.ndarray
    throw_angle: np.ndarray

    def bending_in_plane(self) -> np.ndarray:
        """(speeds, cuts, angles): the bending moment about e_t (in the throw's plane), N·m."""
        s, c = np.sin(self.throw_angle)[None, :, None], np.cos(self.throw_angle)[None, :, None]
        return -s * self.history[:, :, 4] + c * self.history[:, :, 5]

    def bending_out_of_plane(self) -> np.ndarray:
        """(speeds, cuts, angles): the bending moment about e_r (across the throw's plane), N·m."""
        s, c = np.sin(self.throw_angle)[None, :, None], np.cos(self.throw_angle)[None, :, None]
        return c * self.history[:, :, 4] + s * self.history[:, :, 5]

    def torque(self) -> np.ndarray:
        """(speeds, cuts, angles): the torque through each cut, N·m."""
        return self.history[:, :, 3]

    def to_dict(self) -> dict:
        b, t = self.bending_in_plane(), self.torque()
        return {"name": self.name, "rpm": self.rpm.tolist(), "cuts": list(self.labels),
                "bending_in_plane_mean_nm": b.mean(axis=2).tolist(),
                "bending_in_plane_amplitude_nm": (0.5 * np.ptp(b, axis=2)).tolist(),
                "torque_mean_nm": t.mean(axis=2).tolist(), "torque_amplitude_nm": (0.5 * np.ptp(t, axis=2)).tolist()}

    def plot(self, speed: int, cut: int, ax=None):
        """The in-plane bending moment and the torque of one cut over the cycle. Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 3.5))
        deg = np.degrees(self.angles)
        ax.plot(deg, self.bending_in_plane()[speed, cut], label="bending in the throw plane")
        ax.plot(deg, self.torque()[speed, cut], label="torque")
        ax.set_xlabel("crank angle from cylinder 1's firing TDC [deg]")
        ax.set_ylabel("section load [N m]")
        ax.set_title(f"{self.labels[cut]}, {self.rpm[speed]:.0f} rpm", fontsize=10)
        ax.legend(fontsize=8)
        return ax


def cut_throw_angles(cc: CondensedCrank) -> np.ndarray:
    """Throw-plane angle of each cut: its pin's angle for a pin cut (the centre off the axis);
    for a journal cut, the nearer pin's (the throw whose web meets that journal)."""
    centres = cc.cut_centres
    pins = np.array([cc.positions[cc.labels.index(f"P{c + 1}")][0] for c in range(cc.crank.throws)])
    angles = np.asarray(cc.crank.engine.crank_angles, float)
    out = np.empty(len(centres))
    for k, c in enumerate(centres):
        radius = math.hypot(c[1], c[2])
        out[k] = math.atan2(c[2], c[1]) if radius > 1e-9 else angles[int(np.argmin(np.abs(pins - c[0])))]
    return out


def mean_cut_loads(cc: CondensedCrank, rpm: Sequence[float] | np.ndarray) -> np.ndarray:
    """(speeds, cuts, 6) cycle means of the fillet cuts' resultants at ``rpm``: the gas and inertia
    pin forces' means and the crank's own centrifugal load, solved statically in the bearings
    (the flywheel end reacting the load torque). Independent of damping and dampers."""
    rpm = np.atleast_1d(np.asarray(rpm, dtype=float))
    m = cc.n_master_dofs
    loads = np.zeros((len(rpm), cc.reduced.size))
    loads[:, :m] = mean_master_loads(cc, rpm)
    if cc.centrifugal is not None:  # the crank's own rotating mass (counterweights, webs, pins)
        loads += np.outer((rpm * 2 * np.pi / 60) ** 2, cc.centrifugal)
    return np.einsum("cjr,sr->scj", cc.cut_rows, static_solution(cc, loads), optimize=True)


def run_load_cycle(cc: CondensedCrank, setup: ResponseSetup, dampers: Sequence[Damper] = (),
                   samples: int = CYCLE_SAMPLES, mean: np.ndarray | None = None) -> LoadCycle:
    """The fillet cuts' load histories of the condensed crank in its bearings at every speed of
    ``setup`` (:func:`fetorsion.response.coupled.condensed_setup`, with ``dampers``).

    Parameters
    ----------
    cc : CondensedCrank
        With fillet cuts (``run_condensed(cuts=...)``).
    setup : ResponseSetup
        The crank's condensed setup in ``bearings``; its speeds and orders are used.
    dampers : sequence of Damper
        Torsional dampers on the crank (the description's ``[[dampers]]``); a heat-following
        rubber is put at its own temperature.
    samples : int
        Crank-angle samples over one cycle.
    mean : ndarray, optional
        :func:`mean_cut_loads` at the setup's speeds, when the caller has it (it does not change
        with the damping: an assessment across a damping band computes it once).
    """
    from ..errors import FetorsionError
    from ..lumped_model.damped import complex_times
    from .forced import solve_theta
    from .synthesis import waveform

    if cc.cut_rows is None:
        raise FetorsionError("the condensed crank has no fillet cuts (run_condensed(cuts=...))")
    # the crank's DOF lead the setup's (a driveline's other coordinates follow them)
    own = setup.labels if setup.crank_dofs is None else setup.labels[:setup.crank_dofs]
    keep = np.array([cc.dof(*lb.split(" ")) if not lb.startswith("interior") else
                     cc.n_master_dofs + int(lb.split(" ")[1]) - 1 for lb in own])
    theta, _, _ = solve_theta(setup, dampers)
    rows = cc.cut_rows[:, :, keep]  # (cuts, 6, DOF)
    n = len(keep)
    vib = complex_times(theta[:, :, :n], np.ascontiguousarray(rows.reshape(-1, n).T))  # (speeds, orders, cuts·6)
    vib = np.moveaxis(vib.reshape(vib.shape[:2] + rows.shape[:2]), 1, -1)  # (speeds, cuts, 6, orders)
    angles = np.arange(samples) * cycle_angle(cc.crank.engine) / samples
    if mean is None:
        mean = mean_cut_loads(cc, setup.rpm)
    elif len(mean) != len(setup.rpm):
        raise FetorsionError(f"mean cut loads at {len(mean)} speeds for a setup of {len(setup.rpm)}")
    history = mean[..., None] + waveform(vib, setup.orders, angles)
    labels = list(setup.section_labels)[:len(rows)] if len(setup.section_labels) >= len(rows) else \
        [f"cut {k + 1}" for k in range(len(rows))]
    return LoadCycle(cc.crank.name, np.asarray(setup.rpm), angles, labels, mean, history, cut_throw_angles(cc))
