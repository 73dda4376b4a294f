"""Vibratory shear stress at the pin and journal fillets, from the synthesised section torques.

Each fillet (a journal–web or pin–web junction at axial position x) lies between two anchors of
the lumped chain, so it carries that spring's torque (the lumped model has no inertia between
anchors). Its vibratory shear stress is the nominal stress of the synthesised torque amplitude
(half peak-to-peak, all orders summed with their phases) in the journal or pin section,

    τ = SCF · 16 T D / (π (D⁴ − d_i⁴)),

with the fillet's torsional SCF from fetorsion's static 3D FE of the throw
(:func:`fetorsion.design.scf.fillet_scfs`). A chain file has no sections: its limits are torques.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..description.model import Crank
from ..errors import FetorsionError
from ..results import from_fields
from .scfset import SCFSet
from .scf import nominal_shear

if TYPE_CHECKING:
    from ..lumped_model.parts import PartChain
    from ..response.forced import ResponseResult


@dataclass(frozen=True)
class Fillet:
    """One journal–web or pin–web fillet: ``kind`` (``journal``/``pin``), 0-based ``index`` of
    that journal or pin, axial position ``x`` (m), section ``diameter`` and ``bore`` (m)."""

    kind: str
    index: int
    x: float
    diameter: float
    bore: float

    @property
    def label(self) -> str:
        return f"{'J' if self.kind == 'journal' else 'P'}{self.index + 1} fillet at x = {self.x * 1e3:.1f} mm"


def fillet_of_label(label: str) -> Fillet:
    """The fillet a :attr:`Fillet.label` names ("J2 fillet at x = 85.0 mm"), its diameter and bore
    unknown (NaN)."""
    head, x = label.split(" fillet at x = ")
    kind = "journal" if head[0] == "J" else "pin"
    return Fillet(kind, int(head[1:]) - 1, float(x.removesuffix(" mm")) / 1e3, float("nan"), float("nan"))


def fillets_of(crank: Crank, parts: PartChain | None = None) -> list[Fillet]:
    """Every journal–web and pin–web junction of ``crank``, front to rear (``parts``: its
    :class:`~fetorsion.lumped_model.parts.PartChain` by any web method, when the caller has it:
    the positions do not depend on the method)."""
    from ..lumped_model.parts import build_parts

    chain = build_parts(crank, "carter") if parts is None else parts
    parts = sorted((p for p in chain.parts if p.kind in ("journal", "pin", "web")), key=lambda p: p.x0)
    out = []
    for a, b in zip(parts, parts[1:]):
        if (a.kind == "web") == (b.kind == "web"):
            continue
        shaft = b if a.kind == "web" else a
        c = (crank.journals if shaft.kind == "journal" else crank.pins)[shaft.index]
        out.append(Fillet(shaft.kind, shaft.index, a.x1, c.diameter, c.bore))
    return out


def fillet_cuts(crank: Crank, fillets: list[Fillet]) -> np.ndarray:
    """(fillets, 3) centres of the section cuts at each fillet, m: on the crank axis for a
    journal fillet, on the pin's axis for a pin fillet (so the cut's moment about x is the
    torque its section carries)."""
    R = crank.engine.crank_radius
    out = np.zeros((len(fillets), 3))
    for k, f in enumerate(fillets):
        out[k, 0] = f.x
        if f.kind == "pin":
            a = crank.engine.crank_angles[f.index]
            out[k, 1:] = R * np.cos(a), R * np.sin(a)
    return out


def fillet_springs(fillets: list[Fillet], anchors) -> np.ndarray:
    """The 0-based spring (between anchors i and i + 1, m) that carries each fillet's torque."""
    anchors = np.asarray(anchors, dtype=float)
    if np.any(np.isnan(anchors)):
        raise FetorsionError("fillet stresses need a lumped crank model (a chain file has no sections)")
    return np.clip(np.searchsorted(anchors, [f.x for f in fillets]) - 1, 0, len(anchors) - 2)


def fillet_sections(fillets: list[Fillet], model) -> np.ndarray:
    """The 0-based section of ``model`` (a response setup or result) whose torque each fillet
    carries: the cut at the fillet when the model has cut sections (``section_x``: the
    condensed crank), else the chain spring between the anchors around it."""
    if getattr(model, "section_x", None) is not None:
        x = np.asarray(model.section_x, float)  # NaN: a section off the crank (a driveline's shaft)
        return np.array([int(np.nanargmin(np.abs(x - f.x))) for f in fillets])
    return fillet_springs(fillets, model.positions_m)


@dataclass
class StressResult:
    """Vibratory shear stress at every fillet against speed.

    Attributes
    ----------
    rpm : ndarray
    fillets : list of Fillet
    springs : ndarray of int
        The section (chain spring or cut) whose torque each fillet carries.
    scf : ndarray
        Torsional SCF of each fillet.
    nominal_pa, stress_pa : ndarray, shape (speeds, fillets)
        Nominal and concentrated vibratory shear stress (amplitude: half peak-to-peak), Pa.
    """

    name: str
    rpm: np.ndarray
    fillets: list
    springs: np.ndarray
    scf: np.ndarray
    nominal_pa: np.ndarray
    stress_pa: np.ndarray
    scf_source: str = ""

    def worst(self) -> tuple[int, int]:
        """(speed index, fillet index) of the largest stress."""
        s, f = np.unravel_index(np.argmax(self.stress_pa), self.stress_pa.shape)
        return int(s), int(f)

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        s, f = self.worst()
        return {"name": self.name, "rpm": self.rpm.tolist(), "fillets": [x.label for x in self.fillets],
                "springs": self.springs.tolist(), "scf": self.scf.tolist(), "scf_source": self.scf_source,
                "nominal_shear_pa": self.nominal_pa.tolist(), "shear_pa": self.stress_pa.tolist(),
                "worst": {"rpm": float(self.rpm[s]), "fillet": self.fillets[f].label,
                          "shear_pa": float(self.stress_pa[s, f])},
                "fillet_geometry": [asdict(x) for x in self.fillets]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "StressResult":
        """The result back from its :meth:`to_dict`. Where the fillets' geometry was not kept (a
        result written before it was), each fillet is read from its label: kind, index and place,
        its diameter and bore unknown (NaN)."""
        fillets = [from_fields(Fillet, f) for f in d["fillet_geometry"]] if "fillet_geometry" in d else [
            fillet_of_label(label) for label in d["fillets"]]
        return from_fields(cls, d, {"nominal_pa": "nominal_shear_pa", "stress_pa": "shear_pa"}, fillets=fillets)

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        lines = [f"{self.name}: vibratory shear stress at the fillets (amplitude, SCF from {self.scf_source})",
                 f"{'fillet':<28} {'SCF':>6} {'max nominal [MPa]':>18} {'max at fillet [MPa]':>20} {'at rpm':>7}"]
        for j, f in enumerate(self.fillets):
            i = int(np.argmax(self.stress_pa[:, j]))
            lines.append(f"{f.label:<28} {self.scf[j]:6.3f} {self.nominal_pa[i, j] / 1e6:18.2f} "
                         f"{self.stress_pa[i, j] / 1e6:20.2f} {self.rpm[i]:7.0f}")
        return "\n".join(lines)

    def plot(self, ax=None):
        """The largest fillet stress of journals and of pins against speed. Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4.5))
        for kind, style in (("journal", "-"), ("pin", "--")):
            cols = [j for j, f in enumerate(self.fillets) if f.kind == kind]
            if cols:
                ax.plot(self.rpm, self.stress_pa[:, cols].max(axis=1) / 1e6, style, label=f"worst {kind} fillet")
        ax.set_xlabel("engine speed [rpm]")
        ax.set_ylabel("vibratory shear stress [MPa]")
        ax.set_title(f"{self.name}: fillet shear stress (SCF × nominal)", fontsize=10, wrap=True)
        ax.legend(fontsize=8)
        return ax


def fillet_stress(crank: Crank, response: ResponseResult, scf: SCFSet,
                  fillets: list[Fillet] | None = None) -> StressResult:
    """Fillet stresses of ``response`` (a :class:`~fetorsion.response.forced.ResponseResult` of a
    lumped crank model or of the condensed crank) with the SCFs ``scf`` (``pin``, ``journal``, ``source``); ``fillets``:
    :func:`fillets_of` the crank, when the caller has them."""
    fillets = fillets_of(crank) if fillets is None else fillets
    springs = fillet_sections(fillets, response)
    torque = response.section_torque_nm[:, springs]  # (speeds, fillets)
    D = np.array([f.diameter for f in fillets])
    bore = np.array([f.bore for f in fillets])
    nominal = nominal_shear(torque, D, bore)
    factors = np.array([scf.torsion[f.kind] for f in fillets])
    return StressResult(response.name, response.rpm, fillets, springs, factors, nominal, nominal * factors,
                        scf.source)


def run_stress(crank: Crank, response=None, scf: SCFSet | None = None, **response_options) -> StressResult:
    """Vibratory shear stress at the fillets of a crank over its speed range.

    Parameters
    ----------
    crank : Crank
        With ``[excitation]`` and fillet radii.
    response : ResponseResult, optional
        Default :func:`fetorsion.response.forced.run_response` of ``crank`` (with
        ``response_options``).
    scf : dict, optional
        ``pin`` and ``journal`` SCFs and their ``source``; default
        :func:`fetorsion.design.scf.fillet_scfs` (shipped reference values or one static FE).
    **response_options
        To :func:`~fetorsion.response.forced.run_response` when ``response`` is not given.

    Returns
    -------
    StressResult
        Vibratory shear stress (Pa) at every fillet against speed (rpm).

    Examples
    --------
    >>> import fetorsion
    >>> res = fetorsion.run_stress(fetorsion.load("geometry/peugeot_glx_engine.toml"))  # lumped 17 DOF, shipped SCFs
    >>> import numpy as np
    >>> bool(np.allclose(res.stress_pa, res.scf * res.nominal_pa))  # SCF x 16 T D / (pi (D^4 - d^4)) per fillet
    True
    >>> s, f = res.worst()  # speed and fillet of the largest vibratory shear stress
    >>> bool(res.stress_pa[s, f] == res.stress_pa.max())
    True
    """
    from .scf import fillet_scfs
    from ..response.forced import run_response

    response = run_response(crank, **response_options) if response is None else response
    return fillet_stress(crank, response, fillet_scfs(crank) if scf is None else scf)
