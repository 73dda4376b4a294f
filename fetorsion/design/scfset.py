"""The stress concentration factors a crank's stress and fatigue stages read, as one typed set.

Every factor is against the section it sits on: a fillet's against its pin's or journal's own
section (τ_nom = 16 T D/(π (D⁴ − d⁴)), σ_nom = 32 M D/(π (D⁴ − d⁴))), an oil bore's against the
drilled section's. :mod:`.m53` converts them to the rule's web-section convention.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

from ..errors import FetorsionError

#: The two kinds of fillet and of drilled section.
KINDS = ("pin", "journal")


@dataclass(frozen=True)
class SCFSet:
    """Fillet and oil-bore SCFs of one crank.

    Attributes
    ----------
    torsion : dict[str, float]
        ``{"pin": ..., "journal": ...}``: peak largest shear over τ_nom of the fillet's section.
    bending : dict[str, float]
        Peak largest principal stress under either sign of an in-plane couple over σ_nom (the
        kinds computed; empty when only torsion is known).
    bending_vm : dict[str, float]
        The same with the von Mises stress ([IACSM53] Appendix III's measure).
    source : str
        How the fillet factors were obtained.
    oil_bore : dict[str, tuple[float, float]]
        ``{kind: (bending, torsion)}`` of the drilled kinds of section; empty without drillings.
    oil_bore_source : str
        How the oil-bore factors were obtained.
    """

    torsion: dict[str, float]
    bending: dict[str, float] = field(default_factory=dict)
    bending_vm: dict[str, float] = field(default_factory=dict)
    source: str = ""
    oil_bore: dict[str, tuple[float, float]] = field(default_factory=dict)
    oil_bore_source: str = ""

    def __post_init__(self):
        for name in ("torsion", "bending", "bending_vm"):
            bad = sorted(set(getattr(self, name)) - set(KINDS))
            if bad:
                raise FetorsionError(f"SCF set: unknown {name} kind(s) {', '.join(bad)} (pin, journal)")
        missing = [k for k in KINDS if k not in self.torsion]
        if missing:
            raise FetorsionError(f"SCF set: no torsion SCF for the {' and '.join(missing)} fillets")

    @classmethod
    def of(cls, pin: float, journal: float, source: str = "", pin_bending: float | None = None,
           journal_bending: float | None = None, pin_bending_vm: float | None = None,
           journal_bending_vm: float | None = None) -> "SCFSet":
        """A set from the fillets' factors by name (None: not known)."""
        def pair(p, j):
            return {k: float(v) for k, v in (("pin", p), ("journal", j)) if v is not None}

        return cls(pair(pin, journal), pair(pin_bending, journal_bending), pair(pin_bending_vm, journal_bending_vm),
                   source)

    @classmethod
    def from_dict(cls, d: dict) -> "SCFSet":
        """The set from its :meth:`to_dict` form (also the shipped table's entries)."""
        bores = {k: (float(d[f"{k}_oil_bore_bending"]), float(d[f"{k}_oil_bore_torsion"]))
                 for k in KINDS if f"{k}_oil_bore_bending" in d}
        out = cls.of(d["pin"], d["journal"], d.get("source", ""), d.get("pin_bending"), d.get("journal_bending"),
                     d.get("pin_bending_vm"), d.get("journal_bending_vm"))
        return replace(out, oil_bore=bores, oil_bore_source=d.get("oil_bore_source", ""))

    def to_dict(self) -> dict:
        """Flat JSON keys: ``pin``, ``journal``, ``pin_bending``, …, ``pin_oil_bore_bending``, …, ``source``."""
        out = {k: self.torsion[k] for k in KINDS}
        out.update({f"{k}_bending": v for k, v in self.bending.items()})
        out.update({f"{k}_bending_vm": v for k, v in self.bending_vm.items()})
        for k, (b, t) in self.oil_bore.items():
            out[f"{k}_oil_bore_bending"], out[f"{k}_oil_bore_torsion"] = b, t
        out["source"] = self.source
        if self.oil_bore:
            out["oil_bore_source"] = self.oil_bore_source
        return out

    def with_oil_bores(self, bores: dict, source: str) -> "SCFSet":
        """This set with the oil bores' ``{kind: (bending, torsion)}`` factors."""
        return replace(self, oil_bore={k: (float(b), float(t)) for k, (b, t) in bores.items()}, oil_bore_source=source)

    def missing_bending(self) -> list[str]:
        """The bending factors (``pin_bending``, ``journal_bending_vm``, …) this set lacks."""
        return [f"{k}_{name}" for name, have in (("bending", self.bending), ("bending_vm", self.bending_vm))
                for k in KINDS if k not in have]

    def fillet(self, kind: str) -> tuple[float, float]:
        """(bending, torsion) SCF of a ``pin`` or ``journal`` fillet; raises without the bending one."""
        if kind not in self.bending:
            raise FetorsionError(f"no bending SCF for the {kind} fillets in {self.source or 'the SCFs given'}")
        return self.bending[kind], self.torsion[kind]
