"""Plain oil-film journal bearings: the short-bearing (Ocvirk) linearised coefficients.

A main bearing without a supplier's stiffness is a plain journal bearing: a journal of diameter
D turning at Ω in a bush of radial clearance c, width L, with oil of dynamic viscosity μ. Under
a static load W the journal settles at eccentricity e = ε c, its line of centres at the
attitude angle φ to the load. Small motions about that point see linear forces,
Δf = −K Δx − C Δẋ, with 2×2 stiffness K (N/m) and damping C (N·s/m) [Friswell] §5.5.

The short-bearing theory [Ocvirk] drops the circumferential pressure flow from Reynolds'
equation (right when L/D is small; crank mains have L/D ≈ 0.3–0.5). With the film
h(θ) = c (1 + ε cos θ) the pressure is then

    p(θ, z) = (3 μ / h³) (L²/4 − z²) (−Ω ∂h/∂θ − 2 ∂h/∂t),

kept where it is positive (half-Sommerfeld, π-film: the oil cavitates instead of carrying
tension). Integrated over the film it gives, in closed form [Friswell] §5.5:

* the modified Sommerfeld (Ocvirk) number S_s = D Ω μ L³ / (8 W c²);
* the load equation (1 − ε²)⁴ = S_s² ε² (π² (1 − ε²) + 16 ε²), a quartic in ε²;
* the attitude angle tan φ = π √(1 − ε²) / (4 ε);
* K = (W / c) a(ε) and C = W / (c Ω) b(ε) with the dimensionless a_ij, b_ij of
  :func:`dimensionless_coefficients`.

The frame of a and b is [Friswell]'s: u across the load, v against it (the static load pushes
the journal towards −v) and the journal turning from u towards v. [Friswell] Example 5.5.1
(D = 100 mm, L = 30 mm, c = 0.1 mm, μ = 0.1 Pa·s, 1500 rpm, W = 525 N) gives
K = [[12.81, 16.39], [−25.06, 8.815]] MN/m and C = [[232.9, −81.92], [−81.92, 294.9]] kN·s/m;
tests/test_oilfilm.py checks that, and checks K and C against finite differences of the film
force integrated numerically from p(θ, z) above.

The coefficients hold at one operating point: they scale with the load and, through ε, depend
on speed, viscosity (temperature) and load together.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

#: Bracketing tolerance of the eccentricity ratio (absolute; brentq's relative tolerance is at
#: its floor): ε to ~1e-15 for every load, so that light loads (ε ~ 1e-6) keep full relative
#: precision too.
ECCENTRICITY_TOL = 1e-300


def modified_sommerfeld(load: float, speed: float, diameter: float, width: float, clearance: float,
                        viscosity: float) -> float:
    """The modified Sommerfeld (Ocvirk) number S_s = D Ω μ L³ / (8 W c²) [Friswell] §5.5.

    Parameters
    ----------
    load : float
        Static load W on the bearing, N (> 0).
    speed : float
        Journal speed Ω, rad/s (> 0).
    diameter : float
        Journal diameter D, m.
    width : float
        Bearing width L (axial length of the film), m.
    clearance : float
        Radial clearance c, m.
    viscosity : float
        Dynamic viscosity μ, Pa·s.

    Returns
    -------
    float
        S_s, dimensionless: large for a light, fast bearing (ε → 0), small for a heavy, slow one
        (ε → 1). The classical Sommerfeld number is S_s (D / L)² / π.
    """
    return diameter * speed * viscosity * width ** 3 / (8.0 * load * clearance ** 2)


def eccentricity_ratio(sommerfeld: float) -> float:
    """The static eccentricity ratio ε = e / c of a short bearing at modified Sommerfeld number S_s.

    Solves the short-bearing load equation [Friswell] §5.5,

        S_s ε √(π² (1 − ε²) + 16 ε²) = (1 − ε²)²,

    (the quartic ε⁸ − 4ε⁶ + (6 − S_s²(16 − π²)) ε⁴ − (4 + π² S_s²) ε² + 1 = 0 written back in ε)
    by bracketing on (0, 1). The left side rises and the right side falls with ε, so the root is
    unique; bracketing finds it for any S_s > 0, where the polynomial's roots lose precision at
    the ends (ε ≈ 1/(π S_s) for a light load, 1 − ε² ≈ 2 √S_s for a heavy one).

    Parameters
    ----------
    sommerfeld : float
        S_s > 0 (:func:`modified_sommerfeld`).

    Returns
    -------
    float
        ε in (0, 1).
    """
    s = float(sommerfeld)
    pi2 = math.pi ** 2

    def residual(e):
        return s * e * math.sqrt(pi2 * (1.0 - e * e) + 16.0 * e * e) - (1.0 - e * e) ** 2

    return brentq(residual, 0.0, 1.0, xtol=ECCENTRICITY_TOL)


def attitude_angle(eccentricity: float) -> float:
    """Angle φ (rad) between the load and the line of centres: tan φ = π √(1 − ε²) / (4 ε)
    [Friswell] §5.5; π/2 for a light load, 0 for a heavy one."""
    e = eccentricity
    return math.atan2(math.pi * math.sqrt(1.0 - e * e), 4.0 * e)


def dimensionless_coefficients(eccentricity: float) -> tuple[np.ndarray, np.ndarray]:
    """The short bearing's dimensionless stiffness a and damping b at eccentricity ratio ε.

    [Friswell] §5.5, in its (u, v) frame (u across the load, v against it, the journal turning
    from u towards v), with h₀ = (π² (1 − ε²) + 16 ε²)^(−3/2) and s = √(1 − ε²)::

        a_uu = 4 h₀ (π² (2 − ε²) + 16 ε²)
        a_uv = h₀ π (π² (1 − ε²)² − 16 ε⁴) / (ε s)
        a_vu = −h₀ π (π² (1 − ε²)(1 + 2ε²) + 32 ε² (1 + ε²)) / (ε s)
        a_vv = 4 h₀ (π² (1 + 2ε²) + 32 ε² (1 + ε²) / (1 − ε²))
        b_uu = 2π h₀ s (π² (1 + 2ε²) − 16 ε²) / ε
        b_uv = b_vu = −8 h₀ (π² (1 + 2ε²) − 16 ε²)
        b_vv = 2π h₀ (π² (1 − ε²)² + 48 ε²) / (ε s)

    Parameters
    ----------
    eccentricity : float
        ε in (0, 1).

    Returns
    -------
    a, b : ndarray (2, 2)
        [[uu, uv], [vu, vv]]; K = (W / c) a, C = W / (c Ω) b.
    """
    e = eccentricity
    e2, pi2 = e * e, math.pi ** 2
    s = math.sqrt(1.0 - e2)
    h0 = (pi2 * (1.0 - e2) + 16.0 * e2) ** -1.5
    a = h0 * np.array([
        [4.0 * (pi2 * (2.0 - e2) + 16.0 * e2),
         math.pi * (pi2 * (1.0 - e2) ** 2 - 16.0 * e2 * e2) / (e * s)],
        [-math.pi * (pi2 * (1.0 - e2) * (1.0 + 2.0 * e2) + 32.0 * e2 * (1.0 + e2)) / (e * s),
         4.0 * (pi2 * (1.0 + 2.0 * e2) + 32.0 * e2 * (1.0 + e2) / (1.0 - e2))]])
    cross = -8.0 * (pi2 * (1.0 + 2.0 * e2) - 16.0 * e2)
    b = h0 * np.array([
        [2.0 * math.pi * s * (pi2 * (1.0 + 2.0 * e2) - 16.0 * e2) / e, cross],
        [cross, 2.0 * math.pi * (pi2 * (1.0 - e2) ** 2 + 48.0 * e2) / (e * s)]])
    return a, b


@dataclass(frozen=True)
class FilmCoefficients:
    """A short bearing at one operating point.

    ``stiffness`` (N/m) and ``damping`` (N·s/m) are 2×2 in [Friswell]'s (u, v) load frame
    (:func:`dimensionless_coefficients`); :func:`in_crank_axes` turns them into the crank's y, z.
    """

    eccentricity: float
    attitude: float  # rad
    stiffness: np.ndarray
    damping: np.ndarray


def film_coefficients(load: float, speed: float, diameter: float, width: float, clearance: float,
                      viscosity: float) -> FilmCoefficients:
    """The linearised short-bearing coefficients of a plain journal bearing [Friswell] §5.5.

    Parameters
    ----------
    load : float
        Static load W, N (> 0).
    speed : float
        Journal speed Ω, rad/s (> 0).
    diameter : float
        Journal diameter D, m.
    width : float
        Bearing width L, m (short-bearing theory wants L/D ≲ 0.5).
    clearance : float
        Radial clearance c, m.
    viscosity : float
        Dynamic viscosity μ, Pa·s, at the film's temperature.

    Returns
    -------
    FilmCoefficients
        ε, φ and K = (W / c) a(ε), C = W / (c Ω) b(ε) in the load frame.

    Examples
    --------
    >>> f = film_coefficients(525.0, 50 * math.pi, 0.1, 0.03, 1e-4, 0.1)  # [Friswell] Example 5.5.1
    >>> round(f.eccentricity, 4), np.round(f.stiffness / 1e6, 2).tolist()
    (0.2663, [[12.81, 16.39], [-25.06, 8.82]])
    """
    e = eccentricity_ratio(modified_sommerfeld(load, speed, diameter, width, clearance, viscosity))
    a, b = dimensionless_coefficients(e)
    return FilmCoefficients(e, attitude_angle(e), load / clearance * a, load / (clearance * speed) * b)


def in_crank_axes(matrix: np.ndarray, load_angle: float) -> np.ndarray:
    """A 2×2 bearing matrix from the (u, v) load frame into the crank's (y, z) axes.

    The crank turns positively about +x (from y towards z), as the load frame's journal turns
    from u towards v. ``load_angle`` (rad) is the direction of the static load on the journal,
    from +y towards +z; v points against it and u is v turned back a quarter turn, so with
    Q = [u v] (columns in y, z) the matrix is Q M Qᵀ. A crank turning the other way is the mirror
    image: mirror y (y → −y) on the load angle and on the result.
    """
    v = -np.array([math.cos(load_angle), math.sin(load_angle)])
    Q = np.column_stack([[v[1], -v[0]], v])
    return Q @ np.asarray(matrix) @ Q.T


def isotropic_equivalent(stiffness: np.ndarray, damping: np.ndarray) -> tuple[float, float]:
    """The isotropic spring and damper (N/m, N·s/m) standing for a 2×2 film: the mean of the two
    direct terms, (k_uu + k_vv)/2 and (c_uu + c_vv)/2.

    fetorsion's bearings are isotropic and diagonal (the same k on a journal's y and z) because
    its eigen problem is real and symmetric. The mean of the direct terms is half the trace, so
    it is the same in every frame: it needs no load direction, which changes through the cycle.
    It is the spring that stores the film's mean energy over a circular whirl orbit (½ k r² for
    ½ xᵀKx averaged over the orbit's directions). What it leaves out: the anisotropy (two
    principal stiffnesses, two split frequencies) and the cross-coupled skew part of K, which
    does work over a whirl orbit (oil whirl) and belongs to a non-symmetric, complex eigen
    problem, not to the symmetric one here. C is symmetric in short-bearing theory.
    """
    return 0.5 * float(np.trace(stiffness)), 0.5 * float(np.trace(damping))
