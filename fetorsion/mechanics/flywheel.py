"""Flywheel sizing ([Asgari] §3): rim-speed and diameter checks, and the energy method.

Checks ([Asgari] eq. 14–18)::

    rim speed  v = π D n / 60       within 25–30 m/s (cast iron) or 40–45 m/s (steel)
    mean diameter D_r = (D_max + D_min)/2 with 2S ≤ D_r ≤ 3S      (S the stroke)
    inertia ratio 0.8 ≤ I_F / I_T ≤ 0.9

Energy method (eq. 19–31) for the paper's triangular torque: n = N/2 working cycles per
minute (4-stroke), W = P·60/n per cycle, W_E = 3W/2 (compression takes back W_E/3),
T_max = 2W_E/π (a triangle over the π of the expansion stroke), T_mean = W/(4π),
T_ex = T_max − T_mean, ΔE = ½ T_ex (T_ex/T_max) π, I = ΔE/(C_s ω²),
C_s = 2(N1 − N2)/(N1 + N2), M = 2I/(R1² + R2²).

For any torque curve T(θ) over one cycle, :func:`fluctuation_energy` integrates
E(θ) = ∫(T − T_mean) dθ and returns max E − min E; with :func:`triangular_torque` (the
triangle plus the compression triangle that makes the mean W/(4π)) it gives the ΔE above
exactly, and it takes a real cylinder torque (e.g. from
:func:`fetorsion.excitation.kinematics.tangential_torque`) unchanged.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "RIM_SPEED_LIMITS", "FlywheelSizing", "check_inertia_ratio", "check_mean_diameter", "check_rim_speed",
    "cycle_work", "flywheel_inertia", "flywheel_mass", "fluctuation_energy", "rim_speed", "size_flywheel",
    "speed_fluctuation_coefficient", "triangular_torque",
]

FOUR_STROKE = 4  # strokes per cycle of the engines these sizings assume unless told
RIM_SPEED_LIMITS = {"cast_iron": (25.0, 30.0), "steel": (40.0, 45.0)}   # m/s, [Asgari] eq. 14


def rim_speed(diameter, speed_rpm):
    """v = π D n / 60, m/s ([Asgari] eq. 15).

    Parameters
    ----------
    diameter : float
        Outer diameter, m.
    speed_rpm : float
        Speed, rev/min.

    Examples
    --------
    >>> round(rim_speed(0.27, 3000.0), 2)     # B112; the paper prints 42.23
    42.41
    """
    return np.pi * diameter * speed_rpm / 60.0


def check_rim_speed(diameter, speed_rpm, material):
    """(v in m/s, (low, high) limits, within?) for ``material`` in :data:`RIM_SPEED_LIMITS`."""
    v = rim_speed(diameter, speed_rpm)
    lo, hi = RIM_SPEED_LIMITS[material]
    return v, (lo, hi), bool(lo <= v <= hi)


def check_mean_diameter(d_outer, d_inner, stroke):
    """(D_r = (D_max + D_min)/2 in m, (2S, 3S), within?) ([Asgari] eq. 16–17)."""
    d = 0.5 * (d_outer + d_inner)
    return d, (2 * stroke, 3 * stroke), bool(2 * stroke <= d <= 3 * stroke)


def check_inertia_ratio(i_flywheel, i_rest):
    """(I_F / I_T, (0.8, 0.9), within?) with I_T the other rotating parts ([Asgari] eq. 18)."""
    q = i_flywheel / i_rest
    return q, (0.8, 0.9), bool(0.8 <= q <= 0.9)


def speed_fluctuation_coefficient(n_max, n_min):
    """C_s = 2(N1 − N2)/(N1 + N2) ([Asgari] eq. 19); ±2 % about the mean gives 0.04."""
    return 2.0 * (n_max - n_min) / (n_max + n_min)


def cycle_work(power, speed_rpm, strokes=FOUR_STROKE):
    """Work per cycle W = P·60/n, J, with n = N/2 cycles per minute for a 4-stroke, N for a 2-stroke."""
    cycles_per_min = speed_rpm / 2.0 if strokes == 4 else speed_rpm
    return power * 60.0 / cycles_per_min


def flywheel_inertia(delta_e, cs, omega):
    """I = ΔE/(C_s ω²), kg·m² ([Asgari] eq. 30); ΔE in J, ω in rad/s."""
    return delta_e / (cs * omega**2)


def flywheel_mass(inertia, r_outer, r_inner):
    """Annulus mass M = 2I/(R1² + R2²), kg ([Asgari] eq. 31); radii in m."""
    return 2.0 * inertia / (r_outer**2 + r_inner**2)


def triangular_torque(theta, work_expansion, compression_share=1.0 / 3.0, cycle=4 * np.pi):
    """The paper's torque model over one cycle, N·m.

    A triangle of area W_E over the expansion stroke θ ∈ [0, π] (peak T_max = 2W_E/π at
    π/2) and, so that the cycle work is W = W_E(1 − share), a negative triangle of area
    share·W_E over the compression stroke [cycle − π, cycle]; zero elsewhere.

    Parameters
    ----------
    theta : array_like
        Crank angle from firing TDC, rad (wrapped into one cycle).
    work_expansion : float
        W_E, J.
    compression_share : float
        W_C / W_E ([Asgari] eq. 23: 1/3).
    cycle : float
        Cycle length, rad (4π for a 4-stroke).
    """
    t = np.mod(np.asarray(theta, dtype=float), cycle)
    tri = lambda x: np.clip(1.0 - np.abs(x - np.pi / 2) / (np.pi / 2), 0.0, None)  # noqa: E731
    peak = 2.0 * work_expansion / np.pi
    return peak * (tri(t) - compression_share * tri(t - (cycle - np.pi)))


def fluctuation_energy(theta, torque):
    """Largest swing of kinetic energy over one cycle, ΔE = max E − min E, J.

    Parameters
    ----------
    theta : array_like
        Increasing crank angles covering exactly one cycle (first to last point), rad.
    torque : array_like
        Crank torque at those angles, N·m (any curve: triangle, real cylinder torque).

    Returns
    -------
    delta_e, mean_torque : float
        J and N·m.

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 20001)
    >>> round(fluctuation_energy(th, 10 + np.sin(th))[0], 6)      # ∫ sin over half a turn = 2
    2.0
    """
    theta = np.asarray(theta, dtype=float)
    torque = np.asarray(torque, dtype=float)
    mean = np.trapezoid(torque, theta) / (theta[-1] - theta[0])
    dev = torque - mean
    e = np.concatenate([[0.0], np.cumsum(0.5 * (dev[1:] + dev[:-1]) * np.diff(theta))])
    return float(e.max() - e.min()), float(mean)


@dataclass
class FlywheelSizing:
    """Flywheel sizing by [Asgari]'s energy method, with its checks.

    Attributes
    ----------
    power_w, speed_rpm, speed_fluctuation : float
        Inputs P, N and C_s.
    cycle_work_j, expansion_work_j, torque_max_nm, torque_mean_nm, torque_excess_nm : float
        W, W_E, T_max, T_mean, T_ex of the triangular torque.
    delta_e_j : float
        Fluctuation energy ΔE (closed form, eq. 29).
    delta_e_curve_j : float
        ΔE integrated from the triangular torque curve (equals ``delta_e_j``).
    inertia_kgm2 : float
        I = ΔE/(C_s ω²).
    mass_kg : float or None
        M = 2I/(R1² + R2²) when the diameters are given.
    checks : dict
        Rim speed, mean diameter and inertia ratio checks that the inputs allow.
    """

    power_w: float
    speed_rpm: float
    speed_fluctuation: float
    cycle_work_j: float
    expansion_work_j: float
    torque_max_nm: float
    torque_mean_nm: float
    torque_excess_nm: float
    delta_e_j: float
    delta_e_curve_j: float
    inertia_kgm2: float
    mass_kg: float | None = None
    mass_at_rounded_inertia_kg: float | None = None
    checks: dict = field(default_factory=dict)
    name: str = ""

    def to_dict(self) -> dict:
        return dict(self.__dict__)

    def table(self) -> str:
        """The sizing's numbers and checks, one per line."""
        rows = [("work per cycle W [J]", self.cycle_work_j), ("expansion work W_E [J]", self.expansion_work_j),
                ("T_max [N·m]", self.torque_max_nm), ("T_mean [N·m]", self.torque_mean_nm), ("T_ex [N·m]", self.torque_excess_nm),
                ("ΔE closed form [J]", self.delta_e_j), ("ΔE from the torque curve [J]", self.delta_e_curve_j),
                (f"I = ΔE/(C_s ω²), C_s = {self.speed_fluctuation:g} [kg·m²]", self.inertia_kgm2)]
        if self.mass_kg is not None:
            rows += [("mass 2I/(R1² + R2²) [kg]", self.mass_kg), ("mass with I rounded to 2 digits [kg]", self.mass_at_rounded_inertia_kg)]
        lines = [f"{self.name}: flywheel, {self.power_w / 1e3:g} kW at {self.speed_rpm:g} rpm ([Asgari] energy method)"]
        lines += [f"  {label:<48} {value:12.4f}" for label, value in rows]
        for key, c in self.checks.items():
            vals = list(c.values())
            lines.append(f"  check {key:<42} {vals[0]:12.4f}  limits {vals[1][0]:g}–{vals[1][1]:g}  {'ok' if vals[2] else 'OUTSIDE'}")
        return "\n".join(lines)

    def plot(self, ax=None, n=2001):
        """Triangular torque over the cycle with its mean and the ΔE area; returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4))
        th = np.linspace(0.0, 4 * np.pi, n)
        t = triangular_torque(th, self.expansion_work_j)
        ax.plot(np.degrees(th), t, label="triangular torque ([Asgari] fig. 7)")
        ax.axhline(self.torque_mean_nm, color="k", ls="--", lw=0.8, label=f"T_mean = {self.torque_mean_nm:.1f} N·m")
        ax.fill_between(np.degrees(th), self.torque_mean_nm, t, where=t > self.torque_mean_nm, alpha=0.3,
                        label=f"ΔE = {self.delta_e_j:.1f} J")
        ax.set_xlabel("crank angle from firing TDC [deg]")
        ax.set_ylabel("torque [N·m]")
        ax.set_title(f"{self.name}: I = {self.inertia_kgm2:.4f} kg·m² at C_s = {self.speed_fluctuation:g}", wrap=True)
        ax.legend(fontsize=8)
        ax.figure.tight_layout()
        return ax


def size_flywheel(power, speed_rpm, speed_fluctuation, d_outer=None, d_inner=None, stroke=None,
                  material=None, i_rest=None, strokes=FOUR_STROKE, name="") -> FlywheelSizing:
    """[Asgari]'s flywheel sizing from power and speed.

    Parameters
    ----------
    power : float
        Engine power P, W.
    speed_rpm : float
        Mean speed N, rev/min.
    speed_fluctuation : float
        C_s (e.g. 0.04 for ±2 %).
    d_outer, d_inner : float, optional
        Flywheel outer and inner diameters, m (mass and diameter checks).
    stroke : float, optional
        Piston stroke S, m (mean-diameter check).
    material : {"cast_iron", "steel"}, optional
        Rim-speed limits.
    i_rest : float, optional
        Inertia of the other rotating parts I_T, kg·m² (inertia-ratio check).
    strokes : int
        4 or 2.

    Examples
    --------
    >>> s = size_flywheel(7000.0, 3000.0, 0.04, 0.27, 0.21)     # B112, [Asgari]
    >>> round(s.inertia_kgm2, 2), round(s.mass_at_rounded_inertia_kg, 2)
    (0.09, 6.15)
    """
    w = cycle_work(power, speed_rpm, strokes)
    w_e = 1.5 * w
    t_max = 2.0 * w_e / np.pi
    t_mean = w / (2.0 * np.pi * strokes / 2)
    t_ex = t_max - t_mean
    de = 0.5 * t_ex * (t_ex / t_max) * np.pi
    cycle = 2 * np.pi * strokes / 2
    th = np.linspace(0.0, cycle, 40001)
    de_curve, _ = fluctuation_energy(th, triangular_torque(th, w_e, cycle=cycle))
    omega = speed_rpm * np.pi / 30.0
    inertia = flywheel_inertia(de, speed_fluctuation, omega)
    checks = {}
    mass = mass_rounded = None
    if d_outer is not None and d_inner is not None:
        mass = flywheel_mass(inertia, d_outer / 2, d_inner / 2)
        # The paper rounds I to two digits before eq. 31; kept to compare with its 6.15 kg.
        mass_rounded = flywheel_mass(float(np.round(inertia, 2)), d_outer / 2, d_inner / 2)
        if stroke is not None:
            checks["mean_diameter"] = dict(zip(("value_m", "limits_m", "ok"), check_mean_diameter(d_outer, d_inner, stroke)))
    if d_outer is not None and material is not None:
        checks["rim_speed"] = dict(zip(("value_m_s", "limits_m_s", "ok"), check_rim_speed(d_outer, speed_rpm, material)))
    if i_rest is not None:
        checks["inertia_ratio"] = dict(zip(("value", "limits", "ok"), check_inertia_ratio(inertia, i_rest)))
    return FlywheelSizing(power, speed_rpm, speed_fluctuation, w, w_e, t_max, t_mean, t_ex, de, de_curve,
                          inertia, mass, mass_rounded, checks, name)
