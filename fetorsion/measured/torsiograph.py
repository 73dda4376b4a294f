"""A torsiograph from toothed wheels: the time of every tooth edge a pickup saw, turned into
the wheel's angle and speed, its vibration by engine order against speed, and the twist
between two wheels on the shaft.

Edge ``i`` of a wheel of ``z`` teeth is tooth ``j = i mod z`` of revolution ``r = i div z``;
the first edge recorded is tooth 0 (the angle's origin), so a record needs no once-per-rev
mark and whole revolutions are counted from its first edge. The wheel's angle at edge ``i`` is

    θ_i = 2π i / z + e_j,

with ``e`` the tooth spacing errors (mean zero), estimated by :func:`tooth_errors`. Between
edges the angle is interpolated (a cubic spline of time against angle), so that the vibration
is sampled at equal angles (computed order tracking, with a cubic rather than a linear
interpolation [Fyfe]), and an FFT over N whole revolutions puts every order that is a
multiple of 1/N on a bin.

The tooth spacing errors are calibrated in place by averaging each tooth's deviation over
many revolutions [Resor]. They repeat every revolution, and so does a vibration at a
whole-number order: in one steady record the two cannot be told apart, and averaging leaves
both. So the errors are estimated from a calibration record in which the whole-number orders
are weak (a motored or coasting run at low speed) and applied to the records to analyse. Half
orders (a four-stroke engine's) repeat only every second revolution and average out of the
estimate over an even number of revolutions.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import FetorsionError
from .edges import check_edges
from .wheels import Wheel, repaired_edges, wheel_of

TWIST = "twist"  # the name of the twist's track in a TorsiographResult


def track_order_cut(track, order: float, name: str):
    """A tracked order of :class:`OrderTrack` as a measured order cut against its blocks' mean
    speeds (angle, rad; the node 0 until the comparison places it)."""
    from .uff import MeasuredFunction

    rpm = np.asarray(track.rpm, float)
    amp = np.asarray(track.at(order))
    keep = np.argsort(rpm)
    return MeasuredFunction("order function", rpm[keep], "speed", amp[keep], "rad", (0, 4),
                            label=f"{name}, torsiograph", order=float(order))




def edge_angles(n: int, teeth: int, errors=None) -> np.ndarray:
    """The wheel's angle at its first ``n`` edges [rad]: 2π i / z, plus the tooth errors.

    Parameters
    ----------
    n : int
        Edges.
    teeth : int
        Teeth per revolution, z.
    errors : array_like, optional
        Tooth spacing errors e_j [rad], one per tooth, tooth 0 first (:func:`tooth_errors`).
    """
    theta = 2.0 * np.pi * np.arange(n) / teeth
    if errors is not None:
        e = np.asarray(errors, dtype=float)
        if e.shape != (teeth,):
            raise FetorsionError(f"tooth errors: {e.shape[0] if e.ndim == 1 else e.shape} values for {teeth} teeth")
        if np.any(np.diff(np.append(e, e[0] + 2 * np.pi)) + 2 * np.pi / teeth <= 0):
            raise FetorsionError("tooth errors: larger than the tooth pitch (the edges would run backwards)")
        theta = theta + np.resize(e, n)
    return theta


def instantaneous_speed(times, teeth: int, errors=None):
    """The wheel's speed between consecutive edges.

    Parameters
    ----------
    times : array_like
        Edge timestamps [s].
    teeth : int
        Teeth per revolution.
    errors : array_like, optional
        Tooth spacing errors [rad] (:func:`tooth_errors`).

    Returns
    -------
    t : ndarray
        Mid-times between edges [s].
    omega : ndarray
        Angular speed [rad/s], the angle between the edges over the time between them.
    """
    t = check_edges(times, teeth)
    theta = edge_angles(t.size, teeth, errors)
    return 0.5 * (t[1:] + t[:-1]), np.diff(theta) / np.diff(t)


def tooth_errors(times, teeth: int) -> np.ndarray:
    """Tooth spacing errors of a wheel from a calibration record, averaged over its whole
    revolutions [rad], mean zero, tooth 0 first.

    The rotation is taken to be smooth between once-per-revolution marks (tooth 0): a cubic
    spline of angle against time through the marks, which follows a run-up or a coast-down.
    Each edge's angle on that spline, less its nominal 2π i / z, is its tooth's error plus
    what the spline misses (vibration, timing noise); averaged over revolutions, what repeats
    every revolution is left. Whole-number orders of vibration repeat too: record the
    calibration where they are weak.

    Parameters
    ----------
    times : array_like
        Edge timestamps [s] of at least two whole revolutions (more average the noise).
    teeth : int
        Teeth per revolution.
    """
    from scipy.interpolate import CubicSpline

    t = check_edges(times, teeth, "calibration record", revolutions=2)
    revs = (t.size - 1) // teeth
    marks = t[: revs * teeth + 1 : teeth]
    smooth = CubicSpline(marks, 2.0 * np.pi * np.arange(revs + 1))
    i = np.arange(revs * teeth)
    deviation = (smooth(t[i]) - 2.0 * np.pi * i / teeth).reshape(revs, teeth).mean(axis=0)
    return deviation - deviation.mean()


# ---------------------------------------------------------------------------
# Order tracking


@dataclass(frozen=True, eq=False)
class OrderTrack:
    """Vibration of one angle by order, per block of whole revolutions.

    The angle's vibration in block b is ψ(θ) = Re Σ_k c_bk exp(i k θ), θ the wheel's angle
    from tooth 0 of the record [rad]; so a vibration a sin(kθ + φ) has c = a exp(i(φ − π/2)).

    Attributes
    ----------
    name : str
        The channel, or ``'twist'``.
    rpm : ndarray, shape (blocks,)
        Mean speed of each block [rpm].
    orders : ndarray, shape (orders,)
        Engine orders, multiples of 1 / (revolutions per block).
    amplitudes : ndarray, complex, shape (blocks, orders)
        c_bk [rad].
    """

    name: str
    rpm: np.ndarray
    orders: np.ndarray
    amplitudes: np.ndarray
    definition: str = "angle"  # what the orders are against (:data:`ORDER_DEFINITIONS`)

    def at(self, order: float) -> np.ndarray:
        """The complex amplitudes of one order, per block [rad] (an order cut)."""
        k = np.flatnonzero(np.isclose(self.orders, order, rtol=0, atol=1e-9))
        if not k.size:
            raise FetorsionError(f"{self.name}: order {order:g} is not on the tracked orders "
                                 f"(multiples of {self.orders[0]:g} up to {self.orders[-1]:g})")
        return self.amplitudes[:, int(k[0])]

    @classmethod
    def from_dict(cls, d) -> "OrderTrack":
        """The track back from its :meth:`to_dict` (each amplitude from its magnitude and phase in degrees)."""
        amplitude, phase = (np.radians(np.asarray(d[k], dtype=float)) for k in ("amplitude_deg", "phase_deg"))
        return cls(d["name"], np.asarray(d["rpm"], dtype=float), np.asarray(d["orders"], dtype=float),
                   amplitude * np.exp(1j * phase), d.get("order_definition", "angle"))

    def to_dict(self) -> dict:
        return {"name": self.name, "order_definition": self.definition, "rpm": self.rpm.tolist(),
                "orders": self.orders.tolist(),
                "amplitude_deg": np.degrees(np.abs(self.amplitudes)).tolist(),
                "phase_deg": np.degrees(np.angle(self.amplitudes)).tolist()}


def _blocks(t_grid: np.ndarray, psi: np.ndarray, per_block: int, revolutions: int, theta0: np.ndarray):
    """Mean speed [rpm] and complex order amplitudes of ψ sampled at equal angles."""
    fft = np.fft.rfft(psi[:, :-1], axis=1) * (2.0 / per_block)  # the closing edge is the next block's first
    orders = np.arange(1, fft.shape[1]) / revolutions
    if per_block % 2 == 0:  # the Nyquist bin holds a real number, not an amplitude and a phase
        orders = orders[:-1]
    c = fft[:, 1: 1 + orders.size] * np.exp(-1j * np.outer(theta0, orders))  # phase from tooth 0 of the record
    rpm = 60.0 * revolutions / (t_grid[:, -1] - t_grid[:, 0])
    return rpm, orders, c


#: What an order is taken against: the text the results carry
ORDER_DEFINITIONS = {
    "angle": "orders against the shaft's own angle (computed order tracking: equal-angle samples)",
    "time": "orders against time (equal-time samples over each block, the frequency k times the block's mean speed)",
}


def _grid(times, teeth: int, revolutions: int, errors, name: str, definition: str = "angle"):
    """The samples of each whole block, shape (blocks, N z + 1): (times, angles). ``angle``: the
    times of equal angles (the tooth pitch); ``time``: equal times from the block's first to its
    last equal angle, and the wheel's angle at each."""
    from scipy.interpolate import CubicSpline

    t = check_edges(times, teeth, name, revolutions=revolutions)
    theta = edge_angles(t.size, teeth, errors)
    per_block = revolutions * teeth
    blocks = (t.size - 1) // per_block
    index = np.arange(blocks)[:, None] * per_block + np.arange(per_block + 1)
    nominal = 2.0 * np.pi * index / teeth
    # Without tooth errors the edges are the equal angles; with them, time is interpolated at
    # the nominal angles (angle is a smooth function of time, and so time of angle)
    t_grid = t[index] if errors is None else CubicSpline(theta, t)(nominal)
    if definition == "time":
        t_grid = t_grid[:, :1] + (t_grid[:, -1:] - t_grid[:, :1]) * np.linspace(0.0, 1.0, per_block + 1)
        return t_grid, CubicSpline(t, theta)(t_grid)
    return t_grid, nominal


def order_track(times: np.ndarray, teeth: int, revolutions: int, errors: np.ndarray | None = None, name: str = "wheel",
                accelerating: bool = False, definition: str = "angle", alpha: float | None = None) -> OrderTrack:
    """The angle's vibration by order per block of ``revolutions`` whole revolutions.

    In each block the angle is sampled at equal angles (the tooth pitch), the block's mean
    rotation (the straight line through its first and last edge) is taken off, and the rest
    is Fourier transformed over the block; orders run from 1/N to below z/2.

    In a run-up the mean rotation is not a straight line: at acceleration α over a block of T
    seconds it bows from its chord by α T²/8 (at 1000 rpm/s and 900 rpm over two revolutions,
    14°), which the transform reads as low orders falling as 1/k². With ``accelerating`` the bow
    ½ α τ (τ − T) (τ the time into the block; zero at both ends, so the chord's exactness for
    whole orders is kept) is taken off as well, α from the neighbouring blocks' mean speeds
    (their chords: whole-order vibration does not move them), or ``alpha`` where it is known (a
    simulated run's schedule; a record of one block has no neighbours); a steady record has α ≈ 0.

    Parameters
    ----------
    times : array_like
        Edge timestamps [s].
    teeth : int
        Teeth per revolution, z.
    revolutions : int
        Revolutions per block, N: 2 puts a four-stroke engine's half orders on bins.
    errors : array_like, optional
        Tooth spacing errors [rad] (:func:`tooth_errors`).
    name : str
        The channel, for messages and the result.
    accelerating : bool
        Take off each block's bow of constant acceleration too (a run-up or run-down).
    definition : {"angle", "time"}
        ``angle`` (default): the angle sampled at equal angles of the wheel itself, so an order
        is a harmonic of the shaft's own angle; ``time``: sampled at equal times, an order the
        frequency k Ω̄ (Ω̄ the block's mean speed), as an analyser that resamples in time reads
        it. The two differ at second order in the vibration (a large amplitude at a high
        order: a few per cent).
    alpha : float, optional
        The wheel's mean angular acceleration where it is known, rad/s² (with ``accelerating``):
        instead of the estimate from neighbouring blocks.
    """
    revolutions = _whole(revolutions, "revolutions")
    t_grid, theta = _grid(times, teeth, revolutions, errors, name, definition)
    speed = (theta[:, -1:] - theta[:, :1]) / (t_grid[:, -1:] - t_grid[:, :1])
    tau = t_grid - t_grid[:, :1]
    psi = (theta - theta[:, :1]) - speed * tau
    if accelerating and (alpha is not None or speed.shape[0] > 1):
        if alpha is None:
            alpha = np.gradient(speed[:, 0], 0.5 * (t_grid[:, 0] + t_grid[:, -1]))[:, None]
        psi -= 0.5 * alpha * tau * (tau - tau[:, -1:])
    rpm, orders, c = _blocks(t_grid, psi, revolutions * teeth, revolutions, theta[:, 0])
    return OrderTrack(name, rpm, orders, c, definition)


def twist(times_a, times_b, teeth_a: int, teeth_b: int, revolutions: int, errors_a=None, errors_b=None,
          names=("a", "b"), definition: str = "angle") -> OrderTrack:
    """The twist θ_a − θ_b between two wheels on one shaft, by order, in wheel a's blocks.

    Wheel b's angle is interpolated (a cubic spline against time) at the times of wheel a's
    equal angles; the static twist (and the wheels' different tooth 0) is the mean, left out.

    Parameters
    ----------
    times_a, times_b : array_like
        Edge timestamps of the two wheels [s], on one clock.
    teeth_a, teeth_b : int
        Their teeth per revolution.
    revolutions : int
        Revolutions per block (of wheel a).
    errors_a, errors_b : array_like, optional
        Their tooth spacing errors [rad].
    names : tuple of str
        The two channels, for messages.
    definition : {"angle", "time"}
        As for :func:`order_track`.
    """
    from scipy.interpolate import CubicSpline

    revolutions = _whole(revolutions, "revolutions")
    t_grid, theta = _grid(times_a, teeth_a, revolutions, errors_a, names[0], definition)
    tb = check_edges(times_b, teeth_b, names[1], revolutions=1)
    inside = (t_grid[:, 0] >= tb[0]) & (t_grid[:, -1] <= tb[-1])
    if not inside.any():
        raise FetorsionError(f"{names[0]} and {names[1]}: no block of {revolutions} revolution(s) of "
                             f"{names[0]} lies within {names[1]}'s record")
    t_grid, theta = t_grid[inside], theta[inside]
    theta_b = CubicSpline(tb, edge_angles(tb.size, teeth_b, errors_b))(t_grid)
    psi = theta - theta_b
    rpm, orders, c = _blocks(t_grid, psi - psi.mean(axis=1, keepdims=True), revolutions * teeth_a,
                             revolutions, theta[:, 0])
    return OrderTrack(TWIST, rpm, orders, c, definition)


def _whole(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise FetorsionError(f"{name} = {value!r}: give a whole number >= 1")
    return int(value)


# ---------------------------------------------------------------------------
# The whole analysis


@dataclass(frozen=True, eq=False)
class TorsiographResult:
    """Order tracks of each wheel and of the twist between two, per block of revolutions."""

    tracks: dict[str, OrderTrack]
    teeth: dict[str, int]
    revolutions: int
    errors: dict[str, np.ndarray] = field(default_factory=dict)
    #: Record (channel, or "calibration " + channel) -> what :func:`repaired_edges` did to it
    repairs: dict = field(default_factory=dict)
    definition: str = "angle"

    def warnings(self) -> list[str]:
        """One line per lost or spurious edge found (a reference wheel's own gaps are not warned of)."""
        return [line for name, r in self.repairs.items() for line in r.lines(name)]

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"teeth": dict(self.teeth), "revolutions_per_block": self.revolutions,
                "tooth_errors_deg": {k: np.degrees(v).tolist() for k, v in self.errors.items()},
                "tracks": {k: v.to_dict() for k, v in self.tracks.items()},
                "repairs": self.warnings(), "order_definition": self.definition,
                "definition": "vibration angle psi(theta) = Re sum_k c_k exp(i k theta), theta from tooth 0; "
                              "amplitude |c_k|, phase arg c_k; twist = first wheel - second wheel; "
                              + ORDER_DEFINITIONS[self.definition]}

    def table(self, count: int = 4) -> str:
        """Each track's ``count`` strongest orders per block: amplitude [deg] and phase [deg]."""
        lines = [f"torsiograph: {self.revolutions} revolution(s) a block; vibration angle by order "
                 "(amplitude deg / phase deg)"]
        for name, track in self.tracks.items():
            strongest = np.sort(np.argsort(np.abs(track.amplitudes).max(axis=0))[::-1][:count])
            lines.append(f"{name}:")
            lines.append(f"{'rpm':>8} " + " ".join(f"{'order ' + format(k, 'g'):>17}" for k in track.orders[strongest]))
            for b, rpm in enumerate(track.rpm):
                c = track.amplitudes[b, strongest]
                lines.append(f"{rpm:8.1f} " + " ".join(f"{a:8.4f} / {p:6.1f}" for a, p in
                                                       zip(np.degrees(np.abs(c)), np.degrees(np.angle(c)))))
        return "\n".join(lines)

    def plot(self, orders=(1.0, 2.0), ax=None):
        """Order cuts: amplitude [deg] against mean speed, one line per track and order. Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        for name, track in self.tracks.items():
            for k in orders:
                ax.plot(track.rpm, np.degrees(np.abs(track.at(k))), "o-", ms=3, label=f"{name}, order {k:g}")
        ax.set_xlabel("mean speed [rpm]")
        ax.set_ylabel("vibration amplitude [deg]")
        ax.set_title(f"torsiograph: order cuts ({self.revolutions} revolution(s) a block)", fontsize=10)
        ax.legend(fontsize=8)
        return ax


def run_torsiograph(edges: dict[str, np.ndarray], teeth: dict[str, int | str | Wheel], revolutions: int,
                    calibration: dict[str, np.ndarray] | None = None,
                    twist_of: tuple[str, str] | None = None, definition: str = "angle") -> TorsiographResult:
    """Order tracks of every wheel, tooth errors corrected, and the twist between two of them.

    Every record is repaired first (:func:`repaired_edges`): lost edges interpolated, spurious
    ones left out, a reference wheel's gap filled and its first revolution start made tooth 0;
    what was done is in the result's ``repairs``.

    Parameters
    ----------
    edges : dict[str, ndarray]
        Channel -> edge timestamps [s] (:func:`~fetorsion.measured.edges.read_edges_csv`).
    teeth : dict[str, int or str or Wheel]
        Channel -> teeth per revolution, or a reference-gap wheel (``"60-2"``; :func:`wheel_of`).
    revolutions : int
        Revolutions per block.
    calibration : dict[str, ndarray], optional
        Channel -> edge timestamps [s] of a calibration record (:func:`tooth_errors`); a
        channel without one is analysed with uniform teeth.
    twist_of : tuple of str, optional
        The two channels whose twist (first less second) is tracked.
    definition : {"angle", "time"}
        What an order is taken against (:func:`order_track`).

    Examples
    --------
    >>> import numpy as np
    >>> import fetorsion
    >>> teeth, omega, a = 60, 3000 * np.pi / 30, 2e-3
    >>> phi = 2 * np.pi * np.arange(8 * teeth + 1) / teeth  # eight revolutions of tooth angles
    >>> edges = (phi - a * np.sin(2 * phi)) / omega  # a wheel vibrating a sin(2 theta) at 3000 rpm (to first order in a)
    >>> track = fetorsion.run_torsiograph({"pulley": edges}, {"pulley": teeth}, revolutions=4).tracks["pulley"]
    >>> k = list(track.orders).index(2.0)
    >>> np.round(np.abs(track.amplitudes[:, k]) / a, 3)  # order 2 in each block of four revolutions
    array([1., 1.])
    """
    calibration = calibration or {}
    missing = [c for c in list(edges) + list(calibration) + list(twist_of or ()) if c not in teeth]
    if missing:
        raise FetorsionError(f"channel {missing[0]!r}: no teeth per revolution given (teeth has {sorted(teeth)})")
    unknown = [c for c in list(calibration) + list(twist_of or ()) if c not in edges]
    if unknown:
        raise FetorsionError(f"channel {unknown[0]!r}: not among the recorded channels {sorted(edges)}")
    if definition not in ORDER_DEFINITIONS:
        raise FetorsionError(f"order definition {definition!r}: choose {' or '.join(ORDER_DEFINITIONS)}")
    wheels = {name: wheel_of(teeth[name], f"teeth of {name!r}") for name in set(edges) | set(calibration)}
    revolutions = _whole(revolutions, "revolutions")
    records = {**edges, **{f"calibration {name}": t for name, t in calibration.items()}}
    wheel = {**{name: wheels[name] for name in edges}, **{f"calibration {name}": wheels[name] for name in calibration}}
    for key, t in records.items():  # every record is checked before any is processed
        check_edges(t, wheel[key].positions - wheel[key].gap, key, revolutions=1)
    fixed, repairs = {}, {}
    for key, t in records.items():
        fixed[key], repairs[key] = repaired_edges(t, wheel[key], key)
    z = {name: w.positions for name, w in wheels.items()}
    errors = {name: tooth_errors(fixed["calibration " + name], z[name]) for name in calibration}
    tracks = {name: order_track(fixed[name], z[name], revolutions, errors.get(name), name, definition=definition)
              for name in edges}
    if twist_of is not None:
        a, b = twist_of
        tracks[TWIST] = twist(fixed[a], fixed[b], z[a], z[b], revolutions, errors.get(a), errors.get(b), (a, b),
                              definition=definition)
    return TorsiographResult(tracks, {k: int(z[k]) for k in edges}, int(revolutions), errors,
                             {k: v for k, v in repairs.items() if v.inserted or v.removed or v.reference_edges},
                             definition)
