"""A run's report folder read back: ``results.json`` into the typed :class:`~.outcomes.RunOutcome`
that the Markdown and the web page present, with no FE and nothing recomputed.

Each section's results come back through their own ``from_dict``
(:class:`fetorsion.results.Result`); the pictures are the file names the run gave them, found
in the folder. The description is the one ``results.json`` recorded (its text, read again as
it was; a folder written before the text was kept: the path its report names).

Read back today: the lumped models (a chain's and a network's too: a network's layout and modes,
not its matrices), the FE modes, the Campbell diagram and forced response, the fillet stress, the
sensitivity studies, a chain's or network's verdict, the measured comparison (its figure only
where no FRF was measured: the FRFs and stability chart are not kept) and the run-up (its
envelope, order track and order cuts; its time signals thinned as stored). The condensed crank in its bearings is read
back from the modes, facts and coupled response its entry keeps (a folder written before it kept
the coupled response's pin torque and journal bending, or an oil film's operating point: not read
back). A crank's fatigue verdict is read back from its entry: each configuration's M53 result
and every method's answer as stored, the ``fe`` path's assessment of the crank as described
(``fe_detail``), the damping band, flip and bridge, the recommended damper's design (a folder
written before the entry kept its model and which configuration carries the recommended damper:
not read back). A propulsion line's TVC is read back from its entry (normal running's response and
verdicts, each misfire's verdicts, the barred passages, the mode table, the modes at the settled
temperatures, the Campbell diagram's data and the assumptions; a misfire's response is not kept), its
networks the described one with the couplings at the temperatures it keeps (a folder written before
the entry kept these: not read back). A section not read back is named in :attr:`LoadedRun.unread` with the reason.
"""

from __future__ import annotations

import json
import re
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from collections.abc import Iterable
from typing import TYPE_CHECKING

from ..description.chain_model import Chain, Network
from ..description.files import load
from ..description.model import Crank
from ..errors import FetorsionError
from ..results import JSONObject
from .outcomes import (TVC_IMAGES, BearingsOutcome, CampbellOutcome, ChainOutcome, CondensedFacts, FatigueOutcome, FEOutcome,
                       LumpedOutcome, MeasuredOutcome, ModeImage, RunOutcome, SensitivityOutcome, Skipped,
                       TransientOutcome, TVCOutcome, VerdictOutcome, passage_image)

if TYPE_CHECKING:
    from ..design.stress import StressResult

#: The file a run writes its figures into.
RESULTS_FILE = "results.json"


@dataclass
class LoadedRun:
    """A report folder read back: the run's typed outcome, the JSON it was read from, and the
    sections it holds that were not read back (section -> why)."""

    outcome: RunOutcome
    results: JSONObject
    unread: dict[str, str] = field(default_factory=dict)


def read_results_json(folder: Path) -> dict[str, object]:
    """``folder``'s results.json as a dict; a missing folder or file, or one that is not a run's
    JSON, is refused with one message naming it."""
    path = Path(folder) / RESULTS_FILE
    if not Path(folder).is_dir():
        raise FetorsionError(f"{folder}: no such report folder")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise FetorsionError(f"{folder}: no {RESULTS_FILE} (not a folder written by fetorsion run)") from None
    except (OSError, ValueError) as exc:
        raise FetorsionError(f"{path}: cannot be read as a run's results ({exc})") from None
    if not isinstance(data, dict) or "timings_s" not in data:
        raise FetorsionError(f"{path}: not a run's results (no timings_s)")
    return data


def described_path(folder: Path, data: dict[str, object]) -> str:
    """The description's path as the run named it: recorded in results.json, else (a folder
    written before it was) the ``Description:`` line of its report.md."""
    entry = data.get("description")
    if isinstance(entry, dict):
        return str(entry["path"])
    try:
        found = re.search(r"^Description: `(.+)`$", (Path(folder) / "report.md").read_text(encoding="utf-8"), re.M)
    except OSError:
        found = None
    if found is None:
        raise FetorsionError(f"{folder}: {RESULTS_FILE} records no description and report.md names none")
    return found.group(1)


def read_description(path: str, text: str | None) -> Crank | Chain | Network:
    """The description the run read: the file at ``path`` when it still holds the recorded
    ``text`` (or no text was recorded: a folder written before it was), else ``text`` itself,
    read from a temporary file (a file it names by a relative path is then not found)."""
    here = Path(path).is_file()
    if here and (text is None or Path(path).read_text(encoding="utf-8") == text):
        return load(path)
    if text is None:
        raise FetorsionError(f"{path}: the run's description is no longer there, and results.json does not "
                             "keep its text (a folder written before it did)")
    with tempfile.TemporaryDirectory(prefix="fetorsion-description-") as tmp:
        copy = Path(tmp) / Path(path).name
        copy.write_text(text, encoding="utf-8")
        return load(copy)


def skipped(crank, data: dict[str, object], key: str) -> Skipped | None:
    """The reason the run gave for skipping section ``key`` (results.json's ``skipped``); in a
    folder written before the reasons were kept, the reason the run gives when the description
    lacks the table the section needs, else None."""
    if key in data.get("skipped", {}):
        return Skipped(data["skipped"][key])
    if "skipped" in data:
        return None
    missing = {"campbell": getattr(crank, "excitation", None) is None and "the description has no `[excitation]` table",
               "sensitivity": not getattr(crank, "uncertainty", ()) and "the description has no `[uncertainty]` table",
               "fatigue": isinstance(crank, Crank) and crank.excitation is None
               and "the description has no [excitation] table"}
    return Skipped(missing[key]) if missing.get(key) else None


def _lumped(data: dict[str, object]) -> LumpedOutcome | ChainOutcome | None:
    from ..lumped_model.lumped import LumpedResult

    if "lumped" not in data:
        return None
    if "chain" in data["lumped"]:  # a chain's or network's modes
        return ChainOutcome(LumpedResult.from_dict(data["lumped"]["chain"]), "chain_modes.png")
    table = {m: [LumpedResult.from_dict(r) for r in rs] for m, rs in data["lumped"].items()}
    return LumpedOutcome(table, dict(data.get("lumped_skipped", {})), "lumped_modes_17dof.png")


def mode_images(names: Iterable[str]) -> tuple[ModeImage, ...]:
    """The FE mode pictures among the file ``names`` (``mode_NN_kind.png``), in their order."""
    return tuple(ModeImage(int(m.group(1)) - 1, name) for name in names
                 if (m := re.fullmatch(r"mode_(\d+)_[a-z]+\.png", name)))


def _fe(data: dict[str, object], pictures: list[str]) -> FEOutcome | None:
    from ..fe.crankfe import CrankModal

    if "fe" not in data:
        return None
    images = mode_images(pictures)
    solid = "solid_recognised.png" if "solid_recognised.png" in pictures else ""
    return FEOutcome(CrankModal.from_dict(data["fe"]), data["fe"]["mesh_size_m"], images, solid)


def _campbell(crank, data: dict[str, object]) -> CampbellOutcome | Skipped | None:
    import numpy as np

    from ..excitation.campbell import CampbellResult, major_orders
    from ..response.forced import ResponseResult

    if "campbell" not in data:
        return skipped(crank, data, "campbell")
    camp = CampbellResult.from_dict(data["campbell"])
    if "major_orders" not in data["campbell"] and getattr(crank, "engine", None) is not None:
        # written before the major orders were kept: the engine's, among the diagram's orders
        camp.major = tuple(float(q) for q in major_orders(crank.engine) if np.any(np.isclose(camp.orders, q)))
    return CampbellOutcome(camp, ResponseResult.from_dict(data["response"]), "campbell.png", "response.png")


def _sensitivity(crank, data: dict[str, object]) -> SensitivityOutcome | Skipped | None:
    from ..studies.sensitivity import SensitivityResult
    from ..studies.study import StudyResult

    if "sensitivity" not in data:
        return skipped(crank, data, "sensitivity")
    sens = SensitivityResult.from_dict(data["sensitivity"])
    studies = {m: StudyResult.from_dict(s) for m, s in data.get("studies", {}).items()}
    return SensitivityOutcome(sens, list(data["sensitivity"].get("fe_check", [])), "sensitivity.png", studies,
                              {"montecarlo": "f1_montecarlo.png", "sobol": "f1_sobol.png"})


def _bearings(data: dict[str, object]) -> BearingsOutcome | None:
    """The condensed crank in its bearings (None: not in the run); one of a folder written before
    results.json kept what its section reads is refused by name (FetorsionError)."""
    from ..fe.condensed import CondensedModes
    from ..response.coupled import CoupledResponse

    d = data.get("bearings")
    if d is None:
        return None
    coupled = CoupledResponse.from_dict(d["coupled_response"]) if "coupled_response" in d else None
    images = ("modes_free_and_bearings.png",) + (("coupled_response.png",) if coupled is not None else ())
    return BearingsOutcome(CondensedFacts.from_dict(d), CondensedModes.from_rows("free", d["free"]),
                           CondensedModes.from_rows("bearings", d["bearings"]), dict(d["lumped_17dof"]),
                           d["f1_free_hz"], d["f1_bearings_hz"], images, coupled)


def _verdict(crank, data: dict[str, object]) -> VerdictOutcome | Skipped | None:
    from ..design.scfset import SCFSet
    from ..design.stress import StressResult
    from ..design.verdict import VerdictResult

    d = data.get("verdict")
    if d is None:
        return skipped(crank, data, "verdict")
    scf = SCFSet.from_dict(d["scf"]) if d.get("scf") else None
    stress = StressResult.from_dict(data["stress"]) if scf is not None and "stress" in data else None
    return VerdictOutcome(VerdictResult.from_dict(d), d["mu"], scf, "verdict.png", stress, d.get("model", ""))


#: The pictures of a crank's fatigue verdict, in the order its section shows them.
FATIGUE_IMAGES = ("fatigue_safety.png", "fatigue_haigh.png", "damper_design.png")


def _fatigue(crank, data: dict[str, object]) -> FatigueOutcome | Skipped | None:
    """A crank's fatigue verdict (None: not in the run); one of a folder written before
    results.json kept what its section reads is refused by name (FetorsionError)."""
    from ..design.stress import StressResult

    d = data.get("fatigue")
    if d is None:
        return skipped(crank, data, "fatigue")
    return read_fatigue(d, StressResult.from_dict(data["stress"]) if "stress" in data else None)


def read_fatigue(d: JSONObject, stress: StressResult | None) -> FatigueOutcome:
    """A crank's fatigue verdict from its results.json entry ``d`` and the run's fillet stress
    (``stress``, a :class:`~fetorsion.design.stress.StressResult` or None); one written before the
    entry kept its model is refused by name (FetorsionError)."""
    from ..design.crank_verdict import CrankVerdict
    from ..design.scfset import SCFSet

    if "model" not in d:
        raise FetorsionError("its model is not in results.json (written before it was kept)")
    verdict = CrankVerdict.from_dict(d)
    assessment = next(c for c in verdict.configs if c.as_described).fe
    # a run that left the fe path out drew no Haigh diagram
    images = FATIGUE_IMAGES if assessment is not None else tuple(i for i in FATIGUE_IMAGES if "haigh" not in i)
    return FatigueOutcome(verdict, assessment, stress, SCFSet.from_dict(d["scf"]), images, d["model"])


def _measured(crank, data: dict[str, object]) -> MeasuredOutcome | Skipped | None:
    from ..studies.comparison import ComparisonResult

    if "measured" not in data:
        return skipped(crank, data, "measured")
    return MeasuredOutcome(ComparisonResult.from_dict(data["measured"]), "measured.png")


def _transient(crank, data: dict[str, object]) -> TransientOutcome | Skipped | None:
    d = data.get("transient")
    if d is None:
        return skipped(crank, data, "transient")
    # imported only for a run-up: the time domain's compiled kernel takes 3 s to import, a third
    # of `fetorsion report` on a crank's folder
    from ..response.transient import OrderCut, TransientResult

    cuts = tuple(OrderCut.from_dict(c) for c in d["order_cuts"])
    return TransientOutcome(TransientResult.from_dict(d), d["rate_rpm_per_s"], cuts, d["seconds"],
                            "runup_waterfall.png", "runup_order_cuts.png")


def tvc_outcome(net: Network, d: dict[str, object]) -> TVCOutcome:
    """A propulsion line's TVC read back from its ``tvc`` entry (:meth:`TVCOutcome.to_dict`) and the
    described network ``net``: each configuration's network is ``net`` with its couplings at the
    temperatures the entry keeps. One written before the entry kept its response, modes, Campbell data,
    assumptions or passages' windows is refused by name (FetorsionError)."""
    from ..design.barred_passage import BarredPassage
    from ..design.coupling_heat import at_temperatures
    from ..design.gear_hammering import GearHammering
    from ..design.m53 import M53Result
    from ..design.shaft_verdict import ShaftVerdict
    from ..design.tvc_cases import TVCCase, with_coupling_stiffness, with_failed_damper
    from ..design.tvc_modes import ModeRow, TVCCampbell
    from ..lumped_model.lumped import LumpedResult
    from ..response.forced import ResponseResult

    missing = [k for k in ("network_modes", "campbell", "assumptions") if k not in d] + (
        ["the response"] if "modal_damping_ratio" not in d["response"] else [])
    if missing or any("window_rpm" not in s for p in d["barred_passages"] for s in p["sections"]):
        raise FetorsionError(f"written before its entry kept {', '.join(missing) or 'the passages windows'}")

    def settled(case: dict) -> Network:
        rows = case["couplings"]["rows"] if case.get("couplings") else []
        described = net if case.get("failed_damper") is None else \
            with_failed_damper(net, case["failed_damper"] - 1, case["damper_state"])
        if case.get("coupling") is not None:
            described = with_coupling_stiffness(described, case["coupling"] - 1, case["stiffness_factor"])
        return at_temperatures(described, [r["temperature_c"] for r in rows]) if rows else described

    response = ResponseResult.from_dict(d["response"])
    normal = TVCCase.from_dict({"case": "normal running", "misfire_cylinder": None, **d}, settled(d), response)
    misfires = tuple(TVCCase.from_dict(c, settled(c)) for c in d["misfires"])
    worst = None if d["worst_misfire_cylinder"] is None else misfires[d["worst_misfire_cylinder"] - 1]
    passages = tuple(BarredPassage.from_dict(p) for p in d["barred_passages"])
    crank_m53 = tuple((c["configuration"], M53Result.from_dict(c["result"])) for c in d.get("crank_m53", []))
    shafts, heat, hammer = normal.shafts, normal.couplings, normal.hammering
    return TVCOutcome(normal.network, LumpedResult.from_dict(d["network_modes"]), response, shafts, heat,
                      TVC_IMAGES["shafts"] if shafts else "", TVC_IMAGES["heat"] if heat else "",
                      tuple(d["assumptions"]), hammer, TVC_IMAGES["hammering"] if hammer else "", normal, misfires,
                      worst, d["misfire_note"], TVC_IMAGES["misfire_shafts"] if worst and worst.shafts else "",
                      passages, tuple(passage_image(k) for k in range(len(passages))),
                      tuple(ModeRow.from_dict(r) for r in d["modes"]), TVC_IMAGES["campbell"],
                      TVCCampbell.from_dict(d["campbell"]),
                      tuple(TVCCase.from_dict(c, settled(c)) for c in d.get("failed_dampers", [])),
                      tuple(TVCCase.from_dict(c, settled(c)) for c in d.get("tolerances", [])),
                      crank_m53, d.get("crank_m53_note", ""), TVC_IMAGES["crank_m53"] if crank_m53 else "")


def _tvc(crank, data: dict[str, object]) -> TVCOutcome | Skipped | None:
    """The propulsion line's TVC (None: not in the run)."""
    if "tvc" not in data:
        return skipped(crank, data, "tvc")
    try:
        return tvc_outcome(crank, data["tvc"])
    except FetorsionError as exc:
        raise FetorsionError(f"the propulsion line's TVC: {exc}") from None


def load_run(folder: str | Path) -> LoadedRun:
    """Read the report folder ``folder`` (one ``fetorsion run`` wrote) back, as the module
    docstring says: the typed outcome, the JSON, and the sections not read back with the reason.
    """
    folder = Path(folder)
    data = read_results_json(folder)
    path = described_path(folder, data)
    entry = data.get("description")
    crank = read_description(path, entry.get("text") if isinstance(entry, dict) else None)
    if isinstance(crank, Network) and crank.condensed_crank() is not None:  # the run reported that crank
        crank = crank.condensed_crank()
    pictures = sorted(p.name for p in folder.glob("*.png"))
    driveline = data.get("driveline", {}).get("network", "") if isinstance(data.get("driveline"), dict) else ""
    outcome = RunOutcome(crank, path, timings_s=dict(data["timings_s"]), folder=str(folder), driveline=driveline,
                         from_store=dict(data.get("from_store", {})))
    outcome.lumped, outcome.fe = _lumped(data), _fe(data, pictures)
    unread = {}
    if "fe" in data and not {"backend", "mesh_quality"} <= set(data["fe"]):
        unread["fe"] = "written before results.json kept the solver's backend and the mesh's quality, which it prints"
    try:
        outcome.bearings = _bearings(data)
    except FetorsionError as exc:
        unread["bearings"] = str(exc)
    outcome.campbell = _campbell(crank, data)
    outcome.sensitivity = _sensitivity(crank, data)
    outcome.verdict, outcome.measured = _verdict(crank, data), _measured(crank, data)
    outcome.transient = _transient(crank, data)
    try:
        outcome.fatigue = _fatigue(crank, data)
    except FetorsionError as exc:
        unread["fatigue"] = f"the crank's fatigue verdict: {exc}"
    try:
        outcome.tvc = _tvc(crank, data)
    except FetorsionError as exc:
        unread["tvc"] = str(exc)
    return LoadedRun(outcome, data, unread)


def load_results(folder: str | Path) -> RunOutcome:
    """A run's report folder read back as its typed :class:`~.outcomes.RunOutcome`.

    The sections :func:`load_run` cannot read back (one written before results.json kept what
    it reads: see this module's docstring) are left ``None``; :func:`load_run` names them.

    Parameters
    ----------
    folder : str or Path
        A folder written by ``fetorsion run``.

    Returns
    -------
    RunOutcome
        Every section read back, typed, with the pictures' file names.

    Examples
    --------
    >>> import fetorsion
    >>> run = fetorsion.load_results("results/renault21")
    >>> round(float(run.campbell.campbell.frequencies_hz[0]), 1)
    532.9
    """
    return load_run(folder).outcome
