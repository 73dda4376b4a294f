"""What a report presents: one typed outcome per analysis of a run, filled by the run
(:mod:`fetorsion.app.run`) and read field by field by the Markdown and the web page.

An outcome holds the analysis' results objects (each with ``table()``, ``plot()`` and
``to_dict()``) and the file names of the pictures the run saved for it. A section whose
analysis was not part of the run is ``None`` (left out of the report); one whose analysis had
nothing to work on is :class:`Skipped`, with the reason the report prints.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the results each outcome holds, named for the reader and the checks, not imported at run time
    from ..description.model import Bearings, Crank
    from ..description.chain_model import Chain, Network
    from ..design.assessment import CrankAssessment
    from ..design.coupling_heat import CouplingHeat
    from ..design.gear_hammering import GearHammering
    from ..design.barred_passage import BarredPassage
    from ..design.tvc_cases import TVCCase
    from ..design.tvc_modes import ModeRow, TVCCampbell
    from ..design.shaft_verdict import ShaftVerdict
    from ..design.crank_verdict import CrankVerdict
    from ..design.m53 import M53Result
    from ..design.scfset import SCFSet
    from ..design.stress import StressResult
    from ..design.verdict import VerdictResult
    from ..excitation.campbell import CampbellResult
    from ..fe.condensed import CondensedCrank, CondensedModes
    from ..fe.crankfe import CrankModal
    from ..lumped_model.lumped import LumpedResult
    from ..response.coupled import CoupledResponse
    from ..response.forced import ResponseResult
    from ..response.transient import TransientResult
    from ..solid.recognise import SolidFeatures
    from ..studies.comparison import ComparisonResult
    from ..studies.sensitivity import SensitivityResult
    from ..studies.study import StudyResult


@dataclass(frozen=True)
class Skipped:
    """An analysis of the run that had nothing to work on, and why (a sentence)."""

    reason: str


@dataclass(frozen=True)
class TVCOutcome:
    """A propulsion line's torsional vibration calculation (docs/propulsion-tvc.md): the network at
    its couplings' settled temperatures (``network``: the mass-elastic data; ``modes``: its natural
    frequencies), the forced response with the propellers' and engine's excitation, the shaft
    sections against UR M68 (None: no section stated), the couplings' heat (None: no coupling), the
    gear meshes against hammering (None: no gear), the pictures' file names ("" where none) and what is assumed, one sentence each."""

    network: Network
    modes: LumpedResult
    response: ResponseResult
    shafts: ShaftVerdict | None
    couplings: CouplingHeat | None
    shaft_image: str
    heat_image: str
    assumptions: tuple[str, ...]
    #: Every gear mesh's vibratory against mean torque (None: no gear, or no propeller to give the mean).
    hammering: GearHammering | None = None
    hammering_image: str = ""
    #: Normal running as a case, the misfire of each cylinder and the worst of them (None: no engine).
    normal: TVCCase | None = None
    misfires: tuple[TVCCase, ...] = ()
    worst_misfire: TVCCase | None = None
    misfire_note: str = ""
    misfire_shaft_image: str = ""
    #: The time-domain passage of each barred range against τ_T (normal running's, the worst misfire's)
    #: and each passage's picture.
    passages: tuple[BarredPassage, ...] = ()
    passage_images: tuple[str, ...] = ()
    #: The mode table (each mode's frequency, resonances in the speed range, relative amplitudes) and
    #: the Campbell diagram with the barred ranges.
    mode_rows: tuple[ModeRow, ...] = ()
    campbell_image: str = ""
    #: What the Campbell diagram draws besides the modes (None: not drawn).
    campbell: TVCCampbell | None = None
    #: Each damper failed in each of its states (:func:`fetorsion.design.tvc_cases.damper_failure_cases`).
    failed_dampers: tuple[TVCCase, ...] = ()
    #: Each coupling at both ends of its sheet's stiffness tolerance (:func:`fetorsion.design.tvc_cases.tolerance_cases`).
    tolerances: tuple[TVCCase, ...] = ()
    #: The network's fetorsion crank against UR M53 in each configuration (its name, the result;
    #: :func:`fetorsion.design.tvc_crank.crank_m53`), normal running first; empty: no crank, or not
    #: computed (``crank_m53_note`` says why); the picture of normal running's.
    crank_m53: tuple[tuple[str, M53Result], ...] = ()
    crank_m53_note: str = ""
    crank_m53_image: str = ""

    def to_dict(self) -> dict:
        """results.json's ``tvc`` entry: normal running's response, verdicts and dampers' heat, each misfire, the passages,
        the mode table, the modes at the settled temperatures, the Campbell diagram's data and the assumptions
        (:func:`fetorsion.report.load.tvc_outcome` reads it back)."""
        worst = self.worst_misfire
        return {"response": self.response.to_dict(), "shafts": self.shafts.to_dict() if self.shafts else None,
                "couplings": self.couplings.to_dict() if self.couplings else None,
                "hammering": self.hammering.to_dict() if self.hammering else None,
                "damper_heat_w": list(self.normal.damper_heat_w) if self.normal else [],
                **({k: getattr(self.normal, k) for k in ("crank_torque_nm", "crank_torque_rpm", "crank_section")}
                   if self.normal else {}),
                "misfires": [c.to_dict() for c in self.misfires], "misfire_note": self.misfire_note,
                "failed_dampers": [c.to_dict() for c in self.failed_dampers],
                "tolerances": [c.to_dict() for c in self.tolerances],
                "worst_misfire_cylinder": None if worst is None else worst.misfire + 1,
                "barred_passages": [p.to_dict() for p in self.passages],
                "modes": [r.to_dict() for r in self.mode_rows], "network_modes": self.modes.to_dict(),
                "campbell": self.campbell.to_dict() if self.campbell else None, "assumptions": list(self.assumptions),
                "crank_m53": [{"configuration": n, "result": r.to_dict()} for n, r in self.crank_m53],
                "crank_m53_note": self.crank_m53_note}


#: The file names of the TVC section's pictures (the run saves them, ``fetorsion report`` draws them again).
TVC_IMAGES = {"shafts": "tvc_shafts.png", "heat": "tvc_coupling_heat.png", "hammering": "tvc_hammering.png",
              "misfire_shafts": "tvc_shafts_misfire.png", "campbell": "tvc_campbell.png", "crank_m53": "tvc_crank_m53.png"}


def passage_image(k: int) -> str:
    """The file name of the ``k``-th (0-based) barred passage's picture."""
    return f"tvc_passage_{k + 1}.png"


@dataclass(frozen=True)
class ChainOutcome:
    """A chain file's modes: its :class:`~fetorsion.lumped_model.lumped.LumpedResult` and their plot."""

    chain: LumpedResult
    image: str


@dataclass(frozen=True)
class LumpedOutcome:
    """Every partition with every web method: ``table[method]`` lists the LumpedResults in the
    order of :data:`~fetorsion.lumped_model.lumped.PARTITIONS`; ``skipped[method]`` says why a
    method could not be used; ``image`` the default model's mode shapes."""

    table: dict[str, list[LumpedResult]]
    skipped: dict[str, str]
    image: str


@dataclass(frozen=True)
class ModeImage:
    """The picture of one FE mode: its index in the modal result (0-based) and its file (the FE
    step names it ``mode_<n>_<kind>.png``, n from 1; :mod:`.load` finds it again by that name)."""

    mode: int
    file: str


@dataclass(frozen=True)
class FEOutcome:
    """The 3D FE modal analysis (a :class:`~fetorsion.fe.crankfe.CrankModal`), its global
    element size (m) and the pictures of its torsional and first bending modes."""

    modal: CrankModal
    mesh_size_m: float
    images: tuple[ModeImage, ...]
    #: A CAD crank's picture of the journals, pins, fillets and drillings found on its solid.
    solid_image: str = ""
    #: What was found on a CAD crank's solid (None: a crank built from its dimensions).
    solid_features: SolidFeatures | None = None
    #: The report page's interactive 3D view of the pictured modes (HTML), where the run drew it
    #: ("": the page draws it from the mesh, or shows the pictures where the mesh is not kept).
    view_html: str = ""


@dataclass(frozen=True)
class CondensedFacts:
    """What the report says of the condensed crank: its masters' labels, its reduced and full
    DOF, its condensation's timings (s) and the main bearings it is held in (an oil film's loads
    found from the crank's forces). Made from the live crank by :meth:`of`, read back from its
    entry of ``results.json`` by :meth:`from_dict`."""

    labels: tuple[str, ...]
    reduced_dofs: int
    full_dofs: int
    timings_s: dict[str, float]
    main_bearings: Bearings

    @classmethod
    def of(cls, cc: CondensedCrank) -> "CondensedFacts":
        """The facts of the condensed crank ``cc``."""
        return cls(tuple(cc.labels), int(cc.reduced.size), int(cc.full_dofs), dict(cc.timings_s),
                   cc.crank.main_bearings)

    @classmethod
    def from_dict(cls, d: dict[str, object]) -> "CondensedFacts":
        """The facts back from ``results.json``'s ``bearings`` entry (its ``main_bearings``; a
        folder written before it was kept: rigid or stated bearings from its ``support``, an oil
        film refused)."""
        from ..description.model import Bearings
        from ..errors import FetorsionError
        from ..results import from_fields

        if "main_bearings" in d:
            bearings = from_fields(Bearings, d["main_bearings"])
        elif d["support"]["oil_film_load_n"] is None:
            s = d["support"]
            bearings = Bearings(tuple(s["radial_stiffness_n_per_m"]), tuple(s["radial_damping_ns_per_m"]), (),
                                given=bool(s["from_description"]))
        else:
            raise FetorsionError("the oil film's operating point is not in results.json (written before it was kept)")
        return cls(tuple(m["label"] for m in d["masters"]), int(d["reduced_dofs"]), int(d["full_dofs"]),
                   dict(d["timings_s"]), bearings)


@dataclass(frozen=True)
class BearingsOutcome:
    """The condensed crank free-free and in its bearings (``condensed``: what the report says of
    it; ``free``, ``bearings``: its modes, the lowest :data:`~fetorsion.fe.condensed.CHECKED_MODES`
    and every one up to the first carrying torsion), the 17-DOF chain against both
    (``chain[web method]``: ``f1_hz``, ``vs_free``, ``vs_bearings``), the coupled forced response
    when the crank is excited, the pictures."""

    condensed: CondensedFacts
    free: CondensedModes
    bearings: CondensedModes
    chain: dict[str, dict[str, float]]
    f1_free_hz: float
    f1_bearings_hz: float
    images: tuple[str, ...]
    coupled: CoupledResponse | None = None


@dataclass(frozen=True)
class CampbellOutcome:
    """The Campbell diagram and the forced response, with their pictures."""

    campbell: CampbellResult
    response: ResponseResult
    campbell_image: str
    response_image: str


@dataclass(frozen=True)
class SensitivityOutcome:
    """f1 against each uncertain input, the FE check of the largest, the Monte Carlo and Sobol'
    studies (``studies[method]``) and their pictures (``study_images[method]``)."""

    sensitivity: SensitivityResult
    fe_check: list
    image: str
    studies: dict[str, StudyResult]
    study_images: dict[str, str]


@dataclass(frozen=True)
class VerdictOutcome:
    """The verdict against the description's limits with the damper inertia ratio ``mu`` and the
    fillet SCFs it used (None for torque limits),
    the fillet stress without a damper, and the picture."""

    verdict: VerdictResult
    mu: float
    scf: SCFSet | None
    image: str
    stress: StressResult | None = None
    #: The model the verdict was computed on (a chain's or network's own: the setup's ``model``).
    model: str = ""


@dataclass(frozen=True)
class FatigueOutcome:
    """A crank's verdict: its fatigue (:class:`~fetorsion.design.crank_verdict.CrankVerdict`:
    every configuration by both methods, one deciding, the damping and its source, the flip
    damping ratio, the recommended damper); ``assessment`` the ``fe`` path's detail of the crank as
    described (every fillet and oil bore, each at its worst speed); ``stress`` the vibratory
    torsional stress at the fillets, an input (no verdict of its own); the SCFs and pictures."""

    verdict: CrankVerdict
    assessment: CrankAssessment | None
    stress: StressResult
    scf: SCFSet
    images: tuple[str, ...]
    model: str = ""


@dataclass
class MeasuredOutcome:
    """The model against the measured files given to the run (:func:`fetorsion.studies.comparison.run_comparison`)
    and its figure."""

    comparison: ComparisonResult
    image: str


@dataclass(frozen=True)
class TransientOutcome:
    """The time-domain run-up of a chain or network over its checked speed range: the
    :class:`~fetorsion.response.transient.TransientResult`, its rate (rpm/s), the order cuts
    compared with the steady-state response at the Campbell crossings
    (:class:`~fetorsion.response.transient.OrderCut`), the wall time of the run (s) and the
    pictures (the waterfall, the order cuts against the steady state)."""

    transient: TransientResult
    rate_rpm_per_s: float
    cuts: tuple
    seconds: float
    waterfall_image: str
    cuts_image: str


@dataclass
class RunOutcome:
    """Every section of one run, in pipeline order, and each step's wall time (s)."""

    crank: Crank | Chain | Network
    path: str
    lumped: LumpedOutcome | ChainOutcome | None = None
    fe: FEOutcome | None = None
    bearings: BearingsOutcome | None = None
    campbell: CampbellOutcome | Skipped | None = None
    sensitivity: SensitivityOutcome | Skipped | None = None
    verdict: VerdictOutcome | Skipped | None = None
    fatigue: FatigueOutcome | Skipped | None = None
    measured: MeasuredOutcome | Skipped | None = None
    transient: TransientOutcome | Skipped | None = None
    #: A network with a propeller or shaft sections: its TVC (None otherwise: no section)
    tvc: TVCOutcome | Skipped | None = None
    timings_s: dict[str, float] | None = None
    #: The sections taken from the store (section -> its key): computed by an earlier run of the
    #: same description, options and code (:mod:`fetorsion.app.run_store`), not by this one.
    from_store: dict[str, str] = field(default_factory=dict)
    #: The report folder the run wrote
    folder: str = ""
    #: A network file whose condensed crank part ``crank`` is: the name of that driveline (the
    #: response, fatigue and verdict are the crank's in it); "" for a crank, chain or network run.
    driveline: str = ""
