"""Natural frequencies, damping ratios and mode shapes fitted to measured FRFs, and the modal
assurance criterion that compares shapes.

The poles come from sdypy-EMA's [Sdypy] least-squares complex-frequency estimator (LSCF, the
single-reference core of PolyMAX [Peeters]) over model orders 2 to 2 n; the modal constants at
the measured stations from its least-squares frequency-domain fit (LSFD) with lower and upper
residuals. sdypy-EMA leaves the choice of poles to a person at a stability chart, or to a
list of approximate frequencies; here it is automatic, by the stability chart's own rule
[Peeters]: a pole is stable when the next lower order has one within a relative tolerance in
frequency and in damping, and a mode is a cluster of stable physical poles (in the band,
0 < ζ < ``MAX_DAMPING``) that recurs over a fraction of the model orders. Each mode takes
the pole of the cluster's median frequency.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import FetorsionError

if TYPE_CHECKING:
    from .uff import MeasuredFunction

FORMS = {"angle": "receptance", "length": "receptance", "angular velocity": "mobility", "velocity": "mobility",
         "angular acceleration": "accelerance", "acceleration": "accelerance"}
MAX_MODEL_ORDER = 30  # sdypy-EMA's pol_order_high: denominators of order 2 to 60
FREQUENCY_STABLE = 1e-3  # relative change of a stable pole's frequency from one order to the next
# and of its damping ratio: 5 % left a clean mode (noise-free receptance, ζ = 0.01, the band's edge a
# tenth of its frequency away) unstable at most orders, its LSCF damping wandering 0.0097-0.0107 from
# order to order (numpy 2.4, scipy 1.17); a band without a mode still gives none (tests/test_measured.py)
DAMPING_STABLE = 0.10
MAX_DAMPING = 0.3  # a pole damped more than this is a computational one, not a structural mode
CLUSTER_WIDTH = 5e-3  # stable poles closer than this (relative) are one mode
RECURRENCE = 0.3  # a mode's stable poles appear in this fraction of the model orders at least


@dataclass(frozen=True, eq=False)
class ModalEstimate:
    """Modes fitted to one reference's FRFs.

    Attributes
    ----------
    frequencies_hz : ndarray, shape (modes,)
        Undamped natural frequencies [Hz], ascending.
    damping_ratios : ndarray, shape (modes,)
        Viscous damping ratios [-].
    shapes : ndarray, shape (stations, modes)
        Real mode shapes: mass-normalised when the driving point is among the stations (in
        1/sqrt of the FRF reference's inertia: kg^-1/2, or (kg m^2)^-1/2 for torsion), else
        scaled to a largest component of +1.
    stations : list of tuple
        (node, direction) of each row of ``shapes``.
    mass_normalised : bool
        Whether ``shapes`` are mass-normalised.
    chart : StabilityChart, optional
        The poles of every model order the modes were chosen from.
    """

    frequencies_hz: np.ndarray
    damping_ratios: np.ndarray
    shapes: np.ndarray
    stations: list
    mass_normalised: bool
    chart: StabilityChart | None = None

    def to_dict(self) -> dict:
        return {"frequencies_hz": self.frequencies_hz.tolist(), "damping_ratios": self.damping_ratios.tolist(),
                "shapes": self.shapes.tolist(), "stations": [list(s) for s in self.stations],
                "mass_normalised": self.mass_normalised}

    def table(self) -> str:
        scale = "mass-normalised" if self.mass_normalised else "largest component 1"
        lines = [f"modes fitted to measured FRFs (shapes {scale})",
                 f"{'mode':>4} {'f [Hz]':>10} {'zeta [%]':>9}  shape at " + ", ".join(f"{n}:{d}" for n, d in self.stations)]
        lines += [f"{r + 1:4d} {f:10.3f} {100 * z:9.3f}  " + " ".join(f"{v:9.4g}" for v in self.shapes[:, r])
                  for r, (f, z) in enumerate(zip(self.frequencies_hz, self.damping_ratios))]
        return "\n".join(lines)

    def plot(self, ax=None):
        """Each mode's shape against the station. Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        x = np.arange(len(self.stations))
        for r, f in enumerate(self.frequencies_hz):
            ax.plot(x, self.shapes[:, r], "o-", label=f"{f:.1f} Hz, ζ = {100 * self.damping_ratios[r]:.2f} %")
        ax.set_xticks(x, [f"{n}:{d}" for n, d in self.stations])
        ax.set_xlabel("station (node:direction)")
        ax.set_ylabel("mode shape")
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.legend(fontsize=8)
        return ax


def mac(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Modal assurance criterion: |a_i^H b_j|^2 / ((a_i^H a_i)(b_j^H b_j)), 1 for shapes alike.

    Parameters
    ----------
    a, b : array_like, shape (stations,) or (stations, modes)
        Mode shapes, real or complex, at the same stations.

    Returns
    -------
    ndarray or float
        (modes of a, modes of b); a float when both are single shapes.
    """
    a, b = np.asarray(a), np.asarray(b)
    single = a.ndim == 1 and b.ndim == 1
    a, b = a.reshape(a.shape[0], -1), b.reshape(b.shape[0], -1)
    if a.shape[0] != b.shape[0]:
        raise FetorsionError(f"mac: shapes at {a.shape[0]} and {b.shape[0]} stations")
    m = np.abs(a.conj().T @ b) ** 2 / np.outer(np.sum(np.abs(a) ** 2, axis=0), np.sum(np.abs(b) ** 2, axis=0))
    return float(m[0, 0]) if single else m


def frf_matrix(functions: Sequence[MeasuredFunction]):
    """The FRFs of one reference as a matrix, with what the fit needs to know of them.

    Parameters
    ----------
    functions : list of MeasuredFunction
        FRFs against frequency, one per response station, one reference, one pair of units,
        on one evenly spaced frequency grid.

    Returns
    -------
    frequency_hz : ndarray
    frf : ndarray, complex, shape (stations, frequencies)
    stations : list of tuple
        (node, direction) of each response.
    form : str
        ``'receptance'``, ``'mobility'`` or ``'accelerance'``, from the response's unit.
    driving_point : int or None
        The row whose response is the reference.
    """
    from .units import unit

    frfs = [f for f in functions if f.kind == "frf"]
    if not frfs:
        raise FetorsionError("frf_matrix: no FRF among the functions")
    first = frfs[0]
    for f in frfs:
        what = f"FRF {f.label or f.response}"
        if f.abscissa_quantity != "frequency":
            raise FetorsionError(f"{what}: is against {f.abscissa_quantity}, not frequency")
        if f.reference != first.reference or (f.unit, f.reference_unit) != (first.unit, first.reference_unit):
            raise FetorsionError(f"{what}: reference {f.reference} in {f.unit}/{f.reference_unit}; the first FRF's "
                                 f"is {first.reference} in {first.unit}/{first.reference_unit}")
        if f.abscissa.shape != first.abscissa.shape or not np.allclose(f.abscissa, first.abscissa, rtol=1e-12):
            raise FetorsionError(f"{what}: its frequencies differ from the first FRF's")
    form = FORMS.get(unit(first.unit, "FRF response").quantity)
    if form is None:
        raise FetorsionError(f"FRF response unit {first.unit!r}: not a displacement, velocity or acceleration")
    stations = [tuple(f.response) for f in frfs]
    if len(set(stations)) != len(stations):
        raise FetorsionError(f"frf_matrix: a station appears twice among {stations}")
    driving = stations.index(tuple(first.reference)) if tuple(first.reference) in stations else None
    return first.abscissa, np.array([f.ordinate for f in frfs]), stations, form, driving


@dataclass(frozen=True, eq=False)
class StabilityChart:
    """The poles of every model order of an LSCF fit, as a stability chart shows them [Peeters].

    Attributes
    ----------
    orders : ndarray (poles,)
        The model order each pole came from.
    frequencies_hz : ndarray (poles,)
        Its undamped frequency, Hz.
    damping_ratios : ndarray (poles,)
    stable : ndarray of bool (poles,)
        Stable in frequency and damping against the next lower order, and physical.
    band_hz : (float, float)
        The band the poles were sought in.
    poles : ndarray, complex (poles,)
        The poles themselves (rad/s), as the estimator gives them.
    """

    orders: np.ndarray
    frequencies_hz: np.ndarray
    damping_ratios: np.ndarray
    stable: np.ndarray
    band_hz: tuple[float, float]
    poles: np.ndarray = field(default_factory=lambda: np.zeros(0, complex), repr=False)

    def to_dict(self) -> dict:
        return {"orders": self.orders.tolist(), "frequencies_hz": self.frequencies_hz.tolist(),
                "damping_ratios": self.damping_ratios.tolist(), "stable": self.stable.tolist(),
                "band_hz": list(self.band_hz)}

    def plot(self, ax, modes_hz=(), frequency_hz=None, frf=None):
        """The chart on ``ax``: stable poles as dots, the others as small grey crosses, the chosen
        modes as vertical lines; behind them, on a second axis, the sum of the FRFs' magnitudes
        (``frequency_hz``, ``frf`` (stations, frequencies)) where given. Returns ``ax``."""
        if frf is not None:
            back = ax.twinx()
            back.semilogy(frequency_hz, np.sum(np.abs(np.atleast_2d(frf)), axis=0), color="0.75", lw=0.8, zorder=0)
            back.set_ylabel("sum of |FRF|", color="0.5", fontsize=8)
            back.tick_params(axis="y", labelsize=7, colors="0.5")
            ax.set_zorder(back.get_zorder() + 1)
            ax.patch.set_visible(False)
        ax.plot(self.frequencies_hz[~self.stable], self.orders[~self.stable], "x", color="0.6", ms=3,
                label="pole, not stable")
        ax.plot(self.frequencies_hz[self.stable], self.orders[self.stable], "o", color="C0", ms=3,
                label="stable pole (frequency and damping)")
        for f in modes_hz:
            ax.axvline(f, color="C3", lw=0.8)
        ax.set_xlim(*self.band_hz)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("model order")
        ax.set_title(f"stabilisation diagram: {len(modes_hz)} mode(s) chosen (red)", fontsize=9)
        ax.legend(fontsize=7, loc="upper left")
        return ax


def stability_chart(pole_freq, pole_xi, all_poles, band) -> StabilityChart:
    """Every physical pole of every order (in the band, 0 < ζ < ``MAX_DAMPING``), each marked
    stable where the next lower order has one within ``FREQUENCY_STABLE`` in frequency and
    ``DAMPING_STABLE`` in damping [Peeters]."""
    orders, freqs, zetas, stable, poles = [], [], [], [], []
    for j in range(1, len(all_poles)):
        f, z, p = np.asarray(pole_freq[j], float), np.asarray(pole_xi[j], float), np.asarray(all_poles[j])
        f0, z0 = np.asarray(pole_freq[j - 1], float), np.asarray(pole_xi[j - 1], float)
        physical = (f > band[0]) & (f < band[1]) & (z > 0) & (z < MAX_DAMPING)
        f, z, p = f[physical], z[physical], p[physical]
        if f0.size:
            df = np.abs(f[:, None] - f0[None, :]) / f[:, None]
            dz = np.abs(z[:, None] - z0[None, :]) / z[:, None]
            ok = np.any((df < FREQUENCY_STABLE) & (dz < DAMPING_STABLE), axis=1)
        else:
            ok = np.zeros(f.size, bool)
        orders += [j] * f.size
        freqs.append(f)
        zetas.append(z)
        stable.append(ok)
        poles.append(p)

    def cat(xs, dtype):
        return np.concatenate(xs).astype(dtype) if xs else np.zeros(0, dtype)

    return StabilityChart(np.asarray(orders, int), cat(freqs, float), cat(zetas, float), cat(stable, bool),
                          (float(band[0]), float(band[1])), cat(poles, complex))


def _stable_modes(chart: StabilityChart, orders: int):
    """One pole per mode: the chart's stable poles clustered by frequency, each cluster that recurs
    in ``RECURRENCE`` of the ``orders`` compared orders giving the pole of its median frequency."""
    keep = np.flatnonzero(chart.stable)
    if not keep.size:
        return []
    keep = keep[np.argsort(chart.frequencies_hz[keep], kind="stable")]
    freqs = chart.frequencies_hz[keep]
    breaks = np.flatnonzero(np.diff(freqs) / freqs[:-1] > CLUSTER_WIDTH) + 1
    modes = []
    for cluster in np.split(keep, breaks):
        if len(set(chart.orders[cluster].tolist())) >= RECURRENCE * orders:
            modes.append(chart.poles[cluster[len(cluster) // 2]])
    return modes


def estimate_modes(frequency_hz, frf, band_hz, form: str = "receptance", stations=None,
                   driving_point: int | None = None, max_order: int = MAX_MODEL_ORDER) -> ModalEstimate:
    """Modes of one reference's FRFs in a frequency band, poles chosen automatically.

    Parameters
    ----------
    frequency_hz : array_like
        Evenly spaced frequencies [Hz].
    frf : array_like, complex, shape (stations, frequencies)
        FRFs of each response station to the one reference, in SI.
    band_hz : tuple of float
        (low, high) [Hz]: the poles are sought and fitted there.
    form : str
        ``'receptance'`` (angle or displacement per load), ``'mobility'`` or ``'accelerance'``.
    stations : list of tuple, optional
        (node, direction) of each row, for the result; 0, 1, ... if None.
    driving_point : int, optional
        The row measured at the reference: the shapes are then mass-normalised.
    max_order : int
        The highest model order tried (the denominators run to twice it).
    """
    import warnings

    from sdypy import EMA
    from sdypy.EMA.EMA import LSFD

    f = np.asarray(frequency_hz, dtype=float)
    h = np.atleast_2d(np.asarray(frf))
    low, high = map(float, band_hz)
    if h.shape[1] != f.size or f.size < 3:
        raise FetorsionError(f"estimate_modes: {h.shape[1]} FRF values for {f.size} frequencies")
    step = np.diff(f)
    if np.any(np.abs(step - step[0]) > 1e-6 * step[0]) or step[0] <= 0:
        raise FetorsionError("estimate_modes: the frequencies must be evenly spaced and ascending (LSCF)")
    if not (f[0] <= low < high <= f[-1]):
        raise FetorsionError(f"estimate_modes: band {low:g} to {high:g} Hz is not within the data's "
                             f"{f[0]:g} to {f[-1]:g} Hz")
    if form not in set(FORMS.values()):
        raise FetorsionError(f"estimate_modes: form {form!r}; choose receptance, mobility or accelerance")
    with warnings.catch_warnings():  # sdypy warns of clamping the band to the last bin, and of 1/omega at 0 Hz
        warnings.simplefilter("ignore", UserWarning)
        warnings.simplefilter("ignore", RuntimeWarning)
        model = EMA.Model(frf=h, freq=f, lower=low, upper=high, pol_order_high=int(max_order), frf_form=form)
        model.get_poles(method="lscf", show_progress=False)
        chart = stability_chart(model.pole_freq, model.pole_xi, model.all_poles, (low, high))
        poles = _stable_modes(chart, len(model.all_poles) - 1)
        if not poles:
            raise FetorsionError(f"estimate_modes: no stable mode between {low:g} and {high:g} Hz")
        poles = np.array(sorted(poles, key=abs))
        lower = int(np.argmin(np.abs(model.freq - low)))
        upper = int(np.argmin(np.abs(model.freq - high)))
        constants, *_ = LSFD(poles, model.frf, model.freq, True, True, lower, upper, form)
    omega = np.abs(poles)
    # A mode's residue at station i is phi_i phi_ref / (2 i omega_d) for mass-normalised phi
    products = 2j * poles.imag * constants
    if driving_point is not None:
        shapes = products / np.sqrt(products[driving_point] + 0j)
    else:
        shapes = products / products[np.argmax(np.abs(products), axis=0), np.arange(products.shape[1])]
    # proportional damping: real shapes, up to noise; each turned onto the real axis
    turn = np.exp(-1j * np.angle(np.sum(shapes**2, axis=0)) / 2)
    shapes = (shapes * turn).real
    shapes *= np.where(shapes[np.argmax(np.abs(shapes), axis=0), np.arange(shapes.shape[1])] < 0, -1.0, 1.0)
    return ModalEstimate(frequencies_hz=omega / (2 * np.pi), damping_ratios=-poles.real / omega, shapes=shapes,
                         stations=list(stations) if stations is not None else [(i, 0) for i in range(h.shape[0])],
                         mass_normalised=driving_point is not None, chart=chart)


def run_modal_fit(functions: Sequence[MeasuredFunction], band_hz: tuple[float, float],
                  max_order: int = MAX_MODEL_ORDER) -> ModalEstimate:
    """Modes of measured FRFs (:func:`~fetorsion.measured.uff.read_uff58`) in a band.

    Parameters
    ----------
    functions : sequence of MeasuredFunction
        FRFs of one reference, on one frequency axis [Hz].
    band_hz : tuple of float
        (low, high) frequency band to fit [Hz], inside the data's.
    max_order : int
        Highest model order of the LSCF stabilisation.

    Returns
    -------
    ModalEstimate

    Examples
    --------
    >>> import numpy as np
    >>> import fetorsion
    >>> from fetorsion.measured.uff import MeasuredFunction
    >>> f = np.linspace(50.0, 150.0, 2001)
    >>> wn, w = 2 * np.pi * 100.0, 2 * np.pi * f
    >>> h = 1 / (wn**2 - w**2 + 2j * 0.02 * wn * w)  # one mode: 100 Hz, 2 % damping
    >>> frf = MeasuredFunction("frf", f, "frequency", h, "rad", response=(1, 4), reference=(1, 4),
    ...                        reference_unit="N m", label="drive point")
    >>> fit = fetorsion.run_modal_fit([frf], (80.0, 120.0))
    >>> print(f"{fit.frequencies_hz[0]:.1f} Hz, {fit.damping_ratios[0]:.3f}")
    100.0 Hz, 0.020
    """
    frequency, frf, stations, form, driving = frf_matrix(functions)
    return estimate_modes(frequency, frf, band_hz, form, stations, driving, max_order)
