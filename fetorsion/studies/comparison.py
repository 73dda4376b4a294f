"""The model against measurement: natural frequencies from a modal test and order cuts from a
torsiograph or an analyser, one table and one figure per quantity.

The model is one of :data:`SOURCES`. ``condensed`` (the default of ``fetorsion compare`` for a
crank description) is the condensed crank the run's verdict judged: free-free for a modal test
(a modal test hangs the crank free), in its bearings for what was measured on the running engine
(order cuts, torsiograph order maps). ``lumped17`` is the 17-DOF chain throughout (the fast,
approximate model; a chain file's own). ``fe`` takes the frequencies from the full free-free 3D
FE and the running measurements from the condensed crank in its bearings.

Frequencies: the modes fitted to measured FRFs (:func:`fetorsion.measured.modal.run_modal_fit`)
are paired, each with the nearest model frequency; the difference is (model − measured) /
measured.

Order cuts: a measured cut of engine order k against speed (a UFF 58 order function, a CSV cut,
or a torsiograph's tracked order) is set beside the model's own order-k amplitude of the same
angle at the station the sensor sat on (default the pulley end, where a torsiograph usually
sits). Compared are the peaks (amplitude in %, speed in rpm) and, over the speeds both cover, the
model's amplitude interpolated to each measured speed.

Waterfall: a torsiograph's every tracked order against mean speed (the measurement's own Campbell
diagram, as an order map), with the model's crossings on it: torsional mode n meets order k at
60 f_n / k rpm. A resonance the model places right lights up where its crossing is marked.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .pairing import nearest_modes, pair_frequencies, paired_mac
from ..description.defaults import LUMPED17
from ..errors import FetorsionError
from ..measured.dataset import MeasuredData
from .modelfrf import frf_overlays, model_receptances
from .modelstations import (fe_station_twists, model_order_cut, model_response, need_condensed, order_index,
                            response_stations, station_index)
from .ordermaps import Waterfall, is_steady, model_crossings

if TYPE_CHECKING:
    from ..description.chain_model import Chain, Network
    from ..description.model import Crank
    from ..fe.condensed import CondensedCrank
    from ..response.forced import ResponseResult

#: The models a measurement is set beside (see the module docstring).
SOURCES = ("condensed", LUMPED17, "fe")
#: Free-free modes of the condensed crank paired with a modal test's: the lowest this many.
CONDENSED_MODES = 20
@dataclass
class FrequencyComparison:
    """Measured natural frequencies, each with its nearest model frequency.

    Attributes
    ----------
    measured_hz, damping_ratios : ndarray (modes,)
        The fitted modes.
    model_hz : ndarray (modes,)
        The nearest model frequency of each, Hz.
    model_kinds : list of str
        What the paired model modes are (``torsional``, ``bending``, ...).
    source : str
        Which model.
    """

    source: str
    measured_hz: np.ndarray
    damping_ratios: np.ndarray
    model_hz: np.ndarray
    model_kinds: list
    #: MAC of each fitted shape with its paired model mode at the measured stations (a measured
    #: response node n is the chain's station n), or None where the shapes cannot be set side by side
    mac: np.ndarray | None = None
    #: Why there is no MAC, when there is none
    mac_note: str = ""
    #: Each measured FRF beside the model's (:func:`frf_overlays`), and why any is missing
    overlays: list = field(default_factory=list)
    overlay_note: str = ""
    #: The stability chart the measured modes were chosen from
    chart: object = None

    @property
    def difference_percent(self) -> np.ndarray:
        return 100.0 * (self.model_hz - self.measured_hz) / self.measured_hz

    def to_dict(self) -> dict:
        return {"source": self.source, "measured_hz": self.measured_hz.tolist(),
                "damping_ratios": self.damping_ratios.tolist(), "model_hz": self.model_hz.tolist(),
                "model_kinds": list(self.model_kinds), "difference_percent": self.difference_percent.tolist(),
                "mac": None if self.mac is None else self.mac.tolist(), "mac_note": self.mac_note,
                "frf_overlays": [o.station for o in self.overlays], "overlay_note": self.overlay_note,
                "stabilisation": None if self.chart is None else self.chart.to_dict()}

    def lines(self) -> list[str]:
        out = [f"natural frequencies: measured (fitted modes) against the nearest mode of the {self.source} model",
               f"{'mode':>4} {'measured [Hz]':>13} {'zeta [%]':>8} {'model [Hz]':>10} {'kind':>10} {'diff [%]':>8}"
               + (f" {'MAC':>6}" if self.mac is not None else "")]
        macs = self.mac if self.mac is not None else (None,) * len(self.measured_hz)
        out += [f"{j + 1:4d} {m:13.2f} {100 * z:8.3f} {f:10.2f} {k:>10} {d:+8.2f}" + ("" if c is None else f" {c:6.3f}")
                for j, (m, z, f, k, d, c) in enumerate(zip(self.measured_hz, self.damping_ratios, self.model_hz,
                                                            self.model_kinds, self.difference_percent, macs))]
        if self.mac_note:
            out.append(f"(no MAC: {self.mac_note})")
        if self.overlay_note:
            out.append(f"(FRF overlays: {self.overlay_note})")
        return out

    def plot(self, axes):
        """Onto ``axes`` (rows of two Axes): each measured FRF's magnitude and phase beside the
        model's, then the stabilisation diagram beside the model-against-measured frequencies."""
        for k, (row, o) in enumerate(zip(axes, self.overlays)):
            o.plot(row[0], row[1], self.measured_hz)
            if k:
                row[0].get_legend().remove()  # said once, on the first station
        last = axes[len(self.overlays)]
        if self.chart is not None:
            back = self.overlays[0] if self.overlays else None
            self.chart.plot(last[0], self.measured_hz, None if back is None else back.frequency_hz,
                            None if back is None else np.array([o.measured for o in self.overlays]))
        else:
            last[0].set_axis_off()
        ax = last[1]
        lim = [0, 1.1 * max(self.measured_hz.max(), self.model_hz.max())]
        ax.plot(lim, lim, "k--", lw=0.7)
        ax.plot(self.measured_hz, self.model_hz, "o")
        for m, mod, d in zip(self.measured_hz, self.model_hz, self.difference_percent):
            ax.annotate(f"{d:+.2f} %", (m, mod), fontsize=7, xytext=(4, -8), textcoords="offset points")
        ax.set_xlabel("measured [Hz]")
        ax.set_ylabel(f"model ({self.source}) [Hz]")
        ax.set_title("natural frequencies: model against measured", fontsize=9)

    @property
    def rows(self) -> int:
        """Rows of two panels :meth:`plot` draws."""
        return len(self.overlays) + 1


@dataclass
class OrderCutComparison:
    """One measured order cut beside the model's.

    Attributes
    ----------
    order : float
    rpm, measured_deg : ndarray
        The measured cut: speed and amplitude (zero to peak), degrees.
    model_rpm, model_deg : ndarray
        The model's cut of the same order at the same station.
    """

    name: str
    order: float
    station: str
    rpm: np.ndarray
    measured_deg: np.ndarray
    model_rpm: np.ndarray
    model_deg: np.ndarray
    #: The station's 1-based number among the model's stations
    #: (:func:`~fetorsion.studies.modelstations.response_stations`; 0 a twist)
    node: int = 0
    #: The measured phase at each speed, degrees (its own convention: a torsiograph's from its
    #: tooth 0), where the cut has one
    measured_phase_deg: np.ndarray | None = None

    def _overlap(self):
        both = (self.rpm >= self.model_rpm.min()) & (self.rpm <= self.model_rpm.max())
        if not both.any():
            raise FetorsionError(f"compare: {self.name} ({self.rpm.min():.0f}-{self.rpm.max():.0f} rpm) does not "
                                 f"overlap the model's speeds ({self.model_rpm.min():.0f}-{self.model_rpm.max():.0f} rpm)")
        return both

    def peaks(self) -> dict:
        """Both peaks inside the speeds both cover, and their differences (model against measured)."""
        both = self._overlap()
        mine = (self.model_rpm >= self.rpm[both].min()) & (self.model_rpm <= self.rpm[both].max())
        c = int(np.flatnonzero(both)[np.argmax(self.measured_deg[both])])
        m = int(np.flatnonzero(mine)[np.argmax(self.model_deg[mine])]) if mine.any() else int(
            np.argmin(np.abs(self.model_rpm - self.rpm[c])))
        model_at = np.interp(self.rpm[both], self.model_rpm, self.model_deg)
        return {"measured_peak_deg": float(self.measured_deg[c]), "measured_peak_rpm": float(self.rpm[c]),
                "model_peak_deg": float(self.model_deg[m]), "model_peak_rpm": float(self.model_rpm[m]),
                "peak_difference_percent": float(100 * (self.model_deg[m] - self.measured_deg[c]) / self.measured_deg[c]),
                "peak_rpm_difference": float(self.model_rpm[m] - self.rpm[c]),
                "rms_difference_deg": float(np.sqrt(np.mean((model_at - self.measured_deg[both]) ** 2)))}

    def to_dict(self) -> dict:
        return {"name": self.name, "order": self.order, "station": self.station, "node": self.node,
                "rpm": self.rpm.tolist(), "steady": self.steady(),
                "measured_phase_deg": None if self.measured_phase_deg is None else self.measured_phase_deg.tolist(),
                "measured_deg": self.measured_deg.tolist(), "model_rpm": self.model_rpm.tolist(),
                "model_deg": self.model_deg.tolist(), **self.peaks()}

    def steady(self) -> dict | None:
        """A cut measured at one speed (its speeds within 2 %: a steady record's blocks): the
        mean amplitude and its spread over the blocks, the mean phase, and the model's
        amplitude at that speed; None for a cut over a speed range."""
        rpm = np.asarray(self.rpm, float)
        if not is_steady(rpm):
            return None
        at = float(rpm.mean())
        out = {"rpm": at, "blocks": int(rpm.size), "measured_deg": float(self.measured_deg.mean()),
               "spread_percent": float(100 * np.ptp(self.measured_deg) / max(self.measured_deg.mean(), 1e-300)),
               "model_deg": float(np.interp(at, self.model_rpm, self.model_deg))}
        if self.measured_phase_deg is not None:
            out["phase_deg"] = float(np.degrees(np.angle(np.mean(np.exp(1j * np.radians(self.measured_phase_deg))))))
        return out

    def lines(self) -> list[str]:
        head = f"order {self.order:g} at {self.station} ({self.name}): "
        st = self.steady()
        if st is not None:
            phase = f", phase {st['phase_deg']:+.1f} deg" if "phase_deg" in st else ""
            return [head + f"steady at {st['rpm']:.0f} rpm over {st['blocks']} blocks: measured {st['measured_deg']:.4g} deg "
                    f"(spread {st['spread_percent']:.2g} %){phase}; model {st['model_deg']:.4g} deg: "
                    f"{100 * (st['model_deg'] / st['measured_deg'] - 1):+.1f} %"]
        p = self.peaks()
        phase = ""
        if self.measured_phase_deg is not None:
            c = int(np.argmin(np.abs(self.rpm - p["measured_peak_rpm"])))
            phase = f" (phase {self.measured_phase_deg[c]:+.1f} deg)"
        return [head + f"measured peak {p['measured_peak_deg']:.4g} deg{phase} at "
                f"{p['measured_peak_rpm']:.0f} rpm, model {p['model_peak_deg']:.4g} deg at {p['model_peak_rpm']:.0f} rpm: "
                f"{p['peak_difference_percent']:+.1f} %, {p['peak_rpm_difference']:+.0f} rpm; rms difference over the "
                f"common speeds {p['rms_difference_deg']:.3g} deg"]


#: What a printed phase is, said once above the order cuts that carry one.
PHASE_REFERENCE = ("phases (deg): arg c_k of the cosine series psi(theta) = Re sum_k c_k exp(i k theta) of the "
                   "vibration angle, theta the shaft's angle from the record's tooth 0 (a 60-2 wheel: the first "
                   "tooth after its gap)")


def waterfall(name: str, track, crank, source: str = LUMPED17, condensed=None) -> Waterfall:
    """A torsiograph track (:class:`~fetorsion.measured.torsiograph.OrderTrack`) with the crossings
    of the torsional modes of the running model (:func:`running_frequencies`)."""
    f = running_frequencies(crank, source, condensed)
    return Waterfall(name, track, f, model_crossings(f, track.orders, track.rpm))


def running_frequencies(crank, source: str = LUMPED17, condensed=None) -> np.ndarray:
    """The torsional natural frequencies (Hz) of the model of the running engine: the lumped
    chain's, or the condensed crank's in its bearings (its modes whose journals' kinetic energy
    is mostly torsion)."""
    if source == LUMPED17:
        from ..lumped_model.lumped import lumped

        return np.asarray(lumped(crank, 17).frequencies_hz, float)
    md = need_condensed(condensed, source).modes("bearings", CONDENSED_MODES)
    return np.array([f for f, k in zip(md.frequencies_hz, md.kinds) if k == "torsional"])


@dataclass
class ComparisonResult:
    """The model against every measured quantity given.

    Attributes
    ----------
    model : str
        The model of the running measurements (order cuts, waterfalls).
    gaps : list of str
        Lines saying how far a lumped answer is from the condensed crank's, where both were at hand.
    """

    name: str
    frequencies: list = field(default_factory=list)
    order_cuts: list = field(default_factory=list)
    waterfalls: list = field(default_factory=list)
    model: str = ""
    gaps: list = field(default_factory=list)
    #: What reading the measurement found and mended (lost or spurious tooth edges)
    notes: list = field(default_factory=list)
    #: Why :meth:`plot` cannot draw the figure again ("": it can): a result read back whose FRF
    #: overlays and stability chart ``to_dict`` does not keep
    unplotted: str = ""

    @classmethod
    def from_dict(cls, d) -> "ComparisonResult":
        """The result back from its :meth:`to_dict`: the frequencies (without the measured FRFs
        and stability chart, which only the figure draws), the order cuts and the waterfalls."""
        from ..measured.torsiograph import OrderTrack
        from ..results import from_fields

        freqs = [from_fields(FrequencyComparison, f) for f in d["frequencies"]]
        cuts = [from_fields(OrderCutComparison, c) for c in d["order_cuts"]]
        falls = [Waterfall(w["name"], OrderTrack.from_dict(w["track"]), np.asarray(w["model_hz"], dtype=float),
                           [(c["mode"], c["order"], c["rpm"]) for c in w["crossings"]]) for w in d["waterfalls"]]
        lost = any(f["frf_overlays"] or f["stabilisation"] is not None for f in d["frequencies"])
        return from_fields(cls, d, frequencies=freqs, order_cuts=cuts, waterfalls=falls,
                           unplotted="the measured FRFs and stability chart are not in results.json" if lost else "")

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"name": self.name, "model": self.model, "frequencies": [f.to_dict() for f in self.frequencies],
                "order_cuts": [c.to_dict() for c in self.order_cuts],
                "waterfalls": [w.to_dict() for w in self.waterfalls], "gaps": list(self.gaps),
                "notes": list(self.notes)}

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        lines = [f"{self.name}: model against measurement"]
        for f in self.frequencies:
            lines += f.lines()
        if self.order_cuts or self.waterfalls:
            lines.append(f"running measurements against the {self.model}")
        if any(c.measured_phase_deg is not None for c in self.order_cuts):
            lines.append(PHASE_REFERENCE)
        for c in self.order_cuts:
            lines += c.lines()
        for w in self.waterfalls:
            lines += w.lines()
        return "\n".join(lines + list(self.gaps) + [f"note: {n}" for n in self.notes])

    def plot(self):
        """The measured FRFs beside the model's (magnitude and phase per station), the
        stabilisation diagram and the frequencies; each order cut (measured points, model line);
        each waterfall. Returns the Figure."""
        import matplotlib.pyplot as plt

        if self.unplotted:
            raise FetorsionError(f"compare: the figure is not drawn again: {self.unplotted}")
        # a steady record's cuts are points at one speed: drawn on its order spectrum, not as cuts
        steady = {id(c) for c in self.order_cuts if c.steady() is not None
                  and any(c.name == f"{w.name}, torsiograph" for w in self.waterfalls)}
        cuts = [c for c in self.order_cuts if id(c) not in steady]
        rows = sum(f.rows for f in self.frequencies) + len(cuts) + len(self.waterfalls)
        if rows == 0:
            raise FetorsionError("compare: nothing measured to plot")
        fig = plt.figure(figsize=(11, 3.0 * rows + 0.6))
        grid = fig.add_gridspec(rows, 2)
        k = 0
        for f in self.frequencies:
            f.plot([[fig.add_subplot(grid[k + r, 0]), fig.add_subplot(grid[k + r, 1])] for r in range(f.rows)])
            k += f.rows
        for c in cuts:
            ax = fig.add_subplot(grid[k, :])
            ax.plot(c.rpm, c.measured_deg, ".", label=f"measured: {c.name}")
            ax.plot(c.model_rpm, c.model_deg, "-", label="model")
            ax.set_xlabel("engine speed [rpm]")
            ax.set_ylabel(f"order {c.order:g} at {c.station} [deg]")
            ax.legend(fontsize=7)
            k += 1
        for w in self.waterfalls:
            w.plot(fig.add_subplot(grid[k, :]), [c for c in self.order_cuts if id(c) in steady
                                                 and c.name == f"{w.name}, torsiograph"])
            k += 1
        fig.suptitle(f"{self.name}: model against measurement", fontsize=10, wrap=True)
        fig.tight_layout()
        return fig


def model_modes(crank, source: str = LUMPED17, condensed=None, mesh_size: float | None = None):
    """(frequencies Hz, kinds, shapes at the model's stations (modes, stations)) of the free-free
    ``source`` model: the chain's stations; the condensed crank's masters' θx; the full FE's
    twist of each master's part (:func:`~fetorsion.studies.modelstations.fe_station_twists`)."""
    if source not in SOURCES:
        raise FetorsionError(f"compare: source {source!r}: choose one of {', '.join(SOURCES)}")
    if source == LUMPED17:
        from ..lumped_model.lumped import lumped

        res = lumped(crank, 17)
        f = np.asarray(res.frequencies_hz, float)
        return f, ["torsional"] * f.size, np.asarray(res.mode_shapes)
    if source == "condensed":
        cc = need_condensed(condensed, source)
        md = cc.modes("free", CONDENSED_MODES)
        rx = [cc.dof(lb, "rx") for lb in cc.labels]  # node n the n-th master, as the UFF is written
        return np.asarray(md.frequencies_hz, float), list(md.kinds), md.vectors[rx].T
    from ..description.defaults import DEFAULT_MESH_SIZE
    from ..fe.crankfe import run_modal

    res = run_modal(crank, DEFAULT_MESH_SIZE if mesh_size is None else mesh_size)
    return np.asarray(res.frequencies_hz, float), list(res.kinds), fe_station_twists(res)


def compare_frequencies(estimate, crank, source: str = LUMPED17, condensed=None,
                        mesh_size: float | None = None) -> FrequencyComparison:
    """Pair the fitted modes of ``estimate`` (:class:`~fetorsion.measured.modal.ModalEstimate`)
    with the model's, and their shapes by the MAC at the measured stations (node n the model's
    n-th station: :func:`model_modes`)."""
    f, kinds, shapes = model_modes(crank, source, condensed, mesh_size)
    model_hz, model_kinds = pair_frequencies(estimate.frequencies_hz, f, kinds)
    named = "chain" if not hasattr(crank, "journals") else source  # a chain file is its own model, not a partition
    values, note = paired_mac(estimate, shapes, nearest_modes(estimate.frequencies_hz, f))
    return FrequencyComparison(named, np.asarray(estimate.frequencies_hz, float),
                               np.asarray(estimate.damping_ratios, float), model_hz, model_kinds, values, note)


def compare_order_cut(function, response, station: str | None = None) -> OrderCutComparison:
    """Set a measured order cut (a :class:`~fetorsion.measured.uff.MeasuredFunction` of kind
    ``order function`` against speed, angle in rad) beside the model's."""
    if function.kind != "order function" or function.abscissa_quantity != "speed" or function.order is None:
        raise FetorsionError(f"compare: {function.label or 'a function'} is not an order cut against speed "
                             "(kind 'order function', abscissa rpm, its order stated)")
    if function.unit != "rad":
        raise FetorsionError(f"compare: {function.label or 'an order cut'} is in {function.unit}; the model's "
                             "order cuts are angles (deg, mrad or rad)")
    measured = np.asarray(function.ordinate)
    phase = np.degrees(np.angle(measured)) if np.iscomplexobj(measured) else None
    if isinstance(station, tuple):  # a twist: the first station's angle less the second's
        (ja, na), (jb, nb) = (station_index(response, x) for x in station)
        k = order_index(response, function.order)
        model = np.degrees(np.abs(response.theta[:, k, ja] - response.theta[:, k, jb]))
        return OrderCutComparison(function.label or f"order {function.order:g}", float(function.order),
                                  f"{na} - {nb} twist", np.asarray(function.abscissa, float),
                                  np.degrees(np.abs(measured)), np.asarray(response.rpm, float), model, 0, phase)
    j, name = station_index(response, station)
    node = 1 + [d for _, d in response_stations(response)].index(j)
    return OrderCutComparison(function.label or f"order {function.order:g}", float(function.order), name,
                              np.asarray(function.abscissa, float), np.degrees(np.abs(measured)),
                              np.asarray(response.rpm, float), model_order_cut(response, function.order, j), node,
                              phase)


def run_comparison(crank: Crank | Chain | Network, measured: MeasuredData, source: str = LUMPED17,
                   station: str | None = None, condensed: CondensedCrank | None = None,
                   response: ResponseResult | None = None, mesh_size: float | None = None,
                   reference: ResponseResult | None = None) -> ComparisonResult:
    """The model of a crank against measured data.

    Parameters
    ----------
    crank : Crank
        With an ``[excitation]`` where order cuts are compared.
    measured : MeasuredData
        FRFs, order cuts, torsiograph order maps, the band to fit the FRFs' modes in and where each
        cut was measured, as ``fetorsion.cli.measured.read_measured`` reads them.
    source : {"condensed", LUMPED17, "fe"}
        The model (see the module docstring).
    station : str, optional
        Where the order cuts were measured: ``pulley`` (default), ``flywheel``, or a station's
        name or number (:func:`~fetorsion.studies.modelstations.response_stations`).
    condensed : CondensedCrank, optional
        The condensed crank, with its bearings; needed unless ``source`` is ``lumped17``.
    response : ResponseResult, optional
        The running model's forced response, if already solved
        (:func:`~fetorsion.studies.modelstations.model_response`).
    mesh_size : float, optional
        The full FE's mesh size (``source`` ``fe``), m; default the modal default.
    reference : ResponseResult, optional
        The condensed crank's forced response, beside a lumped comparison: each order cut then
        gets a line saying how far the lumped peak is from it (:func:`gap_line`; none where the
        condensed crank has no such station).

    Returns
    -------
    ComparisonResult

    Examples
    --------
    >>> import numpy as np
    >>> import fetorsion
    >>> from fetorsion.measured.dataset import MeasuredData
    >>> from fetorsion.measured.uff import MeasuredFunction
    >>> chain = fetorsion.load("examples/mendes2008/mwm6_chain.toml")
    >>> f1 = fetorsion.lumped(chain).frequencies_hz[0]
    >>> f = np.linspace(0.7 * f1, 1.3 * f1, 1501)
    >>> wn, w = 2 * np.pi * f1, 2 * np.pi * f
    >>> frf = MeasuredFunction("frf", f, "frequency", 1 / (wn**2 - w**2 + 0.02j * wn * w), "rad", response=(1, 4),
    ...                        reference=(1, 4), reference_unit="N m", label="station 1")  # a "modal test" at f1, 1 %
    >>> res = fetorsion.run_comparison(chain, MeasuredData(frfs=(frf,), band=(0.85 * f1, 1.15 * f1)))
    >>> pair = res.frequencies[0]
    >>> pair.source, pair.model_kinds, bool(abs(pair.difference_percent[0]) < 0.1)  # the fit's tested bound
    ('chain', ['torsional'], True)
    """
    from ..measured.modal import run_modal_fit

    if source not in SOURCES:
        raise FetorsionError(f"compare: source {source!r}: choose one of {', '.join(SOURCES)}")
    running = ("the chain file's own model" if not hasattr(crank, "journals") else
               "the lumped 17-DOF chain" if source == LUMPED17 else "condensed crank in its bearings")
    out = ComparisonResult(crank.name, model=running)  # the response's own name once it is solved
    if measured.frfs:
        estimate = run_modal_fit(measured.frfs, measured.band)
        found = compare_frequencies(estimate, crank, source, condensed, mesh_size)
        found.chart = estimate.chart
        if source != LUMPED17 and condensed is None:
            found.overlay_note = "the model's FRFs are the condensed crank's, which was not built"
        else:
            found.overlays, found.overlay_note = frf_overlays(crank, measured.frfs, source, condensed)
        out.frequencies.append(found)
    if measured.cuts:
        if getattr(crank, "excitation", None) is None:
            raise FetorsionError(f"compare: {crank.name} has no [excitation] table: the model has no order cuts")
        response = response if response is not None else model_response(crank, source, condensed)
        out.model = response.model
        for c in measured.cuts:
            cut = compare_order_cut(c, response, measured.station_of(c.label, station))
            out.order_cuts.append(cut)
            if reference is not None:
                try:
                    out.gaps.append(gap_line(cut, compare_order_cut(c, reference, measured.station_of(c.label, station))))
                except FetorsionError:  # a chain station the condensed crank does not have
                    pass
    out.notes += list(measured.notes)
    out.waterfalls += [waterfall(name, track, crank, source, condensed) for name, track in measured.tracks]
    return out


def gap_line(lumped_cut: OrderCutComparison, engine_cut: OrderCutComparison) -> str:
    """How far a lumped model's order-cut peak is from the condensed crank's (both set beside
    the same measured cut, so both peaks lie in the speeds it covers)."""
    mine, theirs = lumped_cut.peaks(), engine_cut.peaks()
    return (f"(lumped answer; the condensed crank in its bearings, stored, gives order {engine_cut.order:g} at "
            f"{engine_cut.station} a peak of {theirs['model_peak_deg']:.4g} deg at {theirs['model_peak_rpm']:.0f} rpm: "
            f"the lumped one is {100 * (mine['model_peak_deg'] / theirs['model_peak_deg'] - 1):+.1f} % from it)")


def model_predictions(crank: Crank | Chain | Network, comparison: ComparisonResult,
                      response: ResponseResult | None = None, source: str = LUMPED17,
                      condensed: CondensedCrank | None = None, band: tuple[float, float] | None = None) -> list:
    """The model's side of a comparison as measured functions, for a universal file (UFF 58).

    Parameters
    ----------
    crank : Crank
        The crank compared.
    comparison : ComparisonResult
        What was compared (:func:`run_comparison`).
    response : ResponseResult, optional
        The running model's forced response, if already solved.
    source, condensed
        The model, as for :func:`run_comparison`.
    band : (float, float), optional
        The measured band the modes were fitted in, Hz (default: the fitted modes' span).

    Returns
    -------
    list of MeasuredFunction
        Its order cut (complex, rad, against rpm) at the station of each compared cut, and, where
        modes were compared, its free-free receptances at the pulley and flywheel ends to a
        torque at the pulley end over the measured band ±20 % (rad/N·m). Nodes: the stations'
        1-based numbers (:func:`~fetorsion.studies.modelstations.response_stations`: a chain's
        stations, the condensed crank's masters), direction 4 (rotation about x); read back, each
        is the station it came from.
    """
    from ..measured.uff import MeasuredFunction

    out = []
    if comparison.order_cuts:
        response = response if response is not None else model_response(crank, source, condensed)
        stations = response_stations(response)
        for c in comparison.order_cuts:
            j = stations[c.node - 1][1]
            k = int(np.flatnonzero(np.isclose(response.orders, c.order, rtol=0, atol=1e-9))[0])
            out.append(MeasuredFunction("order function", np.asarray(response.rpm, float), "speed",
                                        np.asarray(response.theta[:, k, j]), "rad", (c.node, 4),
                                        label=f"model order {c.order:g} at {c.station}", order=float(c.order)))
    for f in comparison.frequencies:
        lo, hi = band if band is not None else (f.measured_hz.min(), f.measured_hz.max())
        hz = np.linspace(0.8 * lo, 1.2 * hi, 2000)
        if source == LUMPED17:
            from ..lumped_model.lumped import lumped

            last = len(lumped(crank, 17).inertias_kgm2)
            H = model_receptances(crank, hz)
        else:
            last = len(need_condensed(condensed, source).labels)
            H = model_receptances(crank, hz, condensed=condensed)
        for row, node in zip(H, (1, last)):
            out.append(MeasuredFunction("frf", hz, "frequency", row, "rad", (node, 4), reference=(1, 4),
                                        reference_unit="N m", label=f"model receptance {node}:4 / 1:4"))
    return out
