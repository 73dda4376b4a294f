"""Slider-crank kinematics and crank-pin forces, exact and as the papers' series.

Conventions ([Kazemi]): the cylinder axis passes through the crank axis; θ is the crank
angle from top dead centre (TDC), positive in the sense of rotation; r the crank radius,
l the rod length (eye centre to eye centre), λ = r/l, β the rod angle from the cylinder
axis with sin β = λ sin θ. The piston position S is measured from the crank axis towards
the cylinder head; the displacement X from TDC ([Ismailov]) is X = r + l − S.

Exact forms::

    S(θ)  = r cos θ + l √(1 − λ² sin²θ)                                   [Kazemi] eq. 5
    Ṡ(θ)  = −r ω [sin θ + λ sin θ cos θ / √D],      D = 1 − λ² sin²θ
    S̈(θ)  = −r ω² [cos θ + λ (cos 2θ + λ² sin⁴θ) / D^{3/2}]
    β̇     = λ ω cos θ / cos β                                              [Kazemi] eq. 11
    β̈     = −λ (1 − λ²) ω² sin θ / D^{3/2}

Second-order series ([Ismailov] eq. 17–19, [Kazemi] eq. 7, 9, 10, 12)::

    S ≈ r cos θ + l (1 − λ²/4 + (λ²/4) cos 2θ)
    Ṡ ≈ −r ω (sin θ + (λ/2) sin 2θ),      S̈ ≈ −r ω² (cos θ + λ cos 2θ)
    β̇ ≈ λ ω cos θ (1 + λ²/4 − (λ²/4) cos 2θ)

Crank-pin forces from a force F acting on the piston along the cylinder axis, towards the
crank (gas force plus piston inertia force, [Kazemi] eq. 13), with the rod force F/cos β::

    tangential F_T = F sin(θ + β)/cos β        (drives the crank; torque T = F_T r)
    radial     F_R = −F cos(θ + β)/cos β       (positive outwards along the crank)
    side       F_N = F tan β                   (piston on the liner)

Their series to λ³ ([Kazemi] eq. 16–19) are in :func:`pin_forces_series`. Two of the
printed series disagree with the exact forms they come from: eq. 17 lacks the factor λ
in front of sin θ, and eq. 18 has the sign of its λ terms flipped (at θ = 90° the rod
pushes the pin outwards, F_R = +λF/cos β). The functions here follow the exact forms.

Everything is vectorised over θ (any array shape) and in SI units.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "KinematicsResult", "crank_ratio", "kinematics", "pin_forces", "pin_forces_series",
    "piston_acceleration", "piston_acceleration_series", "piston_displacement",
    "piston_displacement_series", "piston_position", "piston_position_series",
    "piston_velocity", "piston_velocity_series", "rod_angle", "rod_angular_acceleration",
    "rod_angular_velocity", "rod_angular_velocity_series", "tangential_torque",
]


def crank_ratio(r, l):
    """λ = r / l, checked to be in (0, 1) so the mechanism can assemble.

    Parameters
    ----------
    r : float
        Crank radius, m.
    l : float
        Rod length (eye centre to eye centre), m.

    Returns
    -------
    float
        λ, dimensionless.

    Examples
    --------
    >>> crank_ratio(0.0425, 0.1345)
    0.3159851301115242
    """
    lam = r / l
    if not 0.0 < lam < 1.0:
        raise ValueError(f"crank radius {r} m and rod length {l} m give λ = {lam}: need 0 < r < l")
    return lam


def _d(theta, lam):
    """D = 1 − λ² sin²θ = cos²β."""
    return 1.0 - (lam * np.sin(theta)) ** 2


def rod_angle(theta, r, l):
    """Rod angle β from the cylinder axis, rad: sin β = λ sin θ ([Kazemi] eq. 3); θ, r and l as
    the module's conventions (rad from TDC; m).

    Examples
    --------
    >>> round(float(np.degrees(rod_angle(np.pi / 2, 0.05, 0.2))), 4)   # arcsin(0.25)
    14.4775
    """
    return np.arcsin(crank_ratio(r, l) * np.sin(theta))


def piston_position(theta, r, l):
    """Exact piston-pin distance from the crank axis S(θ), m ([Kazemi] eq. 5); θ, r and l as the
    module's conventions.

    Examples
    --------
    >>> round(float(piston_position(0.0, 0.0425, 0.1345)), 12)       # TDC: r + l
    0.177
    """
    lam = crank_ratio(r, l)
    return r * np.cos(theta) + l * np.sqrt(_d(theta, lam))


def piston_position_series(theta, r, l):
    """Second-order series of S(θ), m ([Kazemi] eq. 7): r cos θ + l(1 − λ²/4 + λ²/4 cos 2θ)."""
    lam = crank_ratio(r, l)
    return r * np.cos(theta) + l * (1.0 - lam**2 / 4 + lam**2 / 4 * np.cos(2 * theta))


def piston_displacement(theta, r, l):
    """Exact displacement from TDC X(θ) = r[(1 − cos θ) + (1 − √(1 − λ² sin²θ))/λ], m ([Ismailov] eq. 13)."""
    return r + l - piston_position(theta, r, l)


def piston_displacement_series(theta, r, l):
    """Series X(θ) ≈ r[(1 − cos θ) + (λ/4)(1 − cos 2θ)], m ([Ismailov] eq. 17)."""
    lam = crank_ratio(r, l)
    return r * ((1.0 - np.cos(theta)) + lam / 4 * (1.0 - np.cos(2 * theta)))


def piston_velocity(theta: float | np.ndarray, r: float, l: float, omega: float):
    """Exact piston velocity dS/dt, m/s (positive towards the head), at the constant crank speed
    ``omega`` (rad/s); θ, r and l as the module's conventions.

    Examples
    --------
    >>> float(piston_velocity(np.pi / 2, 0.05, 0.2, 100.0))   # rod angle gives no term at 90°
    -5.0
    """
    lam = crank_ratio(r, l)
    s, c = np.sin(theta), np.cos(theta)
    return -r * omega * (s + lam * s * c / np.sqrt(_d(theta, lam)))


def piston_velocity_series(theta, r, l, omega):
    """Series Ṡ ≈ −rω(sin θ + (λ/2) sin 2θ), m/s ([Kazemi] eq. 9; [Ismailov] eq. 18 is dX/dt = −Ṡ)."""
    lam = crank_ratio(r, l)
    return -r * omega * (np.sin(theta) + lam / 2 * np.sin(2 * theta))


def piston_acceleration(theta, r, l, omega):
    """Exact piston acceleration d²S/dt², m/s² (constant ω).

    Examples
    --------
    >>> float(piston_acceleration(0.0, 0.05, 0.2, 100.0))    # TDC: −rω²(1 + λ), exact
    -625.0
    """
    lam = crank_ratio(r, l)
    s = np.sin(theta)
    return -r * omega**2 * (np.cos(theta) + lam * (np.cos(2 * theta) + lam**2 * s**4) / _d(theta, lam) ** 1.5)


def piston_acceleration_series(theta, r, l, omega):
    """Series S̈ ≈ −rω²(cos θ + λ cos 2θ), m/s² ([Kazemi] eq. 10, [Ismailov] eq. 19, [Asgari] eq. 1)."""
    lam = crank_ratio(r, l)
    return -r * omega**2 * (np.cos(theta) + lam * np.cos(2 * theta))


def rod_angular_velocity(theta, r, l, omega):
    """Exact rod angular velocity β̇ = λω cos θ / cos β, rad/s ([Kazemi] eq. 11)."""
    lam = crank_ratio(r, l)
    return lam * omega * np.cos(theta) / np.sqrt(_d(theta, lam))


def rod_angular_velocity_series(theta, r, l, omega):
    """Series β̇ ≈ λω cos θ (1 + λ²/4 − (λ²/4) cos 2θ), rad/s ([Kazemi] eq. 12)."""
    lam = crank_ratio(r, l)
    return lam * omega * np.cos(theta) * (1.0 + lam**2 / 4 - lam**2 / 4 * np.cos(2 * theta))


def rod_angular_acceleration(theta, r, l, omega):
    """Exact rod angular acceleration β̈ = −λ(1 − λ²)ω² sin θ / (1 − λ² sin²θ)^{3/2}, rad/s²."""
    lam = crank_ratio(r, l)
    return -lam * (1.0 - lam**2) * omega**2 * np.sin(theta) / _d(theta, lam) ** 1.5


def pin_forces(theta, force, r, l):
    """Exact crank-pin force components from a piston force along the cylinder axis.

    Parameters
    ----------
    theta : array_like
        Crank angle from TDC, rad.
    force : array_like
        Piston force towards the crank (gas force plus piston inertia force), N;
        broadcast against ``theta``.
    r, l : float
        Crank radius and rod length, m.

    Returns
    -------
    dict of ndarray
        ``tangential`` F·sin(θ+β)/cos β (N, positive driving the crank), ``radial``
        −F·cos(θ+β)/cos β (N, positive outwards), ``side`` F·tan β (N), ``rod`` F/cos β (N).

    Examples
    --------
    >>> f = pin_forces(np.pi / 2, 1000.0, 0.05, 0.2)
    >>> round(float(f["tangential"]), 6), round(float(f["radial"]), 3)    # F and λF/cos β
    (1000.0, 258.199)
    """
    beta = rod_angle(theta, r, l)
    cb = np.cos(beta)
    return {
        "tangential": force * np.sin(theta + beta) / cb,
        "radial": -force * np.cos(theta + beta) / cb,
        "side": force * np.tan(beta),
        "rod": force / cb,
    }


def pin_forces_series(theta, force, r, l):
    """The same components as :func:`pin_forces` as series to λ³ ([Kazemi] eq. 16–19).

    ``tangential`` is eq. 19 as printed; ``rod`` is eq. 16; ``side`` and ``radial`` are eq. 17
    and 18 with the misprints corrected (module docs): F λ(sin θ + (λ²/8)(3 sin θ − sin 3θ))
    and −F(cos θ − λ/2 + (λ/2) cos 2θ − (λ³/16)(3 − 4 cos 2θ + cos 4θ)).
    """
    lam = crank_ratio(r, l)
    t = np.asarray(theta, dtype=float)
    return {
        "tangential": force * (np.sin(t) + lam / 2 * np.sin(2 * t) + lam**3 / 16 * (2 * np.sin(2 * t) - np.sin(4 * t))),
        "radial": -force * (np.cos(t) - lam / 2 + lam / 2 * np.cos(2 * t)
                            - lam**3 / 16 * (3 - 4 * np.cos(2 * t) + np.cos(4 * t))),
        "side": force * lam * (np.sin(t) + lam**2 / 8 * (3 * np.sin(t) - np.sin(3 * t))),
        "rod": force * (1.0 + lam**2 / 4 - lam**2 / 4 * np.cos(2 * t)),
    }


def tangential_torque(theta, force, r, l):
    """Crank torque T = r F sin(θ+β)/cos β, N·m, from a piston force F (N) towards the crank.

    Equal to −F dS/dθ (virtual work), which is how :mod:`fetorsion.mechanics.planetary` computes it
    for mechanisms without a closed form.
    """
    return r * pin_forces(theta, force, r, l)["tangential"]


@dataclass
class KinematicsResult:
    """Slider-crank motion over crank angle, exact and second-order series.

    Attributes
    ----------
    crank_radius_m, rod_length_m, omega_rad_s : float
        The mechanism and its constant speed.
    theta_rad : ndarray
        Crank angle from TDC, rad.
    position_m, velocity_m_s, acceleration_m_s2 : ndarray
        Exact S, Ṡ, S̈ (m, m/s, m/s²).
    position_series_m, velocity_series_m_s, acceleration_series_m_s2 : ndarray
        Their second-order series.
    rod_angle_rad, rod_angular_velocity_rad_s, rod_angular_acceleration_rad_s2 : ndarray
        Exact β, β̇, β̈.
    """

    crank_radius_m: float
    rod_length_m: float
    omega_rad_s: float
    theta_rad: np.ndarray
    position_m: np.ndarray
    velocity_m_s: np.ndarray
    acceleration_m_s2: np.ndarray
    position_series_m: np.ndarray
    velocity_series_m_s: np.ndarray
    acceleration_series_m_s2: np.ndarray
    rod_angle_rad: np.ndarray
    rod_angular_velocity_rad_s: np.ndarray
    rod_angular_acceleration_rad_s2: np.ndarray
    name: str = ""
    inputs: dict = field(default_factory=dict)

    @property
    def crank_ratio(self) -> float:
        return self.crank_radius_m / self.rod_length_m

    def to_dict(self) -> dict:
        """Plain JSON-ready dict (SI units in the key names)."""
        out = {"name": self.name, "crank_ratio": self.crank_ratio, **self.inputs}
        for key, value in self.__dict__.items():
            if key in ("name", "inputs"):
                continue
            out[key] = value.tolist() if isinstance(value, np.ndarray) else value
        return out

    def table(self) -> str:
        """Exact and series piston motion at each crank angle of the result."""
        top = self.crank_radius_m + self.rod_length_m
        head = (f"{'θ [deg]':>8} {'X [mm]':>9} {'X ser':>9} {'v [m/s]':>9} {'v ser':>9} {'a [m/s²]':>10} "
                f"{'a ser':>10} {'β [deg]':>8} {'β̇ [rad/s]':>10}")
        lines = [f"{self.name}: slider crank r = {1e3 * self.crank_radius_m:g} mm, l = {1e3 * self.rod_length_m:g} mm, "
                 f"λ = {self.crank_ratio:.4f}, {self.omega_rad_s * 30 / np.pi:g} rpm (X from TDC, v and a towards "
                 "the head)", head, "-" * len(head)]
        for i, t in enumerate(self.theta_rad):
            lines.append(f"{np.degrees(t):8.1f} {1e3 * (top - self.position_m[i]):9.3f} "
                         f"{1e3 * (top - self.position_series_m[i]):9.3f} {self.velocity_m_s[i]:9.3f} "
                         f"{self.velocity_series_m_s[i]:9.3f} {self.acceleration_m_s2[i]:10.1f} "
                         f"{self.acceleration_series_m_s2[i]:10.1f} {np.degrees(self.rod_angle_rad[i]):8.3f} "
                         f"{self.rod_angular_velocity_rad_s[i]:10.3f}")
        return "\n".join(lines)

    def plot(self, ax=None):
        """Position from TDC, velocity and acceleration, exact (lines) and series (dashed).

        On a given ``ax`` only the position is drawn; without one, a figure with all three.
        Returns the Axes of the position.
        """
        import matplotlib.pyplot as plt

        if ax is None:
            fig = plt.figure(figsize=(8, 7))
            axes = fig.subplots(3, 1, sharex=True)
        else:
            fig, axes = ax.figure, [ax]
        deg = np.degrees(self.theta_rad)
        top = self.crank_radius_m + self.rod_length_m
        rows = (("displacement from TDC [mm]", 1e3, top - self.position_m, top - self.position_series_m),
                ("velocity [m/s]", 1.0, self.velocity_m_s, self.velocity_series_m_s),
                ("acceleration [m/s²]", 1.0, self.acceleration_m_s2, self.acceleration_series_m_s2))
        for a, (label, scale, exact, series) in zip(axes, rows):
            a.plot(deg, scale * exact, label="exact")
            a.plot(deg, scale * series, "--", label="second-order series")
            a.set_ylabel(label)
            a.grid(alpha=0.3)
        axes[0].legend(fontsize=8)
        axes[-1].set_xlabel("crank angle from TDC [deg]")
        axes[0].set_title(f"{self.name}: r = {1e3 * self.crank_radius_m:g} mm, l = {1e3 * self.rod_length_m:g} mm, "
                          f"λ = {self.crank_ratio:.3f}, {self.omega_rad_s * 30 / np.pi:g} rpm", wrap=True)
        fig.tight_layout()
        return axes[0]


def kinematics(theta, r, l, omega, name: str = "") -> KinematicsResult:
    """Exact and series slider-crank motion at the crank angles ``theta`` and the crank speed
    ``omega`` (rad/s); θ, r and l as the module's conventions.

    Parameters
    ----------
    name : str
        Label for tables and plots.

    Returns
    -------
    KinematicsResult

    Examples
    --------
    >>> res = kinematics(np.radians([0.0, 90.0, 180.0]), 0.0425, 0.1345, 600.0)
    >>> np.round(res.position_m - res.position_series_m, 9).tolist()[::2]   # exact at TDC and BDC
    [0.0, 0.0]
    """
    theta = np.asarray(theta, dtype=float)
    return KinematicsResult(
        r, l, omega, theta,
        piston_position(theta, r, l), piston_velocity(theta, r, l, omega), piston_acceleration(theta, r, l, omega),
        piston_position_series(theta, r, l), piston_velocity_series(theta, r, l, omega),
        piston_acceleration_series(theta, r, l, omega),
        rod_angle(theta, r, l), rod_angular_velocity(theta, r, l, omega), rod_angular_acceleration(theta, r, l, omega),
        name,
    )
