"""Single-cylinder balancing: rod split, shaking forces, counterweights, balance shafts,
over-balancing with an advanced counterweight ([Asgari] and [Wang]).

Masses and forces
-----------------
Two-mass rod ([Asgari] eq. 2–5): the rod mass m_rod is split between the big end (crank
pin) and the small end (piston pin) so that the centroid stays put::

    m_big + m_small = m_rod,   m_big h_big = m_small h_small
    m_big = m_rod h_small/(h_big + h_small),   m_small = m_rod h_big/(h_big + h_small)

with h_big, h_small the distances of the rod centroid from the big- and small-end eye
centres. ([Asgari]'s printed eq. 4–5 swap the numerators; its numbers use the form above.)
The crank's own unbalance (mass m_crank, centroid at radius r_g) is moved to the pin
radius r: m_crank r_g / r (eq. 6). Then m1 = m_piston + m_small reciprocates and
m2 = m_crank r_g/r + m_big rotates (eq. 10–11).

The inertia force on the frame along the cylinder axis (towards the head positive) is
−m1 S̈ ≈ m1 r ω² (cos θ + λ cos 2θ): primary m1 r ω² cos θ, secondary m1 r ω² λ cos 2θ
([Asgari] eq. 7–8 give the same with the opposite sign, i.e. m1 S̈). The rotating mass
adds m2 r ω² along the crank.

Counterweights and balance shafts
---------------------------------
[Asgari]: a counterweight opposite the pin balances M = c m1 + m2 (eq. 9); at radius b it
has mass B = M r / b (eq. 12). One shaft counter-rotating at crank speed with
M_shaft r_shaft = (1 − c) r m1 (eq. 13) takes the rest of the primary force along the axis;
with c = ½ the primary force vanishes in the plane.

[Wang]: two shafts at ω, counter-rotating, each m_b r_b = ½ m_j r, cancel the primary
force exactly; two more at 2ω with m_c r_c = (λ/8) m_j r cancel the secondary (each pair
adds 2 m r (nω)² along the axis and cancels across it). :class:`BalanceShaft` describes
any such shaft; :func:`shaft_forces` sums them.

Over-balancing ([Wang] §3–4)
------------------------------
A counterweight m_b r_b = k m_j r advanced by α, in units of J = m_j r ω²::

    P_x/J = (cos θ + λ cos 2θ) − k cos(θ + α),   P_y/J = −k sin(θ + α)        (37, 38)

Primary only (λ = 0) the locus is an ellipse with P_max = (1 + √(1 − 4k cos α + 4k²)) J/2
(eq. 32), smallest, (1 + |sin α|) J/2, at k = cos α / 2 (eq. 36). With the secondary force
:func:`minmax_overbalance` minimises P_max over (k, α): a grid start, then a semi-infinite
(epigraph) SLSQP problem whose constraint set is refreshed with the exact peaks of P(θ).
P(θ; k, −α) = P(−θ; k, α), so α ≥ 0 loses nothing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# re-exported (__all__): callers read the whole single-cylinder analysis from balance (bal.rod_split)
from .masses import counterweight_mass, crank_equivalent_mass, primary_shaft_mass, rod_split, unbalanced_mass

#: Points of a residual-force locus over one revolution (every half degree, both ends).
LOCUS_POINTS = 721
#: Refinement rounds of the min-max overbalance search, each on a grid around the last best.
MINMAX_ROUNDS = 4

__all__ = [
    "BalanceShaft", "CrankMasses", "MinMaxResult", "ResidualLocus", "counterweight_mass",
    "crank_equivalent_mass", "ellipse_orientation", "ellipse_pmax", "four_shaft_arrangement",
    "grid_minmax", "minmax_overbalance", "primary_shaft_mass", "residual_force", "residual_locus",
    "residual_peaks", "rod_split", "shaft_forces", "shaking_forces", "two_shaft_arrangement",
    "unbalanced_mass",
]


# ---------------------------------------------------------------------------
# Masses and forces ([Asgari]; the masses themselves: :mod:`.masses`)


@dataclass(frozen=True)
class CrankMasses:
    """Reciprocating and rotating masses of a single-cylinder crank train (SI).

    Attributes
    ----------
    rod_big_end_kg, rod_small_end_kg : float
        Two-mass rod split.
    crank_at_pin_kg : float
        Crank unbalance moved to the pin radius.
    reciprocating_kg, rotating_kg : float
        m1 = piston + small end, m2 = crank at pin + big end.
    """

    rod_big_end_kg: float
    rod_small_end_kg: float
    crank_at_pin_kg: float
    reciprocating_kg: float
    rotating_kg: float

    @classmethod
    def from_parts(cls, m_rod, h_big, h_small, m_piston, m_crank, r_centroid, r):
        """Build from the part masses (kg) and lengths (m) of [Asgari] §2."""
        big, small = rod_split(m_rod, h_big, h_small)
        crank = crank_equivalent_mass(m_crank, r_centroid, r)
        return cls(big, small, crank, m_piston + small, crank + big)


def shaking_forces(theta, m_rec, m_rot, r, l, omega):
    """Inertia forces on the frame versus crank angle, N.

    Parameters
    ----------
    theta : array_like
        Crank angle from TDC, rad.
    m_rec, m_rot : float
        Reciprocating and rotating masses, kg.
    r, l : float
        Crank radius and rod length, m.
    omega : float
        Crank speed, rad/s.

    Returns
    -------
    dict of ndarray
        ``primary`` m1 r ω² cos θ and ``secondary`` m1 r ω² λ cos 2θ along the cylinder axis
        (towards the head positive); ``rotating_x``, ``rotating_y``: m2 r ω² (cos θ, sin θ).
    """
    theta = np.asarray(theta, dtype=float)
    j = m_rec * r * omega**2
    return {
        "primary": j * np.cos(theta),
        "secondary": j * (r / l) * np.cos(2 * theta),
        "rotating_x": m_rot * r * omega**2 * np.cos(theta),
        "rotating_y": m_rot * r * omega**2 * np.sin(theta),
    }


@dataclass(frozen=True)
class BalanceShaft:
    """An unbalanced mass turning at ``order`` × crank speed.

    Attributes
    ----------
    mass_radius_kgm : float
        m r of the shaft unbalance, kg·m.
    order : float
        Speed ratio to the crank (1 primary, 2 secondary).
    sense : int
        +1 turns with the crank, −1 against it.
    phase_rad : float
        Angle of the mass from the cylinder axis when θ = 0, rad.
    """

    mass_radius_kgm: float
    order: float = 1.0
    sense: int = -1
    phase_rad: float = np.pi


def shaft_forces(theta, shafts, omega):
    """Sum of the centrifugal forces of ``shafts`` on the frame, (F_x, F_y) in N.

    The mass of shaft i is at angle sense·order·θ + phase; x is the cylinder axis.
    """
    theta = np.asarray(theta, dtype=float)
    fx, fy = np.zeros_like(theta), np.zeros_like(theta)
    for s in shafts:   # a handful of shafts, each vectorised over θ
        ang = s.sense * s.order * theta + s.phase_rad
        amp = s.mass_radius_kgm * (s.order * omega) ** 2
        fx = fx + amp * np.cos(ang)
        fy = fy + amp * np.sin(ang)
    return fx, fy


def two_shaft_arrangement(m_rec, r):
    """[Wang] §2.1: two shafts at ω turning opposite ways, each m_b r_b = ½ m_j r."""
    half = 0.5 * m_rec * r
    return [BalanceShaft(half, 1.0, +1, np.pi), BalanceShaft(half, 1.0, -1, np.pi)]


def four_shaft_arrangement(m_rec, r, lam):
    """[Wang] §2.2: :func:`two_shaft_arrangement` plus two shafts at 2ω, each m_c r_c = (λ/8) m_j r."""
    sec = lam / 8 * m_rec * r
    return two_shaft_arrangement(m_rec, r) + [BalanceShaft(sec, 2.0, +1, np.pi), BalanceShaft(sec, 2.0, -1, np.pi)]


# ---------------------------------------------------------------------------
# Over-balancing with an advanced counterweight ([Wang])


def residual_force(theta, k, alpha, lam):
    """Residual force (P_x, P_y)/J of [Wang] eq. 37–38, dimensionless.

    Parameters
    ----------
    theta : array_like
        Crank angle from TDC, rad.
    k : array_like
        Counterweight m_b r_b / (m_j r).
    alpha : array_like
        Counterweight advance, rad.
    lam : float
        λ = r / l; 0 keeps the primary force only.

    All arguments broadcast.
    """
    c = np.cos(theta) + lam * np.cos(2 * theta)
    return c - k * np.cos(theta + alpha), -k * np.sin(theta + alpha)


def ellipse_pmax(k, alpha):
    """P_max / J of the primary-only locus, (1 + √(1 − 4k cos α + 4k²))/2 ([Wang] eq. 32).

    Examples
    --------
    >>> [round(float(ellipse_pmax(k, 0.0)), 12) for k in (0.5, 0.3, 0.8)]   # J/2, (1 − k)J, kJ
    [0.5, 0.7, 0.8]
    """
    return 0.5 * (1.0 + np.sqrt(1.0 - 4.0 * k * np.cos(alpha) + 4.0 * k**2))


def ellipse_orientation(k, alpha):
    """Direction φ of the primary-only ellipse's major axis from the cylinder axis, rad, in (−π/2, π/2].

    P_x + i P_y = J[(1/2 − k e^{iα}) e^{iθ} + e^{−iθ}/2]: the two counter-rotating terms line
    up at tan 2φ = 2k sin α / (2k cos α − 1), the branch chosen by the sign of the
    denominator as in [Wang] eq. 33–35 (φ = ±π/4 when 2k cos α = 1).
    """
    phi = -0.5 * np.arctan2(2 * k * np.sin(alpha), 1.0 - 2 * k * np.cos(alpha))
    return np.where(phi <= -np.pi / 2, phi + np.pi, np.where(phi > np.pi / 2, phi - np.pi, phi))


def _p2_and_derivatives(theta, k, alpha, lam):
    """(P/J)² and its first two θ-derivatives (P² is a trigonometric polynomial of degree 4)."""
    a = theta + alpha
    u = np.cos(theta) + lam * np.cos(2 * theta) - k * np.cos(a)
    v = -k * np.sin(a)
    du = -np.sin(theta) - 2 * lam * np.sin(2 * theta) + k * np.sin(a)
    dv = -k * np.cos(a)
    ddu = -np.cos(theta) - 4 * lam * np.cos(2 * theta) + k * np.cos(a)
    ddv = k * np.sin(a)
    return u * u + v * v, 2 * (u * du + v * dv), 2 * (du * du + u * ddu + dv * dv + v * ddv)


def residual_peaks(k, alpha, lam, n_theta=720, newton_steps=4):
    """All local maxima of P(θ)/J over a revolution, refined by Newton steps on dP²/dθ = 0.

    Parameters
    ----------
    k, alpha : float
        Counterweight ratio and advance (rad).
    lam : float
        λ = r / l.
    n_theta : int
        Grid points over 2π used to bracket the peaks.
    newton_steps : int
        Newton iterations from each grid peak (each step is kept within one grid spacing).

    Returns
    -------
    theta, p : ndarray
        Peak crank angles in [0, 2π) and P/J there, largest first.
    """
    h = 2 * np.pi / n_theta
    grid = np.arange(n_theta) * h
    p2 = _p2_and_derivatives(grid, k, alpha, lam)[0]
    idx = np.flatnonzero((p2 >= np.roll(p2, 1)) & (p2 > np.roll(p2, -1)))
    t = grid[idx]
    for _ in range(newton_steps):
        _, d1, d2 = _p2_and_derivatives(t, k, alpha, lam)
        step = np.where(d2 < 0, -d1 / np.where(d2 < 0, d2, -1.0), 0.0)
        t = t + np.clip(step, -h, h)
    p = np.sqrt(_p2_and_derivatives(t, k, alpha, lam)[0])
    order = np.argsort(-p)
    return np.mod(t[order], 2 * np.pi), p[order]


def _pmax_grid(k, alpha, lam, n_theta):
    """max over a θ grid of P/J for arrays of (k, α) (broadcast), dimensionless."""
    theta = np.linspace(0.0, 2 * np.pi, n_theta, endpoint=False)
    k = np.asarray(k, dtype=float)[..., None]
    alpha = np.asarray(alpha, dtype=float)[..., None]
    px, py = residual_force(theta, k, alpha, lam)
    return np.sqrt((px * px + py * py).max(axis=-1))


@dataclass
class ResidualLocus:
    """The residual-force locus of an over-balanced single cylinder over one revolution.

    Attributes
    ----------
    lam, k, alpha_rad : float
        λ, counterweight ratio m_b r_b/(m_j r) and advance.
    theta_rad : ndarray
        Crank angles, rad.
    px, py : ndarray
        Residual force / J along and across the cylinder axis.
    p_max : float
        max over θ of P / J (refined peak).
    theta_max_rad, phi_max_rad : float
        Crank angle of the peak and direction of the force there ([Wang] eq. 40:
        arctan(P_y/P_x), in (−90°, 90°]).
    j_newton : float or None
        J = m_j r ω² in N when the masses and speed are known, else None.
    """

    lam: float
    k: float
    alpha_rad: float
    theta_rad: np.ndarray
    px: np.ndarray
    py: np.ndarray
    p_max: float
    theta_max_rad: float
    phi_max_rad: float
    j_newton: float | None = None
    name: str = ""

    def to_dict(self) -> dict:
        """Plain JSON-ready dict; forces are in units of J (and N when ``j_newton`` is set)."""
        out = {"name": self.name, "lambda": self.lam, "k": self.k, "alpha_deg": float(np.degrees(self.alpha_rad)),
               "p_max_over_j": self.p_max, "theta_max_deg": float(np.degrees(self.theta_max_rad)),
               "phi_max_deg": float(np.degrees(self.phi_max_rad)), "j_n": self.j_newton,
               "theta_deg": np.degrees(self.theta_rad).tolist(), "px_over_j": self.px.tolist(),
               "py_over_j": self.py.tolist()}
        if self.j_newton is not None:
            out["p_max_n"] = self.p_max * self.j_newton
        return out

    def table(self) -> str:
        """The counterweight and the largest residual force it leaves."""
        force = f" = {self.p_max * self.j_newton:.1f} N" if self.j_newton is not None else ""
        return (f"{self.name or 'residual force'}: λ = {self.lam:g}, k = {self.k:.4f}, α = "
                f"{np.degrees(self.alpha_rad):.3f}°: P_max = {self.p_max:.4f} J{force} at θ = "
                f"{np.degrees(self.theta_max_rad):.1f}°, φ = {np.degrees(self.phi_max_rad):.2f}°")

    def plot(self, ax=None, label=None):
        """The locus (P_x, P_y)/J with its peak marked; returns the matplotlib Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 5.5))
        tag = label or f"λ = {self.lam:g}, k = {self.k:.3f}, α = {np.degrees(self.alpha_rad):.2f}°"
        line, = ax.plot(self.px, self.py, label=f"{tag}: P_max = {self.p_max:.4f} J")
        pk = self.p_max * np.array([np.cos(self.phi_max_rad), np.sin(self.phi_max_rad)])
        pk = pk * np.sign(np.interp(self.theta_max_rad, self.theta_rad, self.px) or 1.0)
        ax.plot([0, pk[0]], [0, pk[1]], ":", color=line.get_color())
        ax.plot(*pk, "o", color=line.get_color())
        ax.set_aspect("equal")
        ax.axhline(0, color="0.7", lw=0.6)
        ax.axvline(0, color="0.7", lw=0.6)
        ax.set_xlabel("P_x / J  (cylinder axis)")
        ax.set_ylabel("P_y / J")
        ax.set_title("residual inertia force locus ([Wang] eq. 37–38)")
        ax.legend(fontsize=7, loc="lower left")
        return ax


def residual_locus(k, alpha, lam, n_theta=LOCUS_POINTS, j_newton=None, name="") -> ResidualLocus:
    """Residual-force locus over one revolution and its maximum.

    Parameters
    ----------
    k : float
        m_b r_b / (m_j r).
    alpha : float
        Counterweight advance, rad.
    lam : float
        λ = r / l (0 for the primary force alone).
    n_theta : int
        Samples of the returned locus (the maximum is refined independently of it).
    j_newton : float, optional
        J = m_j r ω², N, to report forces in N too.

    Examples
    --------
    >>> loc = residual_locus(0.6, np.radians(5.0), 0.20)   # [Wang] Table 1 row λ = 0.20
    >>> round(loc.p_max, 4), round(float(np.degrees(loc.theta_max_rad)), 1)  # peak past 180°
    (0.6758, 255.4)
    """
    theta = np.linspace(0.0, 2 * np.pi, n_theta)
    px, py = residual_force(theta, k, alpha, lam)
    t_pk, p_pk = residual_peaks(k, alpha, lam)
    qx, qy = residual_force(t_pk[0], k, alpha, lam)
    phi = float(np.arctan(qy / qx)) if qx != 0 else np.pi / 2
    return ResidualLocus(lam, float(k), float(alpha), theta, px, py, float(p_pk[0]), float(t_pk[0]), phi,
                         j_newton, name)


@dataclass
class MinMaxResult:
    """The (k, α) that minimise the largest residual force over a revolution.

    Attributes
    ----------
    lam, k, alpha_rad, p_max : float
        λ, the optimum and (P_max)_min / J.
    peaks_theta_rad, peaks_phi_rad, peaks_p : ndarray
        The active peaks at the optimum (within ``tol`` of P_max): at a min–max optimum
        several crank angles share the largest force, so θ0 and φ0 are not unique.
    grid_k, grid_alpha_rad, grid_p_max : float
        The best point of the starting grid and its P_max / J.
    """

    lam: float
    k: float
    alpha_rad: float
    p_max: float
    peaks_theta_rad: np.ndarray
    peaks_phi_rad: np.ndarray
    peaks_p: np.ndarray
    grid_k: float
    grid_alpha_rad: float
    grid_p_max: float

    def to_dict(self) -> dict:
        return {"lambda": self.lam, "k": self.k, "alpha_deg": float(np.degrees(self.alpha_rad)),
                "p_max_over_j": self.p_max, "peaks_theta_deg": np.degrees(self.peaks_theta_rad).tolist(),
                "peaks_phi_deg": np.degrees(self.peaks_phi_rad).tolist(), "peaks_p_over_j": self.peaks_p.tolist(),
                "grid_k": self.grid_k, "grid_alpha_deg": float(np.degrees(self.grid_alpha_rad)),
                "grid_p_max_over_j": self.grid_p_max}

    def locus(self, n_theta=LOCUS_POINTS) -> ResidualLocus:
        return residual_locus(self.k, self.alpha_rad, self.lam, n_theta)

    def table(self) -> str:
        """The optimum and its active peaks."""
        peaks = ", ".join(f"θ {t:.1f}° φ {p:.1f}°" for t, p in zip(np.degrees(self.peaks_theta_rad),
                                                                 np.degrees(self.peaks_phi_rad)))
        return (f"over-balancing min–max, λ = {self.lam:g}: k = {self.k:.4f}, α = {np.degrees(self.alpha_rad):.3f}°, "
                f"P_max = {self.p_max:.4f} J (peaks: {peaks})")

    def plot(self, ax=None):
        """The optimum's residual-force locus; returns the Axes."""
        return self.locus().plot(ax, label="min–max")


def _pmax_exact(k, alpha, lam):
    return residual_peaks(k, alpha, lam)[1][0]


def minmax_overbalance(lam, k_range=(0.0, 1.5), alpha_range_deg=(0.0, 45.0), k_step=0.005,
                       alpha_step_deg=0.25, n_theta_grid=360, rounds=MINMAX_ROUNDS, tol=1e-6) -> MinMaxResult:
    """Minimise over (k, α) the largest residual force max_θ P(θ) of [Wang] eq. 37–39.

    Parameters
    ----------
    lam : float
        λ = r / l.
    k_range, alpha_range_deg : (float, float)
        Search box; α in degrees (α ≥ 0 suffices by symmetry).
    k_step, alpha_step_deg : float
        Starting-grid spacing.
    n_theta_grid : int
        θ samples per revolution on the starting grid.
    rounds : int
        Exchange rounds: each solves the epigraph problem min t s.t. P²(θ_i) ≤ t on a θ grid
        plus the current exact peaks, then adds the new exact peaks.
    tol : float
        Relative gap under which a peak counts as active.

    Returns
    -------
    MinMaxResult

    Examples
    --------
    >>> res = minmax_overbalance(0.0, k_step=0.01, alpha_step_deg=1.0)   # primary only: eq. 36
    >>> round(res.p_max, 6), round(res.k, 4), round(float(np.degrees(res.alpha_rad)), 3)
    (0.5, 0.5, 0.0)
    """
    ks = np.arange(k_range[0], k_range[1] + 0.5 * k_step, k_step)
    als = np.radians(np.arange(alpha_range_deg[0], alpha_range_deg[1] + 0.5 * alpha_step_deg, alpha_step_deg))
    # Row blocks keep the (k, α, θ) array near 10^7 numbers.
    block = max(1, int(1e7 // (len(ks) * n_theta_grid)))
    grid = np.concatenate([_pmax_grid(ks[None, :], als[i:i + block, None], lam, n_theta_grid)
                           for i in range(0, len(als), block)])
    ia, ik = np.unravel_index(np.argmin(grid), grid.shape)
    k0, a0 = ks[ik], als[ia]
    # Start the refinement from the exact max (the grid value can sit slightly below it).
    best = (k0, a0, _pmax_exact(k0, a0, lam))
    theta_fixed = np.linspace(0.0, 2 * np.pi, 1440, endpoint=False)
    extra = np.array([])
    scale = np.array([1.0, 1.0 / np.radians(1.0)])   # α in degrees inside the solver: balanced steps

    for _ in range(rounds):
        thetas = np.concatenate([theta_fixed, extra])

        def cons(z, thetas=thetas):
            k, a = z[0], z[1] / scale[1]
            return z[2] - _p2_and_derivatives(thetas, k, a, lam)[0]

        def cons_jac(z, thetas=thetas):
            k, a = z[0], z[1] / scale[1]
            ang = thetas + a
            u = np.cos(thetas) + lam * np.cos(2 * thetas) - k * np.cos(ang)
            v = -k * np.sin(ang)
            dk = 2 * (u * -np.cos(ang) + v * -np.sin(ang))
            da = 2 * (u * k * np.sin(ang) + v * -k * np.cos(ang)) / scale[1]
            return np.column_stack([-dk, -da, np.ones_like(thetas)])

        # imported here: scipy.optimize costs 0.27 s, and every CLI command imports this module
        from scipy.optimize import minimize

        z0 = np.array([best[0], best[1] * scale[1], best[2] ** 2])
        sol = minimize(lambda z: z[2], z0, jac=lambda z: np.array([0.0, 0.0, 1.0]), method="SLSQP",
                       constraints=[{"type": "ineq", "fun": cons, "jac": cons_jac}],
                       options={"maxiter": 200, "ftol": 1e-14})
        k1, a1 = float(sol.x[0]), float(sol.x[1] / scale[1])
        if a1 < 0:   # mirror image: same P_max
            a1 = -a1
        p1 = _pmax_exact(k1, a1, lam)
        if p1 < best[2]:
            best = (k1, a1, p1)
        extra = np.concatenate([extra, residual_peaks(k1, a1, lam)[0]])

    k, a, p = best
    t_pk, p_pk = residual_peaks(k, a, lam)
    active = p_pk >= p * (1 - tol)
    px, py = residual_force(t_pk[active], k, a, lam)
    phi = np.arctan(py / np.where(px == 0, 1e-300, px))
    return MinMaxResult(lam, float(k), float(a), float(p), t_pk[active], phi, p_pk[active],
                        float(k0), float(a0), float(grid[ia, ik]))


def grid_minmax(lam, k_values, alpha_values_deg, theta_values_deg):
    """Min–max of P/J by plain search on given grids, as [Wang] §4 (fig. 8) does it.

    Parameters
    ----------
    lam : float
        λ = r / l.
    k_values, alpha_values_deg, theta_values_deg : array_like
        The grids; [Wang] used k in steps of 0.1, α in steps of 5° and, as its Table 1
        shows, θ in whole degrees over half a revolution only (0°–180°).

    Returns
    -------
    dict
        ``p_max`` (P/J), ``k``, ``alpha_deg``, ``theta_deg`` and ``phi_deg`` (eq. 40,
        arctan(P_y/P_x)) at the grid optimum.

    Examples
    --------
    >>> g = grid_minmax(0.20, np.arange(1, 11) / 10, np.arange(0, 50, 5), np.arange(0, 181))
    >>> round(g["p_max"], 4), g["k"], g["alpha_deg"], g["theta_deg"], round(g["phi_deg"], 2)
    (0.6177, 0.6, 5.0, 95.0, 73.06)
    """
    k = np.asarray(k_values, dtype=float)[:, None, None]
    a = np.radians(np.asarray(alpha_values_deg, dtype=float))[None, :, None]
    th = np.radians(np.asarray(theta_values_deg, dtype=float))
    px, py = residual_force(th, k, a, lam)
    p = np.hypot(px, py)
    pmax = p.max(axis=-1)
    ik, ia = np.unravel_index(np.argmin(pmax), pmax.shape)
    it = int(np.argmax(p[ik, ia]))
    return {"p_max": float(pmax[ik, ia]), "k": float(k[ik, 0, 0]), "alpha_deg": float(np.degrees(a[0, ia, 0])),
            "theta_deg": float(np.degrees(th[it])),
            "phi_deg": float(np.degrees(np.arctan(py[ik, ia, it] / px[ik, ia, it])))}
