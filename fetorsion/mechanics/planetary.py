"""Planetary crank mechanisms ([Ismailov]): big-end trajectories, piston motion, torque arm.

The carrier is the crank: it turns by φ about the crank axis O and carries a satellite
gear of pitch diameter d_p that rolls on a fixed gear of pitch diameter d_f, outside a
fixed sun (epicycloid) or inside a fixed ring (hypocycloid). The rod's big end sits on
the satellite at distance e from its centre ([Ismailov]: on the pitch circle, e = d_p/2;
other e give trochoids). In complex form, with a = d_f/2, ρ = d_p/2 (derived here from
rolling without slip)::

    epicycloid:   B(φ) = (a + ρ) e^{iφ} + e · e^{i((a + ρ)/ρ · φ + ψ0)}
    hypocycloid:  B(φ) = (a − ρ) e^{iφ} + e · e^{−i((a − ρ)/ρ · φ − ψ0)}

ψ0 = 0 puts the big end at its farthest from O, on the cylinder axis, at φ = 0. The
cylinder axis is x through O (as in :mod:`fetorsion.excitation.kinematics`); a rod of length l gives
the piston-pin position x_p = B_x + √(l² − B_y²). A conventional crank is the case
ρ → 0 with a + ρ = r, e = 0.

Two "torque arms" are reported, because they differ for a geared crank:

* geometric arm h = B_y x_p / l, the distance from O to the rod line ([Ismailov] fig. 3,
  "MN"); the rod-force moment about O is F_rod·h. For the conventional crank h = r sin(φ+β).
* effective arm −dx_p/dφ: by virtual work the torque the carrier delivers per unit piston
  force, reactions of the fixed gear included. For the conventional crank it is
  r sin(φ+β)/cos β (= F_T r / F).

At a dead centre of the piston dx_p/dφ = 0, so the effective arm is zero for every
mechanism; the planetary crank can have a geometric arm there (the rod line misses O), but
the fixed gear's reaction then cancels its moment. The module reports both and
:func:`dead_centres` finds the piston's dead centres
(not the dwells at the path's cusps).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

__all__ = ["KINDS", "PlanetaryResult", "big_end", "closing_turns", "dead_centres", "planetary", "piston_motion"]

KINDS = ("epicycloid", "hypocycloid", "conventional")


def _geometry(kind, fixed_diameter, planet_diameter, eccentricity):
    """(carrier radius, satellite spin per carrier turn, pin radius) of a mechanism."""
    a, rho = fixed_diameter / 2, planet_diameter / 2
    e = rho if eccentricity is None else eccentricity
    if kind == "epicycloid":
        return a + rho, (a + rho) / rho, e
    if kind == "hypocycloid":
        if not rho < a:
            raise ValueError(f"a hypocycloid needs the planet ({planet_diameter} m) smaller than the ring ({fixed_diameter} m)")
        return a - rho, -(a - rho) / rho, e
    if kind == "conventional":
        return fixed_diameter / 2, 0.0, 0.0
    raise ValueError(f"kind {kind!r}: choose from {KINDS}")


def big_end(phi, kind, fixed_diameter, planet_diameter=0.0, eccentricity=None, pin_phase=0.0):
    """Big-end position B(φ) and its first two φ-derivatives, complex, m.

    Parameters
    ----------
    phi : array_like
        Carrier (crank) angle, rad.
    kind : {"epicycloid", "hypocycloid", "conventional"}
        Fixed sun, fixed ring, or plain crank (then ``fixed_diameter`` is the stroke 2r).
    fixed_diameter : float
        Pitch diameter of the fixed gear, m (for "conventional": 2r).
    planet_diameter : float
        Pitch diameter of the satellite, m.
    eccentricity : float, optional
        Big-end distance from the satellite centre, m; default on the pitch circle.
    pin_phase : float
        ψ0, rad.

    Returns
    -------
    b, db, ddb : ndarray of complex
        B, dB/dφ, d²B/dφ² (x = real, y = imag).

    Examples
    --------
    >>> b = big_end(np.radians([0.0, 45.0, 90.0]), "hypocycloid", 0.06, 0.03)[0]   # Cardan: a line
    >>> np.round(b.imag, 12).tolist(), np.round(b.real, 6).tolist()
    ([0.0, 0.0, 0.0], [0.03, 0.021213, 0.0])
    """
    phi = np.asarray(phi, dtype=float)
    arm, spin, e = _geometry(kind, fixed_diameter, planet_diameter, eccentricity)
    c = arm * np.exp(1j * phi)
    p = e * np.exp(1j * (spin * phi + pin_phase))
    return c + p, 1j * c + 1j * spin * p, -c - spin**2 * p


def piston_motion(b, db, ddb, l):
    """Piston-pin position x_p and its φ-derivatives from a big-end path, m, m/rad, m/rad².

    x_p = B_x + g with g = √(l² − B_y²); g' = −B_y B_y'/g; g'' = −(B_y'² + B_y B_y'')/g − B_y² B_y'²/g³.
    """
    bx, by = b.real, b.imag
    dbx, dby = db.real, db.imag
    if np.any(np.abs(by) >= l):
        raise ValueError(f"rod length {l} m is shorter than the big end's reach across the axis ({np.abs(by).max():.4g} m)")
    g = np.sqrt(l**2 - by**2)
    dg = -by * dby / g
    ddg = -(dby**2 + by * ddb.imag) / g - by**2 * dby**2 / g**3
    return bx + g, dbx + dg, ddb.real + ddg


def closing_turns(kind, fixed_diameter, planet_diameter, max_den=64):
    """Carrier turns after which the big-end path closes (the satellite spin ratio's denominator)."""
    if kind == "conventional":
        return 1
    spin = _geometry(kind, fixed_diameter, planet_diameter, None)[1]
    return Fraction(abs(spin)).limit_denominator(max_den).denominator


def dead_centres(x, dx):
    """Indices of the piston's dead centres over a closed (periodic) sampling.

    A dead centre is where dx_p/dφ changes sign; where it only touches zero (the big end
    stops at a cusp of the path and goes on the same way) the piston dwells but does not
    turn back, and that is not counted. The sample nearer the sign change is returned.

    Returns
    -------
    top, bottom : ndarray of int
        Indices of the TDCs (+ to −) and BDCs (− to +).
    """
    dx = np.asarray(dx)
    nxt = np.roll(dx, -1)
    pick = lambda i: np.where(np.abs(dx[i]) <= np.abs(nxt[i]), i, (i + 1) % len(dx))  # noqa: E731
    return pick(np.flatnonzero((dx > 0) & (nxt <= 0))), pick(np.flatnonzero((dx < 0) & (nxt >= 0)))


@dataclass
class PlanetaryResult:
    """Big-end path and piston motion of a planetary (or conventional) crank.

    Attributes
    ----------
    kind : str
        "epicycloid", "hypocycloid" or "conventional".
    fixed_diameter_m, planet_diameter_m, eccentricity_m, rod_length_m : float
        The mechanism.
    phi_rad : ndarray
        Carrier angle over the closing period (``turns`` × 2π, last point excluded).
    big_end_x_m, big_end_y_m : ndarray
        Big-end path.
    piston_m, piston_dphi_m, piston_dphi2_m : ndarray
        x_p and its derivatives per radian of carrier angle (times ω, ω² for velocity and
        acceleration at constant carrier speed).
    geometric_arm_m, effective_arm_m : ndarray
        Distance from O to the rod line, and −dx_p/dφ (module docs).
    tdc_index, bdc_index : ndarray of int
        Piston dead centres.
    """

    kind: str
    fixed_diameter_m: float
    planet_diameter_m: float
    eccentricity_m: float
    rod_length_m: float
    turns: int
    phi_rad: np.ndarray
    big_end_x_m: np.ndarray
    big_end_y_m: np.ndarray
    piston_m: np.ndarray
    piston_dphi_m: np.ndarray
    piston_dphi2_m: np.ndarray
    geometric_arm_m: np.ndarray
    effective_arm_m: np.ndarray
    tdc_index: np.ndarray
    bdc_index: np.ndarray
    name: str = ""
    inputs: dict = field(default_factory=dict)

    @property
    def stroke_m(self) -> float:
        return float(self.piston_m.max() - self.piston_m.min())

    @property
    def strokes_per_turn(self) -> float:
        """Piston double strokes (TDC to TDC) per carrier turn."""
        return len(self.tdc_index) / self.turns

    def at_top_dead_centre(self) -> dict:
        """Geometric and effective arm at the highest TDC, m (and its carrier angle)."""
        i = self.tdc_index[np.argmax(self.piston_m[self.tdc_index])]
        return {"phi_deg": float(np.degrees(self.phi_rad[i])), "piston_m": float(self.piston_m[i]),
                "geometric_arm_m": float(self.geometric_arm_m[i]), "effective_arm_m": float(self.effective_arm_m[i])}

    def at_dead_centres(self) -> dict:
        """Largest |geometric| and |effective| arm over all dead centres (TDC and BDC), m."""
        dead = np.concatenate([self.tdc_index, self.bdc_index])
        return {"max_geometric_arm_m": float(np.abs(self.geometric_arm_m[dead]).max()),
                "max_effective_arm_m": float(np.abs(self.effective_arm_m[dead]).max())}

    def figures(self) -> dict:
        """The mechanism's scalar results (no curves), SI units."""
        return {"name": self.name, "kind": self.kind, "fixed_diameter_m": self.fixed_diameter_m,
                "planet_diameter_m": self.planet_diameter_m, "eccentricity_m": self.eccentricity_m,
                "rod_length_m": self.rod_length_m, "turns_to_close": self.turns, "stroke_m": self.stroke_m,
                "strokes_per_turn": self.strokes_per_turn,
                "max_geometric_arm_m": float(np.abs(self.geometric_arm_m).max()),
                "max_effective_arm_m": float(np.abs(self.effective_arm_m).max()),
                "at_tdc": self.at_top_dead_centre(), "at_dead_centres": self.at_dead_centres(), **self.inputs}

    def to_dict(self) -> dict:
        out = self.figures()
        for key in ("phi_rad", "big_end_x_m", "big_end_y_m", "piston_m", "piston_dphi_m", "piston_dphi2_m",
                    "geometric_arm_m", "effective_arm_m", "tdc_index", "bdc_index"):
            out[key] = getattr(self, key).tolist()
        return out

    def label(self) -> str:
        if self.kind == "conventional":
            return f"conventional r = {1e3 * self.fixed_diameter_m / 2:g} mm"
        return f"{self.kind} d_f = {1e3 * self.fixed_diameter_m:g}, d_p = {1e3 * self.planet_diameter_m:g} mm"

    def table(self) -> str:
        """One line: turns to close, strokes per turn, stroke and the largest arms (mm)."""
        dc = self.at_dead_centres()
        return (f"{self.label()}: {self.turns} turn(s), {self.strokes_per_turn:.2f} strokes/turn, stroke "
                f"{1e3 * self.stroke_m:.3f} mm, dead-centre arms {1e3 * dc['max_geometric_arm_m']:.3f} (geometric) / "
                f"{1e3 * dc['max_effective_arm_m']:.3f} mm (effective)")

    def plot(self, ax=None):
        """Big-end path with the fixed gear circle and the dead centres; returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(5, 5))
        line, = ax.plot(1e3 * self.big_end_x_m, 1e3 * self.big_end_y_m, lw=1.2, label=self.label())
        ax.plot(1e3 * self.big_end_x_m[self.tdc_index], 1e3 * self.big_end_y_m[self.tdc_index], "^",
                color=line.get_color(), ms=5)
        if self.kind != "conventional":
            t = np.linspace(0, 2 * np.pi, 200)
            ax.plot(1e3 * self.fixed_diameter_m / 2 * np.cos(t), 1e3 * self.fixed_diameter_m / 2 * np.sin(t),
                    color=line.get_color(), lw=0.6, ls=":")
        ax.set_aspect("equal")
        ax.set_xlabel("x (cylinder axis) [mm]")
        ax.set_ylabel("y [mm]")
        return ax


def planetary(kind, fixed_diameter, planet_diameter, rod_length, eccentricity=None, pin_phase=0.0,
              samples_per_turn=3600, name="") -> PlanetaryResult:
    """Big-end path, piston motion and torque arms of a planetary crank over its closing period.

    Parameters
    ----------
    kind : {"epicycloid", "hypocycloid", "conventional"}
        See :func:`big_end`.
    fixed_diameter, planet_diameter : float
        Pitch diameters of the fixed gear and the satellite, m (conventional: 2r and 0).
    rod_length : float
        Rod length l, m.
    eccentricity : float, optional
        Big-end distance from the satellite centre, m (default d_p/2).
    pin_phase : float
        ψ0, rad.
    samples_per_turn : int
        Carrier-angle samples per turn.

    Examples
    --------
    >>> res = planetary("epicycloid", 0.060, 0.030, 0.200)    # [Ismailov] fig. 2b: two cusps
    >>> res.turns, res.strokes_per_turn, round(res.stroke_m * 1e3, 3)   # x_p from 260 to 140 mm
    (1, 3.0, 120.0)
    """
    turns = closing_turns(kind, fixed_diameter, planet_diameter)
    n = samples_per_turn * turns
    phi = np.arange(n) * (2 * np.pi * turns / n)
    b, db, ddb = big_end(phi, kind, fixed_diameter, planet_diameter, eccentricity, pin_phase)
    x, dx, ddx = piston_motion(b, db, ddb, rod_length)
    top, bottom = dead_centres(x, dx)
    e = _geometry(kind, fixed_diameter, planet_diameter, eccentricity)[2]
    return PlanetaryResult(kind, fixed_diameter, planet_diameter, e, rod_length, turns, phi, b.real, b.imag,
                           x, dx, ddx, b.imag * x / rod_length, -dx, top, bottom, name)
