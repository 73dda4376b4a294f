"""Validation against the measured first torsional frequencies: the FE f1 and its band.

The reference cranks are reconstructions; each ``[uncertainty]`` range bounds one input. The
3D FE (free-free, as the modal tests were) is run for the nominal description and for the two
corners of the band found by :func:`fetorsion.studies.sensitivity.run_sensitivity` (every input
at the bound that lowers, then raises, the lumped f1). The measured frequency should lie in
the FE band, and the nominal FE within :data:`FE_ERROR_BOUND` of it. The README's validation
table and the test are both made by :func:`run_validation`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..description.defaults import DEFAULT_MESH_SIZE
from ..description.model import Crank
from ..errors import FetorsionError
from .sensitivity import run_sensitivity, with_values

#: Stated bound on |FE f1 / measured − 1| for the reference reconstructions: the
#: reconstruction's own 90 % interval, 1.645 σ, with σ the smaller of the two cranks' FE f1
#: spreads under their [uncertainty] ranges (6.0 % Renault 21, 7.0 % Peugeot GLX: 24-sample FE
#: Monte Carlo, results/studies/fe_band.md) — a reconstruction cannot be held closer to a
#: measurement than its inputs are known. (The earlier 6 % had been set after −4.9 % was seen.)
FE_ERROR_BOUND = 0.10


@dataclass
class ValidationResult:
    """FE f1 of the nominal description and of the band's two corners, against the measurement (Hz)."""

    name: str
    measured_hz: float
    fe_hz: float
    band_hz: tuple[float, float]
    dofs: int
    mesh_size: float
    details: bool

    @property
    def error(self) -> float:
        return self.fe_hz / self.measured_hz - 1.0

    @property
    def measured_inside(self) -> bool:
        return self.band_hz[0] <= self.measured_hz <= self.band_hz[1]

    def to_dict(self) -> dict:
        return {"name": self.name, "measured_hz": self.measured_hz, "fe_hz": self.fe_hz, "error": self.error,
                "band_hz": list(self.band_hz), "measured_inside_band": self.measured_inside,
                "error_bound": FE_ERROR_BOUND, "dofs": self.dofs, "mesh_size_m": self.mesh_size,
                "fillets_and_drillings": self.details}

    def row(self) -> str:
        """One Markdown table row: crank, measured, FE, error, band, inside."""
        lo, hi = self.band_hz
        return (f"| {self.name} | {self.measured_hz:.1f} | {self.fe_hz:.1f} | {100 * self.error:+.1f} % | "
                f"{lo:.0f} – {hi:.0f} | {'yes' if self.measured_inside else 'NO'} |")

    def table(self) -> str:
        return "\n".join(["| crank | measured f1 [Hz] | FE f1 [Hz] | FE error | FE band [Hz] | measured in band |",
                          "|---|---|---|---|---|---|", self.row()])

    def plot(self, ax=None):
        """The FE band, the nominal FE and the measured frequency."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 2))
        ax.axvspan(*self.band_hz, color="C0", alpha=0.15, label="FE band ([uncertainty] corners)")
        ax.axvline(self.fe_hz, color="C0", label=f"FE nominal {self.fe_hz:.0f} Hz")
        ax.axvline(self.measured_hz, color="k", ls="--", label=f"measured {self.measured_hz:.0f} Hz")
        ax.set_yticks([])
        ax.set_xlabel("first torsional frequency (Hz)")
        ax.legend(fontsize=7)
        ax.figure.tight_layout()
        return ax


def band_corners(crank: Crank) -> tuple[dict, dict]:
    """The changes that put every ``[uncertainty]`` input at the bound lowering (then raising) f1."""
    rows = {r.field: r for r in run_sensitivity(crank).rows}
    lower, upper = {}, {}
    for name, members in crank.uncertainty:
        lows = {path: low for path, low, _ in members}
        highs = {path: high for path, _, high in members}
        down = rows[name].f1_low_hz <= rows[name].f1_high_hz
        (lower if down else upper).update(lows)
        (upper if down else lower).update(highs)
    return lower, upper


def run_validation(crank: Crank, mesh_size: float = DEFAULT_MESH_SIZE, details: bool = True) -> ValidationResult:
    """Free-free FE f1 of ``crank`` and of its band's corners, against its measured f1.

    Parameters
    ----------
    crank : Crank
        With ``[meta] measured_first_torsional_hz`` and an ``[uncertainty]`` table.
    mesh_size : float
        Global element size, m.
    details : bool
        Keep fillets and oil drillings (False: a coarse, fast model).
    """
    from ..fe.crankfe import run_modal

    measured = crank.measured_f1_hz
    if measured is None or not crank.uncertainty:
        raise FetorsionError(f"{crank.source or crank.name}: validation needs [meta] measured_first_torsional_hz "
                             "and an [uncertainty] table")
    lower, upper = band_corners(crank)
    nominal = crank if details else with_values(crank, {}, details=False)
    fe = run_modal(nominal, mesh_size)
    band = tuple(run_modal(with_values(crank, c, details=details), mesh_size).first_torsional() for c in (lower, upper))
    return ValidationResult(crank.name, float(measured), fe.first_torsional(), (min(band), max(band)), fe.dofs,
                            mesh_size, details)
