"""A torsiograph's orders as a reader looks at them: a run-up's speed-order map with the model's
crossings (:class:`Waterfall`), a steady record's order spectrum, and the rule that tells the two
apart (:func:`is_steady`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


#: Crossings a waterfall's summary line quotes (those the measurement responds to most).
WATERFALL_LINES = 4
#: A record whose blocks' mean speeds lie within this fraction of each other is steady: one speed
STEADY_SPREAD = 0.02


def is_steady(rpm) -> bool:
    """Whether a record's block speeds are one speed (within :data:`STEADY_SPREAD`)."""
    rpm = np.asarray(rpm, float)
    return rpm.size >= 2 and rpm.max() <= (1 + STEADY_SPREAD) * rpm.min()


@dataclass
class Waterfall:
    """A torsiograph track's order map and the model's crossings on it.

    Attributes
    ----------
    name : str
        The file and channel.
    track : OrderTrack
        Every tracked order per block (:class:`~fetorsion.measured.torsiograph.OrderTrack`).
    model_hz : ndarray
        The model's natural frequencies, Hz.
    crossings : list of (int, float, float)
        (mode number from 1, order, rpm) of every crossing inside the track's speeds and orders.
    """

    name: str
    track: object
    model_hz: np.ndarray
    crossings: list

    def to_dict(self) -> dict:
        return {"name": self.name, "track": self.track.to_dict(), "model_hz": self.model_hz.tolist(),
                "crossings": [{"mode": m, "order": k, "rpm": n} for m, k, n in self.crossings]}

    def lines(self, count: int = WATERFALL_LINES) -> list[str]:
        """One line: how many crossings, and the ``count`` the measurement responds to most."""
        near = []
        for m, k, n in self.crossings:
            b = int(np.argmin(np.abs(self.track.rpm - n)))
            a = float(np.degrees(abs(self.track.at(k)[b])))
            near.append((a, f"mode {m} x order {k:g} at {n:.0f} rpm (measured {a:.3g} deg at {self.track.rpm[b]:.0f} rpm)"))
        near = [text for _, text in sorted(near, key=lambda x: -x[0])[:count]]
        return [f"- waterfall {self.name}: {len(self.crossings)} model crossing(s) in the measured speeds and orders"
                + ("; the strongest measured: " + "; ".join(near) if near else "")]

    def plot(self, ax, steady_cuts=()):
        """A run-up's speed-order colour map (amplitude in deg, logarithmic colours) with the
        model's crossings marked; a steady record's order spectrum instead (there is no speed axis
        to draw a map over), each order's mean amplitude over the blocks with its spread, and the
        model's amplitude at that speed for the orders compared (``steady_cuts``)."""
        if is_steady(self.track.rpm):
            return self._spectrum(ax, steady_cuts)
        from matplotlib.colors import LogNorm

        order = np.argsort(self.track.rpm)
        amp = np.degrees(np.abs(self.track.amplitudes[order]))
        positive = amp[amp > 0]
        low = max(positive.max() * 1e-4, positive.min()) if positive.size else 1e-12
        mesh = ax.pcolormesh(self.track.rpm[order], self.track.orders, np.maximum(amp, low).T, shading="nearest",
                             norm=LogNorm(vmin=low, vmax=max(low * 10, amp.max())), cmap="viridis")
        ax.figure.colorbar(mesh, ax=ax, label="vibration [deg]")
        for m, k, n in self.crossings:
            ax.plot(n, k, "o", mfc="none", mec="w", ms=7)
            ax.annotate(f"{m}", (n, k), color="w", fontsize=7, xytext=(4, 3), textcoords="offset points")
        ax.set_xlabel("mean speed [rpm]")
        ax.set_ylabel("order")
        ax.set_title(f"{self.name}: speed-order map, model crossings (o: mode number)", fontsize=9, wrap=True)
        return ax

    def _spectrum(self, ax, steady_cuts):
        amp = np.degrees(np.abs(self.track.amplitudes))
        mean, low, high = amp.mean(axis=0), amp.min(axis=0), amp.max(axis=0)
        floor = max(mean.max() * 1e-4, 1e-12)
        orders = self.track.orders
        ax.vlines(orders, floor, np.maximum(mean, floor), color="C0", lw=1.5, label="measured (mean over the blocks)")
        ax.errorbar(orders, np.maximum(mean, floor), yerr=[mean - np.maximum(low, floor), high - mean], fmt="none",
                    ecolor="0.4", lw=0.8, capsize=2, label="spread over the blocks")
        for j, c in enumerate(steady_cuts):
            ax.plot(c.order, c.steady()["model_deg"], "D", color="C3", ms=6, label="model at this speed" if j == 0
                    else None)
        ax.set_yscale("log")
        ax.set_ylim(bottom=floor)
        ax.set_xlabel("order")
        ax.set_ylabel("vibration [deg]")
        ax.set_title(f"{self.name}: order spectrum, steady at {self.track.rpm.mean():.0f} rpm over "
                     f"{self.track.rpm.size} blocks", fontsize=9, wrap=True)
        ax.legend(fontsize=7)
        return ax


def model_crossings(model_hz, orders, rpm) -> list:
    """(mode from 1, order, rpm) where each natural frequency meets each order, 60 f / k rpm, kept
    inside the span of ``rpm``."""
    lo, hi = float(np.min(rpm)), float(np.max(rpm))
    out = []
    for m, f in enumerate(np.asarray(model_hz, float), start=1):
        for k in np.asarray(orders, float):
            n = 60.0 * f / k
            if lo <= n <= hi:
                out.append((m, float(k), float(n)))
    return out
