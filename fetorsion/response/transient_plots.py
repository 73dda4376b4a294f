"""Figures of a time-domain run (:class:`fetorsion.response.transient.TransientResult`): a section's
torque against time with the tracked station's order cuts, the order track as a map, and a run-up's
order cuts over the steady-state response's."""

from __future__ import annotations

import numpy as np


def plot_transient(result, ax, orders):
    """The most loaded section's torque against time and, on a new figure, the order cuts of the
    tracked station against speed. Returns the Axes of the torque.

    Parameters
    ----------
    result : TransientResult
        The run.
    ax : matplotlib Axes or None
        Where the torque is drawn (then without the order cuts); None: a new figure with both.
    orders : sequence of float
        The orders whose cuts are drawn (those tracked).
    """
    import matplotlib.pyplot as plt

    if ax is None:
        fig = plt.figure(figsize=(9, 7))
        a1, a2 = fig.subplots(2, 1)
    else:
        fig, a1, a2 = ax.figure, ax, None
    k = int(np.argmax(result.block_peak_nm.max(axis=0)))
    every = max(1, result.time_s.size // 50000)
    a1.plot(result.time_s[::every], result.section_torque_nm[k, ::every], lw=0.5, color="C0",
            label=f"section {result.section_labels[k]}")
    a1.set_xlabel("time [s]")
    a1.set_ylabel("vibratory torque [N m]")
    a1.set_title(f"{result.name}: {result.mode}", fontsize=10, wrap=True)
    a1.legend(fontsize=8)
    if a2 is not None:
        for q in orders:
            if np.any(np.isclose(result.track.orders, q)):
                a2.plot(result.track.rpm, np.degrees(np.abs(result.track.at(q))), label=f"order {q:g}")
        a2.set_xlabel("mean speed [rpm]")
        a2.set_ylabel(f"{result.track_station}: vibration [deg]")
        a2.legend(fontsize=8)
        fig.tight_layout()
    return a1


def plot_waterfall(result, ax, max_order, span: float):
    """The order track as a map: the tracked station's vibration (deg, colour on a log scale over
    ``span`` decades below its largest value) against mean speed (rpm) and order. Returns the Axes.

    Parameters
    ----------
    result : TransientResult
        The run.
    ax : matplotlib Axes or None
        Where it is drawn; None: a new figure.
    max_order : float or None
        The highest order shown; None: all tracked.
    span : float
        Decades of the colour scale.
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5))
    keep = result.track.orders <= (max_order if max_order is not None else np.inf)
    amp = np.degrees(np.abs(result.track.amplitudes[:, keep])).T  # (orders, blocks)
    top = float(amp.max()) if amp.size and amp.max() > 0 else 1.0
    mesh = ax.pcolormesh(result.track.rpm, result.track.orders[keep], np.maximum(amp, top * 10.0**-span),
                         shading="nearest", norm=LogNorm(top * 10.0**-span, top), cmap="viridis")
    ax.figure.colorbar(mesh, ax=ax, label=f"{result.track_station}: vibration [deg]")
    ax.set_xlabel("mean speed [rpm]")
    ax.set_ylabel("order")
    ax.set_title(f"{result.name}: {result.mode}, order track of {result.track_station}", fontsize=10, wrap=True)
    ax.figure.tight_layout()
    return ax


def plot_order_cuts(result, response, cuts, ax=None):
    """Each compared order's cut of the run-up (solid) over the steady-state response's (dashed),
    the tracked station's vibration in deg against speed. Returns the Axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5))
    for i, q in enumerate(dict.fromkeys(c.order for c in cuts)):
        k = int(np.flatnonzero(np.isclose(response.orders, q))[0])
        ax.plot(result.track.rpm, np.degrees(np.abs(result.track.at(q))), color=f"C{i}", lw=1.2,
                label=f"order {q:g}, run-up")
        ax.plot(response.rpm, response.order_pulley_deg[:, k], color=f"C{i}", lw=1.0, ls="--",
                label=f"order {q:g}, steady state")
    ax.set_yscale("log")  # a low order's rigid-body swing at idle would flatten the resonances
    ax.set_xlabel("mean speed [rpm]")
    ax.set_ylabel(f"{result.track_station}: vibration [deg]")
    ax.set_title(f"{result.name}: order cuts, {result.mode} (solid) and steady state (dashed)", fontsize=9, wrap=True)
    ax.legend(fontsize=8, ncol=2)
    ax.figure.tight_layout()
    return ax
