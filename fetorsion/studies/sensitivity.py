"""How the first torsional frequency depends on each reconstructed input, and its band.

Each ``[uncertainty]`` entry of a description gives a range [low, high] for one input
(``*`` paths set every entry of the list to the bound), or for a named group of inputs
that move together (a material's E and density). The lumped model is re-run with
that input at each bound, all else nominal: that gives the one-at-a-time change of f1 and
its elasticity (Δf/f)/(Δx/x). The band of f1 is then computed, not estimated: every input
is put at the bound that lowers f1 (and then at the one that raises it) and the model run
once more, so the band's ends are real model results, interactions included.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

from ..description.model import Crank

from ..errors import FetorsionError
from ..results import from_fields
from ..lumped_model.lumped import lumped
from ..description.edit import field_values, with_values
from ..description.defaults import CHECK_MESH_SIZE, DEFAULT_PARTITION, DEFAULT_WEB_METHOD

if TYPE_CHECKING:
    from distributed import Client

    from ..lumped_model.parts import PartChain
    from .runner import ClusterOnDemand, SampleStore


@dataclass(frozen=True)
class SensitivityRow:
    """One ``[uncertainty]`` input: its name (``field``), nominal, low and high values (file
    units), f1 at each bound (Hz) and the elasticity (Δf/f)/(Δx/x) across the range."""

    field: str
    nominal: float
    low: float
    high: float
    f1_low_hz: float
    f1_high_hz: float
    elasticity: float

    @property
    def swing_hz(self) -> float:
        """The absolute change of f1 from the low bound to the high one, Hz."""
        return abs(self.f1_high_hz - self.f1_low_hz)


@dataclass
class SensitivityResult:
    """One-at-a-time sensitivities of f1 and the corner band.

    ``rows``: one :class:`SensitivityRow` per input. ``band_hz``: f1 with every input at the
    bound that lowers it, and at the one that raises it.
    """

    name: str
    model: str
    f1_hz: float
    rows: list[SensitivityRow]
    band_hz: tuple[float, float]
    measured_hz: float | None

    @property
    def measured_inside(self) -> bool | None:
        if self.measured_hz is None:
            return None
        return self.band_hz[0] <= self.measured_hz <= self.band_hz[1]

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"name": self.name, "model": self.model, "f1_hz": self.f1_hz, "rows": [asdict(r) for r in self.rows],
                "band_hz": list(self.band_hz), "measured_hz": self.measured_hz,
                "measured_inside_band": self.measured_inside}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "SensitivityResult":
        """The result back from its :meth:`to_dict`."""
        return from_fields(cls, d)

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        head = f"{'input':<32} {'range':>22} {'f1 at low':>10} {'f1 at high':>10} {'elasticity':>10}"
        lines = [f"{self.name}: f1 = {self.f1_hz:.1f} Hz ({self.model}); one input at a time", head, "-" * len(head)]
        for r in sorted(self.rows, key=lambda r: -r.swing_hz):
            rng = f"{r.low:g} .. {r.high:g}"
            lines.append(f"{r.field:<32} {rng:>22} {r.f1_low_hz:10.1f} {r.f1_high_hz:10.1f} {r.elasticity:10.3f}")
        lo, hi = self.band_hz
        lines.append(f"band of f1 (all inputs at their worst bounds): {lo:.1f} .. {hi:.1f} Hz")
        if self.measured_hz is not None:
            where = "inside" if self.measured_inside else "OUTSIDE"
            lines.append(f"measured {self.measured_hz:g} Hz is {where} the band")
        return "\n".join(lines)

    def plot(self, ax=None):
        """Tornado chart of f1 against each input's range."""
        import matplotlib.pyplot as plt

        rows = sorted(self.rows, key=lambda r: r.swing_hz)
        if ax is None:
            _, ax = plt.subplots(figsize=(8, 0.35 * len(rows) + 1.5))
        for i, r in enumerate(rows):
            a, b = sorted((r.f1_low_hz, r.f1_high_hz))
            ax.barh(i, b - a, left=a, color="C0")
        ax.set_yticks(range(len(rows)), [r.field for r in rows], fontsize=7)
        ax.axvline(self.f1_hz, color="k", lw=1, label=f"nominal {self.f1_hz:.0f} Hz")
        ax.axvspan(*self.band_hz, color="C0", alpha=0.12, label="band")
        if self.measured_hz is not None:
            ax.axvline(self.measured_hz, color="crimson", lw=1.5, ls="--", label=f"measured {self.measured_hz:g} Hz")
        ax.set_xlabel("first torsional frequency [Hz]")
        ax.set_title(f"{self.name}\nf1 sensitivity ({self.model})", fontsize=10, wrap=True)
        ax.legend(fontsize=7)
        ax.figure.tight_layout()
        return ax


def fe_check(crank: Crank, result: SensitivityResult, count: int = 3, mesh_size: float = CHECK_MESH_SIZE,
             client: Client | ClusterOnDemand | None = None, store: SampleStore | None = None) -> list[dict]:
    """FE first torsional frequency at the bounds of the ``count`` most influential inputs.

    Runs on the crank without fillets and drillings at a coarse mesh (a few seconds per
    run): what is compared is the change of f1, which those details barely affect. The
    ``1 + 2 count`` FE runs are samples of a study (:mod:`fetorsion.studies.runner`): on
    ``client``'s cluster when given (else here, one after the other), each stored as it
    finishes in ``store`` (default the sample store), so a second report computes none.
    """
    from .runner import open_store, run_samples
    from .models import FEModel

    groups = dict(crank.uncertainty)
    rows = sorted(result.rows, key=lambda r: -r.swing_hz)[:count]
    samples = [{}]
    for row in rows:
        members = groups[row.field]
        samples += [{p: low for p, low, _ in members}, {p: high for p, _, high in members}]
    records, _ = run_samples(FEModel(crank, mesh_size), samples, store or open_store(), client,
                             label=f"{crank.name}: FE checks", progress=client is not None)
    failed = [r for r in records if "error" in r]
    if failed:
        raise FetorsionError(f"FE check of the sensitivity: {failed[0]['error']}")
    f1 = [r["outputs"]["f1"] for r in records]
    nominal = f1[0]
    out = []
    for k, row in enumerate(rows):
        lo, hi = f1[1 + 2 * k], f1[2 + 2 * k]
        out.append({"field": row.field, "fe_f1_nominal_hz": nominal, "fe_f1_low_hz": lo, "fe_f1_high_hz": hi,
                    "fe_change_percent": 100 * (hi - lo) / nominal,
                    "lumped_change_percent": 100 * (row.f1_high_hz - row.f1_low_hz) / result.f1_hz})
    return out


def run_sensitivity(crank: Crank, dof: int = DEFAULT_PARTITION, stiffness: str = DEFAULT_WEB_METHOD,
                    parts: PartChain | None = None) -> SensitivityResult:
    """Sensitivity of the lumped f1 to each ``[uncertainty]`` input, and the f1 band.

    Parameters
    ----------
    crank : Crank
        A description with an ``[uncertainty]`` table (ranges in file units).
    dof : int
        Lumped partition (5, 6, 17, 19, 21).
    stiffness : str
        Web-stiffness method (a key of :data:`fetorsion.webs.methods.WEB_METHODS`).
    parts : PartChain, optional
        The nominal crank's parts for ``stiffness``, when the caller has them.

    Returns
    -------
    SensitivityResult
        f1 (Hz) at each input's bounds and the band with every input at its worst bound.

    Examples
    --------
    >>> import fetorsion
    >>> from fetorsion.studies.sensitivity import run_sensitivity
    >>> s = run_sensitivity(fetorsion.load("geometry/peugeot_glx.toml"))
    >>> s.band_hz[0] < s.f1_hz < s.band_hz[1]
    True
    """
    if not crank.uncertainty:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [uncertainty] table")

    def f1(c: Crank) -> float:
        return float(lumped(c, dof, stiffness).frequencies_hz[0])

    nominal = float(lumped(crank, dof, stiffness, parts=parts).frequencies_hz[0])
    rows, lower, upper = [], {}, {}
    for name, members in crank.uncertainty:
        lows = {path: low for path, low, _ in members}
        highs = {path: high for path, _, high in members}
        f_lo, f_hi = f1(with_values(crank, lows)), f1(with_values(crank, highs))
        path, low, high = members[0]  # the group's first member scales the elasticity
        values = [v for _, v in field_values(crank, path)]
        x0 = sum(values) / len(values)
        rows.append(SensitivityRow(name, x0, low, high, f_lo, f_hi, (f_hi - f_lo) / nominal / ((high - low) / x0)))
        (lower if f_lo <= f_hi else upper).update(lows)
        (upper if f_lo <= f_hi else lower).update(highs)
    band = (f1(with_values(crank, lower)), f1(with_values(crank, upper)))
    measured = getattr(crank, "measured_f1_hz", None)  # a chain file has none
    return SensitivityResult(crank.name, f"lumped {dof} DOF, {stiffness}", nominal, rows, band,
                             float(measured) if measured is not None else None)
