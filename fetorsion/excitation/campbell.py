"""Campbell (interference) diagram with the excitation of each order measured ([Seyedalian] eq. 21).

A mode j of frequency f_j meets order q at n = 60 f_j / q rpm. Whether that crossing
matters depends on the cylinders' torque harmonic T_q at that speed and on how the
cylinders' contributions add on the mode: the phase-vector sum

    S_jq = Σ_c a_jc e^{−i q φ_c}

(a_jc the mode's twist at the pin of cylinder c, φ_c the firing angle of cylinder c).
The severity of a crossing is the resonant vibratory angle at the pulley it drives, for a
modal damping ratio ζ:

    θ_pulley = |p_j| · |T_q| · |S_jq| / (2 ζ ω_j² m_j)       (m_j the modal inertia)

which does not depend on how the mode shape is normalised. ``phase_sum`` = |S_jq| / Σ|a_jc|
says how well the cylinders add (1 = all in phase, 0 = cancelled).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..description.model import Crank
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from .loads import cylinder_loads
from .torque import cycle_angle, firing_angles
from ..lumped_model.damped import DampedSystem, damped_modes_of
from ..lumped_model.lumped import lumped, lumped_modes_source, modal_damping_ratios, stated_damping
from ..lumped_model.network import network_damper_dof, rear_coordinate
from ..modes import TorsionalModes, modal_damping_matrix
from ..results import from_fields
from ..description.defaults import DEFAULT_PARTITION, DEFAULT_TORSIONAL_MODES, DEFAULT_WEB_METHOD

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence
    from ..description.model import Engine
    from ..lumped_model.parts import PartChain


def damper_model(crank, res):
    """(M, K, at, scale) of ``crank``'s lumped result ``res`` for its dampers: the model's own
    matrices (a network's in its reduced coordinates, the gears' ratios in them) and where each
    damper acts and how it is referred (:func:`fetorsion.lumped_model.network.network_damper_dof`, the
    forced response's placement; a chain: its front and rear stations)."""
    M, K = res.matrices()
    if res.network is None:
        return M, K, None, None
    dof, scale = network_damper_dof(crank, res.network, rear_coordinate(crank, res.network.masters))
    return M, K, (lambda d: dof[d.at]), (lambda d: scale.get(d.at, 1.0))


def damped_crossing_angles(crank, res, zeta: float, omega: np.ndarray, Tq: np.ndarray, phasors: np.ndarray):
    """The pulley's complex angle (rad) at each crossing from the full solve of the chain with its
    dampers: the order's torques ``Tq`` (modes, orders, cylinders: each cylinder's own harmonic) at
    ω (modes, 1) rad/s, the modal damping ratio ``zeta`` on the chain's own modes plus a chain
    file's stated dampers."""
    M, K, at, scale = damper_model(crank, res)
    C = modal_damping_matrix(M, K, zeta)
    if isinstance(crank, (Chain, Network)):
        C_stated, H = stated_damping(crank, res)
        C, K = C + C_stated, K + 1j * H
    system = DampedSystem(M, K, C, crank.dampers, stations=len(M), at=at, scale=scale)
    N = len(system.M)
    loads = np.zeros(Tq.shape[:2] + (N,), dtype=complex)
    loads[..., : len(M)] = np.einsum("joc,oc,cd->jod", Tq, phasors, res.pin_weights)
    omegas = np.broadcast_to(omega, Tq.shape[:2])
    return np.linalg.solve(system.matrix(omegas), loads[..., None])[..., 0, 0]




def lumped_modes(crank: Crank | Chain, partition: int = DEFAULT_PARTITION,
                 web_method: str = DEFAULT_WEB_METHOD, parts: PartChain | None = None) -> TorsionalModes:
    """Torsional modes of a lumped partition (or of a chain file) in the form the Campbell analysis
    uses (``parts``: the crank's PartChain for ``web_method``, when the caller has it)."""
    return lumped(crank, partition, web_method, parts=parts).torsional_modes()


@dataclass(frozen=True)
class Crossing:
    """Mode ``mode`` meeting order ``order`` at ``rpm``, and how severely it is excited.

    Attributes
    ----------
    mode : int
        1-based mode number.
    frequency_hz : float
        The mode's natural frequency, Hz.
    order : float
        Engine order.
    rpm : float
        Crossing speed, 60 f / q.
    in_range : bool
        Inside the operating speed range.
    torque_harmonic_nm : float
        One cylinder's torque harmonic ``|T_q|`` at that speed, N·m.
    phase_sum : float
        The phase-vector sum's share of its terms' magnitudes, 0..1.
    severity : float
        The resonant response in the result's ``severity_unit``.
    mode_kind : str
        Torsional or bending and the strain-energy split (a condensed crank's modes), else empty.
    worst_section : str
        The section of the largest stress (a condensed crank's crossings with named sections).
    worst_cut : int or None
        Its index, where the sections are not named.
    shear_mpa, bending_mpa : float or None
        Nominal shear and bending stress there, MPa (a condensed crank's crossings).
    """

    mode: int
    frequency_hz: float
    order: float
    rpm: float
    in_range: bool
    torque_harmonic_nm: float
    phase_sum: float
    severity: float
    mode_kind: str = ""
    worst_section: str = ""
    worst_cut: int | None = None
    shear_mpa: float | None = None
    bending_mpa: float | None = None

    def to_dict(self) -> dict:
        """The crossing's figures as JSON; the fields its model does not give left out."""
        return {k: v for k, v in asdict(self).items() if v is not None and v != ""}


def most_severe(crossings: Iterable[Crossing], count: int | None = None) -> list[Crossing]:
    """The crossings inside the speed range, most severe first (the first ``count`` of them)."""
    return sorted((c for c in crossings if c.in_range), key=lambda c: -c.severity)[:count]


@dataclass
class CampbellResult:
    """Crossings of modes and orders, with their measured severity.

    Attributes
    ----------
    crossings : list of Crossing
        Every mode against every order (severity: resonant vibratory angle at the pulley,
        degrees, for the modal damping, unless ``severity_unit`` says otherwise).
    """

    name: str
    source: str
    frequencies_hz: np.ndarray
    orders: np.ndarray
    speed_range_rpm: tuple[float, float]
    damping_ratio: float | tuple[float, ...]
    crossings: list[Crossing]
    harmonics_table: dict[str, dict[str, list[float] | float]] = field(default_factory=dict)
    severity_unit: str = "deg: resonant vibratory angle at the pulley"
    #: The engine's major orders among ``orders`` (:func:`major_orders`), drawn bold
    major: tuple[float, ...] = ()

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"name": self.name, "source": self.source, "frequencies_hz": self.frequencies_hz.tolist(),
                "orders": self.orders.tolist(), "speed_range_rpm": list(self.speed_range_rpm),
                "modal_damping_ratio": (list(self.damping_ratio) if isinstance(self.damping_ratio, tuple)
                                        else self.damping_ratio),
                "severity_unit": self.severity_unit, "crossings": [c.to_dict() for c in self.crossings],
                "torque_harmonics": self.harmonics_table, "major_orders": list(self.major)}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "CampbellResult":
        """The result back from its :meth:`to_dict`."""
        return from_fields(cls, d, {"damping_ratio": "modal_damping_ratio", "harmonics_table": "torque_harmonics",
                                    "major": "major_orders"})

    def table(self, only_in_range: bool = True) -> str:
        """The result as plain text: the table the command line prints."""
        rows = sorted((c for c in self.crossings if c.in_range or not only_in_range), key=lambda c: -c.severity)
        kinds = any(c.mode_kind for c in self.crossings)
        unit = self.severity_unit.split(":")[0]
        head = (f"{'mode':>4} {'f [Hz]':>8} {'order':>6} {'rpm':>7} {'|T_q| [N m]':>12} {'phase sum':>9} "
                f"{'severity [' + unit + ']':>15}")
        head += f"  {'kind (torsion/bending share)'}" if kinds else ""
        lines = [head, "-" * len(head)]
        lines += [f"{c.mode:>4} {c.frequency_hz:8.1f} {c.order:6.1f} {c.rpm:7.0f} "
                  f"{c.torque_harmonic_nm:12.2f} {c.phase_sum:9.3f} {c.severity:15.4g}"
                  + (f"  {c.mode_kind}" if kinds else "") for c in rows]
        return "\n".join(lines)

    def plot(self, ax=None, max_rpm: float | None = None):
        """Campbell diagram: modes, order lines (the engine's major orders bold), the operating
        range, crossings sized by severity with a key of three sizes in the severity's unit."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(9, 6))
        lo, hi = self.speed_range_rpm
        top = max_rpm or hi * 1.1
        fmax = max(self.frequencies_hz) * 1.15
        ax.axvspan(lo, hi, color="0.92", zorder=0, label="operating range")
        rpm = np.array([0.0, top])
        major = {round(float(q), 9) for q in self.major}
        # the order lines that leave through the top crowd there: a label is kept where it has room
        # (a major order's always), so that "12 11.5 11" does not print as "1211.511"
        room, kept, labelled = 0.025 * top, [], set()
        ends = {float(q): min(top, fmax * 60 / q) for q in self.orders}
        for q in sorted(self.orders, key=lambda q: (round(float(q), 9) not in major, ends[float(q)])):
            e = ends[float(q)]
            if e >= top or round(float(q), 9) in major or all(abs(e - k) > room for k in kept):
                kept.append(e)
                labelled.add(float(q))
        for q in self.orders:
            bold = round(float(q), 9) in major
            ax.plot(rpm, q * rpm / 60, color="0.1" if bold else "0.6", lw=1.6 if bold else 0.6, zorder=1,
                    label="major order (all cylinders in phase)" if bold and round(float(q), 9) == min(major) else None)
            if float(q) in labelled:
                end = ends[float(q)]
                ax.text(end, q * end / 60, f" {q:g}", fontsize=8 if bold else 7, color="0.1" if bold else "0.45",
                        va="bottom", fontweight="bold" if bold else None)
        zetas = self.damping_ratio if isinstance(self.damping_ratio, tuple) else None
        for j, f in enumerate(self.frequencies_hz):
            damped = f", ζ {zetas[j]:.3g}" if zetas and j < len(zetas) else ""
            ax.axhline(f, color=f"C{j}", lw=1.2, label=f"mode {j + 1}: {f:.0f} Hz{damped}" if f >= 100
                       else f"mode {j + 1}: {f:.3g} Hz{damped}")
        inside = [c for c in self.crossings if c.in_range]
        unit = self.severity_unit.split(":")[0]
        if inside:
            sev = np.array([c.severity for c in inside])
            top_sev = sev.max()
            area = (lambda v: 20 + 400 * np.asarray(v) / top_sev)  # noqa: E731
            ax.scatter([c.rpm for c in inside], [c.frequency_hz for c in inside], s=area(sev),
                       facecolors="none", edgecolors="crimson", lw=1.3, zorder=3)
            for v in size_key(top_sev):  # the key: the same area for the same severity
                ax.scatter([], [], s=area(v), facecolors="none", edgecolors="crimson", lw=1.3,
                           label=f"crossing, {v:g} {unit}")
        ax.set_xlim(0, top)
        ax.set_ylim(0, fmax)
        ax.set_xlabel("engine speed [rpm]")
        ax.set_ylabel("frequency [Hz]")
        damping = "ζ per mode in the key" if isinstance(self.damping_ratio, tuple) else f"ζ = {zeta_text(self.damping_ratio)}"
        ax.set_title(f"{self.name}\nCampbell diagram, modes from {self.source}\n{damping}", fontsize=9, pad=14)
        ax.legend(fontsize=7, loc="upper left", labelspacing=1.1, borderpad=0.8)
        ax.figure.tight_layout()
        return ax


def size_key(largest: float) -> list[float]:
    """Three round severities for a size key: the largest crossing's, rounded down to 1, 2 or 5
    times a power of ten, and a half and a fifth of that (each a round number too)."""
    if not largest > 0:
        return []
    decade = 10.0 ** np.floor(np.log10(largest))
    top = max(m for m in (1.0, 2.0, 5.0, 10.0) if m * decade <= largest * (1 + 1e-12)) * decade
    return [float(f"{v:.3g}") for v in (top, top / 2, top / 5)]


def zeta_text(zeta: float | tuple[float, ...]) -> str:
    """A damping ratio, or one per mode, as text."""
    return ", ".join(f"{z:.3g}" for z in zeta) if isinstance(zeta, tuple) else f"{zeta:g}"


#: The highest order a forced response sums by default. Orders to 12 left out up to 12 % of a
#: section's torque at speeds away from resonance (the Renault 21 at 2098 rpm; 2.8 % of its largest)
#: and 4.4 % of the geared example's largest; orders to 24 are within 0.3 % of orders to 48 on every
#: example chain, network and reference crank (tests/test_forced.py).
RESPONSE_HIGHEST_ORDER = 24.0


#: The highest order the Campbell diagram draws and the report's major orders go to.
CAMPBELL_HIGHEST_ORDER = 12.0


def default_orders(crank: Crank, highest: float = CAMPBELL_HIGHEST_ORDER) -> np.ndarray:
    """0.5, 1, 1.5 … for a 4-stroke, 1, 2 … for a 2-stroke, up to ``highest`` (the Campbell
    diagram's orders; a response sums to :data:`RESPONSE_HIGHEST_ORDER`: :func:`response_orders`)."""
    step = 2 * np.pi / cycle_angle(crank.engine)
    return np.arange(1, int(round(highest / step)) + 1) * step


def response_orders(crank: Crank) -> np.ndarray:
    """The orders a forced response sums by default: :func:`default_orders` to
    :data:`RESPONSE_HIGHEST_ORDER`."""
    return default_orders(crank, RESPONSE_HIGHEST_ORDER)


def order_sums(engine, pin_amplitudes, orders) -> np.ndarray:
    """|Σ_c a_c e^{−i q φ_c}| / Σ_c |a_c|: how much of each order ``q`` the cylinders' torques
    put into a mode with twist ``a_c`` at cylinder c's pin (``pin_amplitudes`` (modes,
    cylinders) or (cylinders,)), φ_c the firing angles (1: every cylinder in phase; 0: they
    cancel). A rigid crank (every a_c = 1) gives the engine's own order content: an even-firing
    four-stroke of z cylinders adds fully at the multiples of z/2 and cancels the rest."""
    a = np.atleast_2d(np.asarray(pin_amplitudes, float))
    phasors = np.exp(-1j * np.asarray(orders, float)[:, None] * firing_angles(engine)[None, :])  # (orders, cylinders)
    return np.abs(a @ phasors.T) / np.abs(a).sum(axis=1, keepdims=True)


def major_orders(engine: Engine, highest: float = CAMPBELL_HIGHEST_ORDER) -> np.ndarray:
    """The orders up to ``highest`` in which every cylinder's torque adds in phase on a rigid crank
    (:func:`order_sums` of 1 to 1e-9): the engine's major orders (a V8's 4, 8, 12)."""
    step = 2 * np.pi / cycle_angle(engine)  # 0.5 for a 4-stroke, 1 for a 2-stroke
    orders = np.arange(1, int(round(highest / step)) + 1) * step
    return orders[order_sums(engine, np.ones(engine.cylinders), orders)[0] > 1 - 1e-9]


def run_campbell(crank: Crank | Chain | Network, modes: TorsionalModes | None = None,
                 orders: Sequence[float] | np.ndarray | None = None, speed_range: Sequence[float] | None = None,
                 n_modes: int = DEFAULT_TORSIONAL_MODES, damping_ratio: float | None = None, partition: int = DEFAULT_PARTITION,
                 web_method: str = DEFAULT_WEB_METHOD, parts: PartChain | None = None) -> CampbellResult:
    """Crossings of the first ``n_modes`` torsional modes with each order, and their severity.

    Parameters
    ----------
    crank : Crank or Chain
        With an ``[excitation]`` table (a chain also with ``[engine]`` and ``cylinder_stations``).
    modes : TorsionalModes, optional
        Default: the 17-DOF lumped model (:func:`lumped_modes`).
    orders : array_like, optional
        Orders to check; default 0.5 … 12 for a 4-stroke.
    speed_range : (float, float), optional
        Operating range, rpm; default the description's ``speed_range_rpm``.
    n_modes : int
        How many of the lowest modes to include.
    damping_ratio : float, optional
        Modal damping ratio ζ for the severity; default the description's. A chain's stated
        dampers add their equivalent ratio per mode (:func:`modal_damping_ratios`).
    partition, web_method, parts : int, str, PartChain
        The lumped model when ``modes`` is not given (``parts``: the crank's, when the caller
        has them). The description's ``[[dampers]]`` then
        join the modes and add their damping per mode
        (:func:`fetorsion.lumped_model.damped.damped_modes`); given ``modes`` are taken as they are.

    Examples
    --------
    >>> import fetorsion
    >>> from fetorsion.excitation.campbell import run_campbell
    >>> res = run_campbell(fetorsion.load("geometry/renault21.toml"))
    >>> all(c.rpm > 0 for c in res.crossings)
    True
    """
    if crank.excitation is None:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [excitation] table")
    gained = None
    if modes is None and crank.dampers:
        res = lumped(crank, partition, web_method, parts=parts)
        M, K, at, scale = damper_model(crank, res)
        modes, gained = damped_modes_of(M, K, res.pin_weights, crank.dampers, at=at, scale=scale,
                                        source=f"{lumped_modes_source(res)} with {len(crank.dampers)} damper(s)")
    modes = modes or lumped_modes(crank, partition, web_method, parts)
    orders = default_orders(crank) if orders is None else np.asarray(orders, dtype=float)
    if np.any(orders <= 0):
        raise FetorsionError(f"orders must be > 0, got {orders.tolist()}")
    lo, hi = crank.excitation.checked_range if speed_range is None else speed_range
    zeta = crank.excitation.modal_damping_ratio if damping_ratio is None else damping_ratio
    zeta_base = zeta
    k = min(n_modes, len(modes.frequencies_hz))
    f = modes.frequencies_hz[:k]
    zeta_modes = np.full(k, zeta)
    if isinstance(crank, (Chain, Network)) and crank.has_dampers:
        res = lumped(crank)
        C, H = stated_damping(crank, res)
        zeta_modes = zeta + modal_damping_ratios(res.frequencies_hz[:k], res.mode_shapes[:k], res.inertias_kgm2, C, H)
        zeta = tuple(float(z) for z in zeta_modes)
    if gained is not None:
        zeta_modes = zeta_modes + gained[:k]
        zeta = tuple(float(z) for z in zeta_modes)
    rpm = 60 * f[:, None] / orders[None, :]  # (modes, orders)
    loads = cylinder_loads(crank)
    phasors = loads.phasors(orders)  # (orders, cylinders)
    phase_sum = order_sums(crank.engine, modes.pin_amplitudes[:k], orders)  # (modes, orders)
    # (modes, orders, cylinders): one torque cycle per mode and order (distinct speeds)
    Tq = np.array([[loads.torque_harmonics([rpm[j, i]], [q])[0, 0] for i, q in enumerate(orders)] for j in range(k)])
    omega = 2 * np.pi * f[:, None]
    # |Σ_c a_jc T_q,c e^{−iqφ_c}|: the order's work on the mode, each cylinder with its own torque
    S = np.abs(np.einsum("jc,joc,oc->jo", modes.pin_amplitudes[:k], Tq, phasors))
    theta = (np.abs(modes.pulley_amplitude[:k, None]) * S
             / (2 * zeta_modes[:, None] * omega**2 * modes.modal_inertia[:k, None]))
    if gained is not None:
        # A damper couples its modes strongly (two close, heavily damped ones): the one-mode
        # estimate above misses the pulley amplitude by up to 36 % (measured on the Renault 21
        # with rubber and tuned rings). The full damped solve of the order at the crossing speed
        # replaces it; without a damper the two agree (the crossing is the resonance peak).
        theta = np.abs(damped_crossing_angles(crank, res, zeta_base, omega, Tq, phasors))
    largest = np.abs(Tq).max(axis=2)  # the largest cylinder's torque harmonic
    crossings = [
        Crossing(j + 1, float(f[j]), float(q), float(rpm[j, i]), bool(lo <= rpm[j, i] <= hi), float(largest[j, i]),
                 float(phase_sum[j, i]), float(np.degrees(theta[j, i])), modes.labels[j] if modes.labels else "")
        for j in range(k) for i, q in enumerate(orders)
    ]
    table = {}
    for speed in np.linspace(lo, hi, 5):
        h = loads.cylinder_harmonics(speed)  # cylinder 1's
        table[f"{speed:.0f}"] = {"orders": orders.tolist(), "amplitude_nm": np.abs(h.at(orders)).tolist(),
                                 "phase_rad": np.angle(h.at(orders)).tolist(), "mean_nm": h.mean_nm}
    return CampbellResult(crank.name, modes.source, f, orders, (lo, hi), zeta, crossings, table,
                          major=tuple(float(q) for q in major_orders(crank.engine) if np.any(np.isclose(orders, q))))


__all__ = ["CampbellResult", "TorsionalModes", "default_orders", "lumped_modes", "run_campbell"]
