"""The natural frequencies of a propulsion line as a TVC tabulates them, and its Campbell diagram
with the barred ranges (docs/propulsion-tvc.md).

**The mode table.** For each undamped mode of the network at its couplings' settled temperatures:
its frequency, the resonances in the speed range (each exciting order q, the engine's and the
propellers' blade orders per revolution of station 1, at n = 60 f / q rpm inside it), and the
relative amplitude of every station: the mode's physical angles (θ = T q, not referred to station
1's speed) over the largest of them, so the station that swings most reads 1.

**The Campbell diagram.** The modes' frequencies against station 1's speed, the engine's orders
(its major orders bold) and the blade orders as lines f = q n / 60, the speed range shaded grey and
each configuration's barred ranges as bands (normal running crimson, a misfire orange, hatched, a failed
damper purple, hatched the other way).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..description.chain_model import Network
from ..lumped_model.lumped import lumped
from ..results import from_fields

if TYPE_CHECKING:
    from matplotlib.axes import Axes


@dataclass(frozen=True)
class ModeRow:
    """One mode: ``number`` (1-based), ``frequency_hz``, its ``resonances`` in the speed range
    ((order, rpm of station 1), …) and ``amplitudes`` (one per station of the network, the largest
    magnitude 1, signed)."""

    number: int
    frequency_hz: float
    resonances: tuple[tuple[float, float], ...]
    amplitudes: np.ndarray

    def to_dict(self) -> dict:
        """JSON-ready."""
        return {"mode": self.number, "frequency_hz": self.frequency_hz,
                "resonances": [{"order": q, "rpm": n} for q, n in self.resonances],
                "relative_amplitudes": self.amplitudes.tolist()}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "ModeRow":
        """The row back from its :meth:`to_dict`."""
        return from_fields(cls, d, {"number": "mode", "amplitudes": "relative_amplitudes"},
                           resonances=tuple((float(r["order"]), float(r["rpm"])) for r in d["resonances"]))


@dataclass(frozen=True)
class TVCCampbell:
    """What the TVC's Campbell diagram draws besides the modes (:func:`plot_tvc_campbell`): the engine's
    orders, its major orders and the blade orders (per revolution of station 1), the speed range (rpm),
    each configuration's barred ranges ((configuration, from rpm, to rpm), …) and the title."""

    engine_orders: tuple[float, ...]
    major_orders: tuple[float, ...]
    blade_orders: tuple[float, ...]
    speed_range: tuple[float, float]
    barred: tuple[tuple[str, float, float], ...]
    title: str

    def to_dict(self) -> dict:
        """JSON-ready (speeds in rpm)."""
        return {"engine_orders": list(self.engine_orders), "major_orders": list(self.major_orders),
                "blade_orders": list(self.blade_orders), "speed_range_rpm": list(self.speed_range),
                "barred": [{"configuration": c, "from_rpm": a, "to_rpm": b} for c, a, b in self.barred],
                "title": self.title}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "TVCCampbell":
        """The diagram's data back from its :meth:`to_dict`."""
        barred = tuple((b["configuration"], b["from_rpm"], b["to_rpm"]) for b in d["barred"])
        return from_fields(cls, d, {"speed_range": "speed_range_rpm"}, barred=barred)

    def plot(self, rows: Sequence[ModeRow], ax: Axes | None = None):
        """The diagram with the modes ``rows`` (:func:`plot_tvc_campbell`). Returns the Axes."""
        return plot_tvc_campbell(list(rows), self.engine_orders, self.major_orders, self.blade_orders,
                                 self.speed_range, list(self.barred), self.title, ax)


def mode_table(net: Network, orders: np.ndarray, speed_range: tuple[float, float],
               max_modes: int = 6) -> list[ModeRow]:
    """The lowest ``max_modes`` elastic modes of ``net`` with their resonances in ``speed_range`` (rpm
    of station 1) for ``orders`` (per revolution of station 1) and their relative station amplitudes
    (module docs)."""
    res = lumped(net)
    T = res.network.T
    freqs = np.asarray(res.frequencies_hz, dtype=float)
    shapes = np.asarray(res.mode_shapes, dtype=float)
    lo, hi = speed_range
    rows = []
    for k, f in enumerate(freqs[:max_modes]):
        theta = T @ shapes[k]
        amp = theta / theta[np.argmax(np.abs(theta))]
        hits = tuple((float(q), float(60.0 * f / q)) for q in sorted(set(np.round(orders, 9)))
                     if q > 0 and lo <= 60.0 * f / q <= hi)
        rows.append(ModeRow(k + 1, float(f), hits, amp))
    return rows


#: Each kind of configuration's barred band on the Campbell diagram: (colour, hatch).
BAND_STYLES = {"normal running": ("crimson", None), "misfire": ("orange", "//"), "failed damper": ("purple", "\\\\"),
               "coupling tolerance": ("teal", "..")}


def plot_tvc_campbell(rows: list[ModeRow], engine_orders: Sequence[float], major_orders: Sequence[float],
                      blade_orders: Sequence[float], speed_range: tuple[float, float],
                      barred: list[tuple[str, float, float]], title: str, ax: Axes | None = None):
    """The Campbell diagram with the barred ranges (module docs). ``barred``: (configuration, from
    rpm, to rpm) of each range; orders per revolution of station 1. Returns the Axes."""
    import matplotlib.pyplot as plt

    ax = ax if ax is not None else plt.figure(figsize=(9, 6)).add_subplot()
    lo, hi = speed_range
    top = 1.1 * hi
    ax.axvspan(lo, hi, color="0.93", zorder=0, label="speed range")
    major = {round(float(q), 9) for q in major_orders}
    n = np.array([0.0, top])
    first = min(major, default=None)
    fmax = 1.15 * max(r.frequency_hz for r in rows)
    placed = []  # an order line leaving through the top is labelled there, where it has room (a major order always)
    for q in sorted(engine_orders, key=lambda q: (round(float(q), 9) not in major, -q)):
        bold = round(float(q), 9) in major
        ax.plot(n, q * n / 60, color="0.15" if bold else "0.65", lw=1.4 if bold else 0.6, zorder=1,
                label="engine major order" if bold and round(float(q), 9) == first else None)
        style = {"fontsize": 7 if bold else 6, "color": "0.1" if bold else "0.4", "fontweight": "bold" if bold else None}
        if q * top / 60 < fmax:  # leaves through the right edge
            ax.annotate(f"{q:g}", (top, q * top / 60), xytext=(2, 0), textcoords="offset points", va="center", **style)
        else:
            x = fmax * 60 / q
            if bold or all(abs(x - p) > 0.03 * top for p in placed):
                placed.append(x)
                ax.annotate(f"{q:g}", (x, fmax), xytext=(0, 2), textcoords="offset points", ha="center", va="bottom",
                            **style)
    for r in rows:  # each resonance inside the speed range marked where its order meets the mode
        ax.scatter([rpm for _, rpm in r.resonances], [r.frequency_hz] * len(r.resonances), s=14, facecolors="none",
                   edgecolors="crimson", lw=0.9, zorder=3,
                   label="resonance in the speed range" if r is rows[0] or not any(x.resonances for x in rows[:rows.index(r)])
                   else None)
    for q in blade_orders:
        ax.plot(n, q * n / 60, color="tab:blue", ls="--", lw=1.2, zorder=1,
                label=f"propeller blade rate (engine order {q:.4g})")
    for r in rows:
        ax.axhline(r.frequency_hz, color="tab:green", lw=1.0, zorder=2)
        ax.annotate(f"mode {r.number}: {r.frequency_hz:.1f} Hz", (0.99 * top, r.frequency_hz), fontsize=7, ha="right",
                    xytext=(0, 2), textcoords="offset points", color="darkgreen", zorder=4,
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85})
    shown = set()
    for name, a, b in barred:
        kind = "normal running" if name == "normal running" else "misfire" if name.startswith("misfire") \
            else "coupling tolerance" if name.startswith("coupling") else "failed damper"
        color, hatch = BAND_STYLES[kind]
        ax.axvspan(a, b, color=color, alpha=0.25, lw=0, hatch=hatch, zorder=1,
                   label=None if kind in shown else f"barred, {kind}")
        shown.add(kind)
    ax.set(xlim=(0, top), ylim=(0, fmax), xlabel="engine speed (rpm)", ylabel="frequency (Hz)")
    ax.set_title(title, pad=14)
    ax.legend(fontsize=7, loc="upper left", framealpha=0.95)
    if not barred:
        ax.text(0.5, -0.1, "no barred range in any configuration computed", transform=ax.transAxes, ha="center",
                va="top", fontsize=8)
    return ax
