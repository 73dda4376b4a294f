"""The permissible vibratory torsional stress of a propulsion line's intermediate, thrust and
propeller shafts: IACS UR M68 [IACSM68] as the class rules carry it.

For continuous running, at speed ratio λ = n / n_rated (n_rated the maximum continuous speed),

    τ_C = ± (σ_B + 160) / 18 · C_K · C_D · (3 − 2 λ²)     for λ < 0.9,
    τ_C = ± (σ_B + 160) / 18 · C_K · C_D · 1.38           for 0.9 ≤ λ ≤ 1.05,

and for the transient passage of a barred speed range (λ ≤ 0.8) τ_T = 1.7 τ_C / √C_K; σ_B the
specified minimum tensile strength of the shaft's material in N/mm² (capped, below), C_K the
factor of the shaft's design feature (:data:`fetorsion.description.marine.CK_FACTORS`) and
C_D = 0.35 + 0.93 d^−0.2 the size factor (d the shaft's outer diameter in mm). The stresses the
limits are compared with are half-range amplitudes of the synthesis over all orders, on the
plain section (stress raisers neglected: C_K carries them).

**What was read.** The rule's text itself was not found readable. The symbols, the definition of
C_D, the half-range synthesised stress on the plain section and the first rows of the C_K table
were read in Lloyd's Register's naval rules [LRNavalTV] (Vol 2, Pt 5, Ch 1, §3.1), which carry
the same limits; the caps on σ_B (carbon and carbon-manganese steel 400–760 N/mm², alloy steel not
above 800 N/mm², greater strengths giving no higher limit) in Lloyd's Register's ship rules
[LRShipsShafts] (Pt 5, Ch 6, §2.1.1 and §2.1.4). The formulas for τ_C and τ_T above are as
restated in the literature, not read in a rule's text here (docs/propulsion-tvc.md).

SI at the API (m, Pa); the rule's units (mm, N/mm²) only inside the formulas.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..description.marine import CK_FACTORS, SIGMA_B_CAP_PA
from ..errors import ParameterError

#: λ up to which τ_C falls as (3 − 2λ²); above it, up to :data:`LAMBDA_MAX`, the factor is 1.38.
LAMBDA_KNEE = 0.9
#: The largest speed ratio the rule gives τ_C for.
LAMBDA_MAX = 1.05
#: The largest speed ratio a barred range (and so τ_T) may lie at, for propulsion.
LAMBDA_TRANSIENT_MAX = 0.8


@dataclass(frozen=True)
class ShaftLimit:
    """The rule's limits for one shaft section at one speed ratio, every factor shown.

    ``sigma_b_pa`` is σ_B as the formula used it (the stated one capped: ``sigma_b_stated_pa``);
    ``tau_t_pa`` is None above λ = 0.8, where the rule allows no barred range.
    """

    feature: str
    diameter_m: float
    sigma_b_stated_pa: float
    sigma_b_pa: float
    ck: float
    cd: float
    speed_ratio: float
    tau_c_pa: float
    tau_t_pa: float | None

    def to_dict(self) -> dict[str, float | str | None]:
        """The factors and limits, JSON-ready (SI, the unit in each key)."""
        return asdict(self)

    def table(self) -> str:
        """The factors and limits as plain text, in the rule's units (N/mm², mm)."""
        tau_t = "—" if self.tau_t_pa is None else f"{self.tau_t_pa / 1e6:.2f}"
        return (f"shaft ({self.feature}), d = {self.diameter_m * 1e3:.1f} mm, λ = {self.speed_ratio:.3f}\n"
                f"  σ_B {self.sigma_b_pa / 1e6:.0f} N/mm² (stated {self.sigma_b_stated_pa / 1e6:.0f}), "
                f"C_K {self.ck:.3f}, C_D {self.cd:.4f}\n"
                f"  τ_C ±{self.tau_c_pa / 1e6:.2f} N/mm², τ_T ±{tau_t} N/mm²")

    def plot(self, ax=None):
        """τ_C and τ_T of this shaft over λ (N/mm²), this λ marked; returns the Axes."""
        import matplotlib.pyplot as plt
        import numpy as np

        ax = ax if ax is not None else plt.figure().add_subplot()
        lam = np.linspace(0.0, LAMBDA_MAX, 106)
        tau_c = [continuous_limit(self.sigma_b_pa, self.ck, self.cd, x) / 1e6 for x in lam]
        ax.plot(lam, tau_c, label="τ_C")
        low = lam <= LAMBDA_TRANSIENT_MAX
        ax.plot(lam[low], [transient_limit(t * 1e6, self.ck) / 1e6 for t in np.asarray(tau_c)[low]], label="τ_T")
        ax.axvline(self.speed_ratio, color="0.5", lw=0.8)
        ax.set(xlabel="speed ratio λ", ylabel="permissible stress (N/mm²)", title=f"UR M68, {self.feature}")
        ax.legend()
        return ax


def size_factor(diameter_m: float) -> float:
    """C_D = 0.35 + 0.93 d^−0.2, d in mm [LRNavalTV].

    Parameters
    ----------
    diameter_m : float
        The shaft's outer diameter, m (> 0).
    """
    if not diameter_m > 0:
        raise ParameterError("diameter_m", f"{diameter_m}: must be > 0 (the shaft's outer diameter, m)")
    return 0.35 + 0.93 * (diameter_m * 1e3) ** -0.2


def capped_strength(sigma_b_pa: float, material: str) -> float:
    """σ_B as the formulas take it: the stated one, at most the material's cap (Pa).

    Parameters
    ----------
    sigma_b_pa : float
        The specified minimum tensile strength, Pa (> 0).
    material : str
        ``carbon`` (carbon and carbon-manganese steel) or ``alloy``.
    """
    if material not in SIGMA_B_CAP_PA:
        raise ParameterError("material", f"{material!r}: must be one of {', '.join(SIGMA_B_CAP_PA)}")
    if not sigma_b_pa > 0:
        raise ParameterError("sigma_b_pa", f"{sigma_b_pa}: must be > 0 (the tensile strength, Pa)")
    return min(sigma_b_pa, SIGMA_B_CAP_PA[material])


def continuous_limit(sigma_b_pa: float, ck: float, cd: float, speed_ratio: float) -> float:
    """τ_C (Pa) at speed ratio λ.

    Parameters
    ----------
    sigma_b_pa : float
        σ_B as the formula takes it (already capped), Pa.
    ck, cd : float
        The feature factor C_K and the size factor C_D (dimensionless).
    speed_ratio : float
        λ = speed / rated speed, 0 ≤ λ ≤ 1.05.
    """
    if not 0.0 <= speed_ratio <= LAMBDA_MAX:
        raise ParameterError("speed_ratio", f"{speed_ratio}: must be between 0 and {LAMBDA_MAX} (the rule gives "
                             "no limit above 1.05 of the rated speed)")
    speed = 3.0 - 2.0 * speed_ratio**2 if speed_ratio < LAMBDA_KNEE else 1.38
    return (sigma_b_pa / 1e6 + 160.0) / 18.0 * ck * cd * speed * 1e6


def transient_limit(tau_c_pa: float, ck: float) -> float:
    """τ_T = 1.7 τ_C / √C_K (Pa), the limit for passing through a barred speed range."""
    return 1.7 * tau_c_pa / math.sqrt(ck)


def shaft_limit(feature: str, diameter_m: float, sigma_b_pa: float, speed_ratio: float,
                material: str = "carbon") -> ShaftLimit:
    """The rule's τ_C and τ_T of one shaft section at one speed ratio, every factor shown.

    Parameters
    ----------
    feature : str
        The section's design feature, a key of :data:`~fetorsion.description.marine.CK_FACTORS`.
    diameter_m : float
        The shaft's outer diameter, m.
    sigma_b_pa : float
        The specified minimum tensile strength of its material, Pa.
    speed_ratio : float
        λ = speed / rated (maximum continuous) speed.
    material : str
        ``carbon`` or ``alloy``: which cap σ_B takes.

    Examples
    --------
    >>> round(shaft_limit("integral_flange", 0.3, 600e6, 0.5).tau_c_pa / 1e6, 2)
    68.32
    """
    if feature not in CK_FACTORS:
        raise ParameterError("feature", f"{feature!r}: must be one of {', '.join(CK_FACTORS)}")
    ck, cd = CK_FACTORS[feature], size_factor(diameter_m)
    sigma = capped_strength(sigma_b_pa, material)
    tau_c = continuous_limit(sigma, ck, cd, speed_ratio)
    tau_t = transient_limit(tau_c, ck) if speed_ratio <= LAMBDA_TRANSIENT_MAX else None
    return ShaftLimit(feature, diameter_m, sigma_b_pa, sigma, ck, cd, speed_ratio, tau_c, tau_t)
