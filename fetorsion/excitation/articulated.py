"""Master and articulated rods: the articulated cylinder's piston path and its force on the pin.

A vee's two cylinders on one throw can share one big end: the first bank's (master) rod runs on
the pin; the second bank's (articulated) rod runs on a knuckle pin carried by the master rod at a
radius r_k from the big end's centre and an angle γ from the master rod's axis, towards the
second bank. The articulated piston's path is then not a slider-crank's: its stroke, its TDC and
its harmonics differ from the master's. The equations below are derived here from the linkage's
geometry (a textbook treatment is in Taylor's *The Internal-Combustion Engine in Theory and
Practice*, vol. 2, which was not read); the tests check them against the loop closure solved
numerically and against virtual work.

Geometry in the plane of the throw, x along the master cylinder's axis, angles positive in the
crank's rotation; θ is the crank angle from the master's TDC, δ the bank angle (the second bank's
axis e = (cos δ, sin δ), n = (−sin δ, cos δ)), r the crank radius, l the master rod's length:

* pin centre P = r (cos θ, sin θ); master rod angle sin β = (r/l) sin θ, its unit vector from the
  pin to its piston u = (cos β, −sin β);
* knuckle K = P + r_k R(γ) u (R(γ) the rotation by γ);
* articulated piston on its axis at s e with |s e − K| = l_a: s = K·e + √(l_a² − (K·n)²).

s′ and s″ (with respect to θ) follow by differentiating these (β′ = (r/l) cos θ / cos β).
With r_k = 0 the knuckle is the pin's centre and the articulated cylinder is a slider-crank
δ later: the path and forces equal a side-by-side rod's (a test holds both to that).

Forces (massless rods, the reciprocating masses at the pistons): a piston force F (gas and
reciprocating inertia, towards the crank) on the articulated piston loads its rod, a two-force
member, with c = F / (w·e) (w the rod's unit vector from K to the piston); the master rod, held by
its own piston's side reaction N n_m and by the pin, takes −c w at K; its moments about the big
end give N = c (K − P) × w / (l u_x), and the rods' force on the pin is F_pin = N n_m − c w. Its
torque about the crank axis equals F · (−s′) (virtual work): a second derivation the tests hold
the statics to.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ArticulatedLink:
    """A master and articulated rod pair: crank radius ``r``, master rod ``l``, knuckle radius
    ``rk`` and angle ``gamma`` (rad, from the master rod's axis towards the second bank),
    articulated rod ``la`` and bank angle ``bank`` (rad); lengths in m."""

    r: float
    l: float
    rk: float
    gamma: float
    la: float
    bank: float

    def _master(self, theta: np.ndarray):
        """(β, β′, β″) of the master rod at crank angles ``theta`` (rad from the master's TDC)."""
        lam = self.r / self.l
        sb = lam * np.sin(theta)
        cb = np.sqrt(1.0 - sb**2)
        b1 = lam * np.cos(theta) / cb
        b2 = (-lam * np.sin(theta) * cb + lam * np.cos(theta) * sb * b1) / cb**2
        return np.arcsin(sb), b1, b2

    def knuckle(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(K, K′, K″), each (..., 2), m: the knuckle pin's centre and its derivatives in θ."""
        theta = np.asarray(theta, dtype=float)
        b, b1, b2 = self._master(theta)
        c, s = np.cos(theta), np.sin(theta)
        P, P1 = self.r * np.stack([c, s], -1), self.r * np.stack([-s, c], -1)
        u = np.stack([np.cos(b), -np.sin(b)], -1)
        du = np.stack([-np.sin(b), -np.cos(b)], -1)  # du/dβ
        ddu = -u  # d²u/dβ²
        u1 = b1[..., None] * du
        u2 = b2[..., None] * du + (b1**2)[..., None] * ddu
        rot = np.array([[np.cos(self.gamma), -np.sin(self.gamma)], [np.sin(self.gamma), np.cos(self.gamma)]])
        return P + self.rk * u @ rot.T, P1 + self.rk * u1 @ rot.T, -P + self.rk * u2 @ rot.T

    def path(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(s, s′, s″): the articulated piston's distance from the crank axis along its bank's axis
        (m) and its first and second derivatives in θ (m/rad, m/rad²)."""
        K, K1, K2 = self.knuckle(theta)
        e = np.array([np.cos(self.bank), np.sin(self.bank)])
        n = np.array([-np.sin(self.bank), np.cos(self.bank)])
        h, h1, h2 = K @ n, K1 @ n, K2 @ n
        q = np.sqrt(self.la**2 - h**2)
        q1 = -h * h1 / q
        q2 = -(h1**2 + h * h2) / q - (h * h1) ** 2 / q**3
        return K @ e + q, K1 @ e + q1, K2 @ e + q2

    def tdc_shift(self) -> float:
        """How far after the bank angle δ the articulated piston reaches its TDC (s′ = 0, s largest),
        rad: the root of s′ within half a radian of δ."""
        from scipy.optimize import brentq

        return float(brentq(lambda d: float(self.path(self.bank + d)[1]), -0.5, 0.5, xtol=1e-15))

    def pin_forces(self, theta, force) -> dict[str, np.ndarray]:
        """The rods' force on the pin from a piston force ``force`` (N, towards the crank) on the
        articulated piston at crank angles ``theta`` (rad from the master's TDC; module docs):
        ``tangential`` (N, positive driving the crank) and ``radial`` (N, positive outwards)."""
        theta = np.asarray(theta, dtype=float)
        force = np.broadcast_to(np.asarray(force, dtype=float), theta.shape)
        K, _, _ = self.knuckle(theta)
        s = self.path(theta)[0]
        e = np.array([np.cos(self.bank), np.sin(self.bank)])
        w = (s[..., None] * e - K) / self.la
        c = force / (w @ e)
        b = self._master(theta)[0]
        P = self.r * np.stack([np.cos(theta), np.sin(theta)], -1)
        arm = K - P
        N = c * (arm[..., 0] * w[..., 1] - arm[..., 1] * w[..., 0]) / (self.l * np.cos(b))
        f = np.stack([np.zeros_like(N), N], -1) - c[..., None] * w
        radial_unit = np.stack([np.cos(theta), np.sin(theta)], -1)
        tangential_unit = np.stack([-np.sin(theta), np.cos(theta)], -1)
        return {"tangential": np.sum(f * tangential_unit, -1), "radial": np.sum(f * radial_unit, -1)}
