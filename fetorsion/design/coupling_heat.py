"""A flexible coupling's heat and vibratory torque against its data sheet, at the temperature its
own heat holds it (docs/propulsion-tvc.md).

Each order q twists the coupling with an elastic torque amplitude T_q (the section torque the
forced response gives: C × twist) at f_q = q n / 60 Hz (n station 1's speed, rpm), so the rubber
dissipates P(n) = Σ_q f_q ψ(T) T_q² / (2 C(T)) (:func:`fetorsion.description.marine.coupling_heat`).

**Heat balance.** P_KV is the heat the coupling turns out continuously without passing its
permissible temperature at the sheet's ambient [CentaxSheet]: its steady rise above the ambient is
taken proportional to the heat, reaching the permissible temperature at P_KV,

    T = T_ambient + (T_max − T_ambient) · P / P_KV,

the coupling-temperature estimate of [PoonaPM] (the rise (P_k / allowable heat) × 70 K above the
ambient, 70 K the span from its 30 °C catalogue ambient to its rubbers' 100 °C). Rubber softens
and loses damping when hot, so the stiffness and ψ at that temperature change the response and so
the heat: the temperature is found by fixed-point iteration T → C(T), ψ(T) → response → P → T,
relaxed by :data:`RELAXATION` against overshoot, to :data:`TOLERANCE_K`, at most
:data:`ITERATIONS` times. As for a heat-following damper (``response/forced.py: solve_theta``) the
heat is the largest over the speed range: the steady temperature of the hottest sustained speed.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, replace
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from ..description.chain_model import Network
from ..description.marine import Coupling, loss_factor_of
from ..errors import FetorsionError
from ..response.forced import ResponseResult, ResponseSetup, section_torques, solve_response
from ..response.synthesis import grouped_extremes
from ..results import from_fields

#: The coupling temperatures are settled when an iteration moves none more than this, K.
TOLERANCE_K = 0.05
#: Iterations allowed (each a whole forced response).
ITERATIONS = 60
#: Each step moves the temperatures this share of the way to what the heat holds.
RELAXATION = 0.5


@dataclass
class CouplingHeat:
    """The network's couplings at their settled temperatures.

    ``temperature_c`` per coupling (°C); ``history_c`` the temperatures of each iteration (the first
    the ambient); ``heat_w`` and ``torque_nm`` (speeds, couplings): the heat and the synthesised
    half-range vibratory torque at the settled temperatures; ``response`` the forced response there
    (None: read back from results.json, which keeps normal running's response beside it, not in it).
    """

    name: str
    couplings: list[Coupling]
    rpm: np.ndarray
    temperature_c: np.ndarray
    history_c: list[list[float]]
    heat_w: np.ndarray
    torque_nm: np.ndarray
    tolerance_k: float
    response: ResponseResult | None
    notes: list[str] = field(default_factory=list)

    @property
    def iterations(self) -> int:
        return len(self.history_c) - 1

    def rows(self) -> list[dict[str, float | str | None]]:
        """One row per coupling: settled temperature, stiffness and ψ there, the largest heat and
        torque with their speeds, against P_KV and the permissible torque (None: not on the sheet)."""
        out = []
        for k, c in enumerate(self.couplings):
            t, h, q = float(self.temperature_c[k]), self.heat_w[:, k], self.torque_nm[:, k]
            out.append({"coupling": c.name, "temperature_c": t, "stiffness_nm_per_rad": c.stiffness_at(t),
                        "relative_damping": c.relative_damping_at(t), "heat_w": float(h.max()),
                        "heat_rpm": float(self.rpm[h.argmax()]), "permissible_power_w": c.permissible_power or None,
                        "torque_nm": float(q.max()), "torque_rpm": float(self.rpm[q.argmax()]),
                        "permissible_torque_nm": c.permissible_torque or None,
                        "heat_ok": None if not c.permissible_power else bool(h.max() <= c.permissible_power),
                        "torque_ok": None if not c.permissible_torque else bool(q.max() <= c.permissible_torque)})
        return out

    def to_dict(self) -> dict:
        """JSON-ready: the rows, the iteration (tolerance K, count, history °C), heat (W) and torque (N·m) over speed."""
        return {"name": self.name, "rows": self.rows(), "tolerance_k": self.tolerance_k,
                "iterations": self.iterations, "history_c": self.history_c, "rpm": self.rpm.tolist(),
                "heat_w": self.heat_w.tolist(), "torque_nm": self.torque_nm.tolist(), "notes": self.notes,
                "sheets": [sheet_dict(c) for c in self.couplings]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object], response: ResponseResult | None = None) -> "CouplingHeat":
        """The result back from its :meth:`to_dict` (each coupling's sheet from ``sheets``; the
        ``response`` given, None where not kept)."""
        couplings = [from_fields(Coupling, s) for s in d["sheets"]]
        temperatures = np.array([r["temperature_c"] for r in d["rows"]], dtype=float)
        return from_fields(cls, d, couplings=couplings, temperature_c=temperatures, response=response)

    def table(self) -> str:
        """Each coupling's settled temperature, heat and torque against the sheet."""
        lines = [f"{self.name}: coupling heat, settled in {self.iterations} iterations to {self.tolerance_k:g} K"]
        for r in self.rows():
            heat = (" (the sheet gives no P_KV: not judged)" if r["permissible_power_w"] is None
                    else f" of P_KV {r['permissible_power_w']:.0f} W")
            torque = (" (the sheet gives no permissible vibratory torque: not judged)"
                      if r["permissible_torque_nm"] is None else f" of {r['permissible_torque_nm']:.0f} N m")
            lines.append(f"  {r['coupling']}: {r['temperature_c']:.1f} °C (C {r['stiffness_nm_per_rad']:.4g} N m/rad, "
                         f"ψ {r['relative_damping']:.3f}); heat up to {r['heat_w']:.1f} W{heat} at "
                         f"{r['heat_rpm']:.1f} rpm; vibratory torque up to {r['torque_nm']:.0f} N m{torque} at "
                         f"{r['torque_rpm']:.1f} rpm")
        return "\n".join(lines + [f"  note: {n}" for n in self.notes])

    def plot(self, ax=None):
        """Each coupling's heat over speed (W) with its P_KV. Returns the Axes."""
        import matplotlib.pyplot as plt

        ax = ax if ax is not None else plt.figure(figsize=(9, 4)).add_subplot()
        for k, c in enumerate(self.couplings):
            ax.plot(self.rpm, self.heat_w[:, k], color=f"C{k}", label=f"{c.name} at {self.temperature_c[k]:.0f} °C")
            if c.permissible_power:
                ax.axhline(c.permissible_power, color=f"C{k}", ls="--", lw=0.9, label=f"P_KV {c.name}")
        ax.set(xlabel="engine speed, station 1 (rpm)", ylabel="coupling heat (W)", title=f"{self.name}: coupling heat")
        ax.legend(fontsize=7)
        return ax


def sheet_dict(coupling: Coupling) -> dict:
    """A coupling's data sheet as JSON-ready (its fields by name; None for a value the sheet does not give)."""
    return {k: None if isinstance(v, float) and not np.isfinite(v) else v for k, v in asdict(coupling).items()}


def held_temperature(coupling: Coupling, heat_w: float) -> float:
    """T = T_ambient + (T_max − T_ambient) P / P_KV, °C (module docs): the steady temperature a heat
    (W) holds the coupling at."""
    return coupling.ambient_c + (coupling.max_temperature_c - coupling.ambient_c) * heat_w / coupling.permissible_power


def at_temperatures(net: Network, temperatures_c: Sequence[float] | np.ndarray) -> Network:
    """The network with each coupling's spring at a temperature: C(T) and η = ψ(T)/2π. The
    couplings' springs are the last of ``net.shafts``, in the couplings' order (as read)."""
    first = len(net.shafts) - len(net.couplings)
    shafts = list(net.shafts)
    for k, (c, t) in enumerate(zip(net.couplings, temperatures_c)):
        shafts[first + k] = replace(shafts[first + k], stiffness=c.stiffness_at(t),
                                    loss_factor=loss_factor_of(c.relative_damping_at(t)))
    return replace(net, shafts=tuple(shafts))


def coupling_loads(net: Network, setup: ResponseSetup,
                   temperatures_c: Sequence[float] | np.ndarray) -> tuple[np.ndarray, np.ndarray, ResponseResult]:
    """(heat W (speeds, couplings), the half-range torque each carries, elastic and damping, N·m (speeds,
    couplings), the response) of the
    network's couplings at ``temperatures_c``, from the forced response of ``setup`` with the
    network's ``[[dampers]]``."""
    response = solve_response(setup, net.dampers)
    theta = response.theta
    torque = section_torques(setup, theta)  # (speeds, sections, orders), the elastic k Δθ
    first = len(net.shafts) - len(net.couplings)
    freq = setup.orders[None, :] * setup.rpm[:, None] / 60.0  # (speeds, orders) Hz
    heat = np.array([[c.heat(np.abs(torque[s, first + k]), freq[s], t) for k, (c, t) in
                      enumerate(zip(net.couplings, temperatures_c))] for s in range(len(setup.rpm))])
    # the torque the element carries, elastic and damping, C (1 + i ψ/2π) Δθ of each order, synthesised
    # over the cycle: what the sheet's permissible vibratory torque is set against (the section
    # torques are the elastic part alone, 1.3 % less at ψ 1)
    eta = np.array([loss_factor_of(c.relative_damping_at(t)) for c, t in zip(net.couplings, temperatures_c)])
    carried = torque[:, first:first + len(net.couplings)] * (1 + 1j * eta)[None, :, None]
    top, bottom = grouped_extremes(carried, setup.orders, setup.period, setup.order_groups)
    return heat, 0.5 * (top - bottom), response


def coupling_heat(net: Network, setup_of: Callable[[Network], ResponseSetup], tolerance_k: float = TOLERANCE_K,
                  iterations: int = ITERATIONS) -> CouplingHeat:
    """The couplings' temperatures held by their own heat, by fixed-point iteration (module docs).

    Parameters
    ----------
    net : Network
        With ``couplings``; those with a P_KV, an ambient and a maximum temperature follow their heat,
        the others stay at their operating temperature.
    setup_of : callable
        Network → its forced-response setup (e.g. ``lambda n: propeller_setup(n, rpm=…)``).
    tolerance_k : float
        Settled when an iteration moves no temperature more than this, K.
    iterations : int
        Iterations allowed.
    """
    follows = np.array([bool(c.permissible_power) and np.isfinite(c.ambient_c) and np.isfinite(c.max_temperature_c)
                        for c in net.couplings])
    temps = np.array([c.ambient_c if f else c.operating_temperature_c for c, f in zip(net.couplings, follows)])
    history = [temps.tolist()]
    for _ in range(iterations):
        current = at_temperatures(net, temps)
        setup = setup_of(current)
        heat, torque, response = coupling_loads(current, setup, temps)
        held = np.array([held_temperature(c, p) if f else t for c, p, f, t in
                         zip(net.couplings, heat.max(axis=0), follows, temps)])
        if np.all(np.abs(held - temps) <= tolerance_k):
            notes = [f"{c.name}: T = {c.ambient_c:g} + ({c.max_temperature_c:g} − {c.ambient_c:g}) P/P_KV °C, P the "
                     f"largest heat over the speeds" for c, f in zip(net.couplings, follows) if f]
            notes += [f"{c.name}: at its operating temperature {c.operating_temperature_c:g} °C (no P_KV, ambient or "
                      "maximum temperature on the sheet)" for c, f in zip(net.couplings, follows) if not f]
            return CouplingHeat(net.name, list(net.couplings), setup.rpm, temps, history, heat, torque, tolerance_k,
                                response, notes)
        temps = temps + RELAXATION * (held - temps)
        history.append(temps.tolist())
    raise FetorsionError(f"{net.name}: the couplings' temperatures did not settle in {iterations} iterations "
                         f"(last {', '.join(f'{t:.1f}' for t in temps)} °C)")
