"""Torsional damper design: Den Hartog's classical optima, the amplification of a damped chain,
and the tuning of a damper on the whole crank — Den Hartog's optimum as the start, then a
numeric optimisation on the full forced response over the speed range.

A damper's element (its ring as one more degree of freedom, its spring and loss in the chain's
matrices) is part of the model, :mod:`fetorsion.lumped_model.damped`, since the Campbell
diagram and the forced response below this stage see it; its design is here.

The crank's mode to damp (the first, by default) is reduced to the single-degree-of-freedom
system Den Hartog's optima assume: with its shape φ scaled to 1 at the damper's station, the
equivalent inertia is the modal inertia J_eq = φᵀMφ and ω_n its frequency. For a ring of
inertia μ J_eq (the inertia limit the user gives through μ):

* viscous: c = 2 ζ_opt J_ring ω_n, ζ_opt = 1/√(2(1 + μ)(2 + μ));
* tuned: ring frequency f_opt ω_n = ω_n/(1 + μ), c = 2 ζ_opt J_ring ω_n, ζ_opt = √(3μ/(8(1 + μ)³));
* rubber: the tuned stiffness, and the loss factor that dissipates as the tuned optimum's
  dashpot at the ring frequency, η = c ω_a / k = 2 ζ_opt / f_opt.

The numeric optimisation then varies the stiffness and the damping (log scale, Nelder–Mead;
a viscous damper: its coefficient, bounded scalar search) with the ring inertia held, to
minimise the objective over every speed of the response: the largest vibratory shear stress
at any fillet (``stress``) or the largest pulley twist (``twist``). Each evaluation reuses the
cylinders' forces (:func:`fetorsion.response.forced.response_setup`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg
import scipy.optimize

from ..description.defaults import DEFAULT_INERTIA_RATIO, DEFAULT_PARTITION
from ..description.model import DAMPER_STATIONS, Crank, Damper
from ..description.chain_model import Chain
from ..errors import FetorsionError, ParameterError
from ..response.forced import response_setup, section_torques, solve_theta
from ..response.synthesis import group_maxima, half_peak_to_peak, largest_half_peak_to_peak
from .scfset import SCFSet

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from ..response.forced import ResponseSetup
    from .stress import Fillet

OBJECTIVES = ("stress", "twist", "fatigue")


def viscous_optimum(mu: float) -> tuple[float, float]:
    """Den Hartog's untuned viscous damper: (optimum ζ = c/(2 J_ring ω_n), peak amplification)."""
    return 1.0 / np.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)), 1.0 + 2.0 / mu


def tuned_optimum(mu: float) -> tuple[float, float, float]:
    """Den Hartog's tuned absorber: (ring frequency / ω_n, optimum ζ = c/(2 J_ring ω_n),
    height of the fixed points = peak amplification at the optimum)."""
    return 1.0 / (1.0 + mu), np.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3)), np.sqrt(1.0 + 2.0 / mu)


def amplification(M, K, C, station: int, omegas) -> np.ndarray:
    """|θ_station| per unit static deflection under a unit harmonic torque on ``station``:
    |(K − ω²M + iωC)⁻¹|_ss · K_static, where the static deflection is that of the system
    without its dampers' dynamics, 1/(K⁻¹)_ss⁻¹ with the ring free to follow (ω = 0)."""
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    force = np.zeros(len(M))
    force[station] = 1.0
    A = K[None] - omegas[:, None, None] ** 2 * M[None] + 1j * omegas[:, None, None] * C[None]
    theta = np.linalg.solve(A, np.broadcast_to(force, (len(omegas), len(M)))[..., None])[..., station, 0]
    static = np.linalg.lstsq(np.real(K), force, rcond=None)[0][station]
    return np.abs(theta) / abs(static)


def peak_amplification(M, K, C, station: int, omega_range: tuple[float, float], samples: int = 2001) -> tuple[float, float]:
    """Largest :func:`amplification` in ``omega_range`` (rad/s): a dense sweep, then the best
    sample refined by a bounded scalar search between its neighbours. Returns (peak, ω)."""
    omegas = np.linspace(*omega_range, samples)
    amp = amplification(M, K, C, station, omegas)
    j = int(np.argmax(amp))
    lo, hi = omegas[max(j - 1, 0)], omegas[min(j + 1, samples - 1)]
    res = scipy.optimize.minimize_scalar(lambda w: -amplification(M, K, C, station, w)[0], bounds=(lo, hi),
                                         method="bounded", options={"xatol": 1e-10 * hi})
    return float(-res.fun), float(res.x)



def equivalent_sdof(M: np.ndarray, K: np.ndarray, station: int, mode: int = 0,
                    candidates=None) -> tuple[float, float]:
    """(J_eq kg·m², ω_n rad/s) of elastic mode ``mode`` (0-based) seen from ``station``: the modal
    inertia with the shape scaled to 1 there, and the mode's frequency. ``candidates``: indices,
    in ascending order of the undamped modes, of the modes to count (a condensed crank's
    torsional ones); default every mode after the free chain's rigid rotation."""
    lam, vec = scipy.linalg.eigh(np.real(K), M)
    j = mode + 1 if candidates is None else int(candidates[mode])
    phi = vec[:, j]
    if abs(phi[station]) < 1e-9 * np.abs(phi).max():
        raise FetorsionError(f"mode {mode + 1} has a node at the damper's station: a damper there cannot act on it")
    phi = phi / phi[station]
    return float(phi @ M @ phi), float(np.sqrt(lam[j]))


#: Loss factor of damper rubbers (filled natural rubber and EPDM blends), low to high: the range
#: engine practice states for torsional damper rubbers (no published table was read; a damper
#: with a measured table gives its own values). Den Hartog's design and the optimiser keep a
#: rubber damper's loss factor inside it.
RUBBER_LOSS_FACTOR_RANGE = (0.1, 0.3)


def den_hartog_damper(kind: str, mu: float, J_eq: float, omega_n: float, at: str = "front",
                      hub_inertia: float = 0.0) -> Damper:
    """Den Hartog's optimum damper of ``kind`` (viscous, tuned, rubber) for ring inertia μ J_eq."""
    if not mu > 0:
        raise ParameterError("mu", f"{mu!r}: must be > 0")
    ring = mu * J_eq
    if kind == "viscous":
        zeta, _ = viscous_optimum(mu)
        return Damper("viscous", at, hub_inertia, ring, damping=2 * zeta * ring * omega_n,
                      name=f"Den Hartog viscous, mu = {mu:g}")
    f, zeta, _ = tuned_optimum(mu)
    k = ring * (f * omega_n) ** 2
    c = 2 * zeta * ring * omega_n
    if kind == "tuned":
        return Damper("tuned", at, hub_inertia, ring, stiffness=k, damping=c, name=f"Den Hartog tuned, mu = {mu:g}")
    if kind == "rubber":
        # the absorber's optimum η = 2ζ/f (0.55 at μ = 0.25) is beyond any damper rubber: held to
        # the rubber's range, the tuning kept
        eta = float(np.clip(2 * zeta / f, *RUBBER_LOSS_FACTOR_RANGE))
        held = "" if eta == 2 * zeta / f else f", loss factor held at {eta:g} (Den Hartog's {2 * zeta / f:.2f})"
        return Damper("rubber", at, hub_inertia, ring, stiffness=k, loss_factor=eta,
                      name=f"Den Hartog rubber, mu = {mu:g}{held}")
    raise ParameterError("kind", f"{kind!r}: choose viscous, rubber or tuned")


def stress_weights(crank: Crank, setup, scf: SCFSet, fillets=None) -> np.ndarray:
    """Pa of fillet shear per N·m of each section's torque in ``setup`` (a chain's spring or a
    cut section): SCF · 16 D / (π (D⁴ − d_i⁴)) of the most stressed fillet the section carries
    (0 for one that carries none); ``fillets`` as :func:`fetorsion.design.stress.fillets_of`
    gives them, when the caller has them."""
    from .stress import fillet_sections, fillets_of
    from .scf import nominal_shear

    fillets = fillets_of(crank) if fillets is None else fillets
    sections = fillet_sections(fillets, setup)
    w = np.zeros(len(setup.section_labels))
    for f, s in zip(fillets, sections):
        w[s] = max(w[s], scf.torsion[f.kind] * float(nominal_shear(1.0, f.diameter, f.bore)))
    return w


@dataclass
class DamperResult:
    """A damper tuned on the whole crank.

    Attributes
    ----------
    den_hartog, optimised : Damper
        The classical start and the numeric optimum (``optimised`` None without ``--optimise``).
    rpm : ndarray
    curves : dict of str to ndarray
        The objective against speed without a damper, with Den Hartog's and with the optimised one.
    peaks : dict of str to float
        The largest value of each curve.
    """

    name: str
    kind: str
    mu: float
    objective: str
    mode_hz: float
    equivalent_inertia_kgm2: float
    den_hartog: Damper
    optimised: Damper | None
    rpm: np.ndarray
    curves: dict = field(default_factory=dict)
    peaks: dict = field(default_factory=dict)
    evaluations: int = 0
    #: The objective's acceptable largest value, where it has one (a fatigue utilisation's
    #: 1/required safety), and what it is
    limit: float | None = None
    limit_label: str = ""

    @property
    def unit(self) -> str:
        return {"stress": "MPa", "twist": "deg", "fatigue": "-"}[self.objective]

    def _scaled(self, v):
        return v / 1e6 if self.objective == "stress" else v

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        def damper(d):
            return None if d is None else {"type": d.kind, "at": d.at, "hub_inertia_kgm2": d.hub_inertia,
                                           "ring_inertia_kgm2": d.ring_inertia, "stiffness_nm_per_rad": d.stiffness,
                                           "damping_nms_per_rad": d.damping, "loss_factor": d.loss_factor, "name": d.name}
        unit = {"stress": "pa", "twist": "deg", "fatigue": "utilisation"}[self.objective]
        return {"name": self.name, "type": self.kind, "inertia_ratio": self.mu, "objective": self.objective,
                "mode_hz": self.mode_hz, "equivalent_inertia_kgm2": self.equivalent_inertia_kgm2,
                "den_hartog": damper(self.den_hartog), "optimised": damper(self.optimised),
                "rpm": self.rpm.tolist(), **{f"{k}_{unit}": v.tolist() for k, v in self.curves.items()},
                **{f"peak_{k}_{unit}": v for k, v in self.peaks.items()}, "evaluations": self.evaluations,
                "limit": self.limit, "limit_label": self.limit_label}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "DamperResult":
        """The result back from its :meth:`to_dict`: its curves and peaks from the keys ending in
        the objective's unit, in order; each damper's figures as :meth:`to_dict` keeps them."""
        from ..results import from_fields

        unit = "_" + {"stress": "pa", "twist": "deg", "fatigue": "utilisation"}[d["objective"]]
        ends = {k[:-len(unit)]: v for k, v in d.items() if k.endswith(unit)}
        curves = {k: np.asarray(v, dtype=float) for k, v in ends.items() if not k.startswith("peak_")}
        peaks = {k[len("peak_"):]: v for k, v in ends.items() if k.startswith("peak_")}
        return from_fields(cls, d, {"kind": "type", "mu": "inertia_ratio"}, den_hartog=damper_of(d["den_hartog"]),
                           optimised=damper_of(d["optimised"]), curves=curves, peaks=peaks)

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        what = {"stress": "largest fillet shear stress", "twist": "largest pulley twist",
                "fatigue": "largest fatigue utilisation sigma_V/sigma_DW (1/safety)"}[self.objective]
        lines = [f"{self.name}: {self.kind} damper, mu = {self.mu:g} of J_eq = {self.equivalent_inertia_kgm2:.4g} kg m^2 "
                 f"(mode at {self.mode_hz:.1f} Hz seen from the {self.den_hartog.at})",
                 f"  objective: {what} over the speed range [{self.unit}]"]
        for key, d in (("none", None), ("den_hartog", self.den_hartog), ("optimised", self.optimised)):
            if key not in self.peaks:
                continue
            text = "" if d is None else (f"  ring {d.ring_inertia:.4g} kg m^2, k {d.stiffness:.4g} N m/rad, "
                                         f"c {d.damping:.4g} N m s/rad, eta {d.loss_factor:.3g}")
            lines.append(f"  {key.replace('_', ' '):<11} {self._scaled(self.peaks[key]):10.4g}{text}")
        return "\n".join(lines)

    def plot(self, ax=None):
        """The objective against speed without and with each damper. Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4.5))
        labels = {"none": "no damper", "den_hartog": "Den Hartog start", "optimised": "optimised"}
        for key, curve in self.curves.items():
            ax.plot(self.rpm, self._scaled(curve), label=labels[key])
        ax.set_xlabel("engine speed [rpm]")
        ax.set_ylabel({"stress": "fillet shear stress", "twist": "pulley twist",
                       "fatigue": "fatigue utilisation 1/safety"}[self.objective] + f" [{self.unit}]")
        if self.limit is not None:
            ax.axhline(self.limit, color="k", ls="--", lw=0.8, label=self.limit_label or f"limit {self.limit:.3g}")
            ax.set_ylim(0, 1.1 * max(self.limit, max(float(np.max(self._scaled(c))) for c in self.curves.values())))
        ax.set_title(f"{self.name}:\n{self.kind} damper, μ = {self.mu:g}", fontsize=9, wrap=True)
        ax.legend(fontsize=8)
        return ax


def damper_of(d: Mapping[str, object] | None) -> Damper | None:
    """A damper from its entry of :meth:`DamperResult.to_dict` (None: none)."""
    if d is None:
        return None
    return Damper(d["type"], d["at"], d["hub_inertia_kgm2"], d["ring_inertia_kgm2"], d["stiffness_nm_per_rad"],
                  d["damping_nms_per_rad"], d["loss_factor"], name=d.get("name", ""))


def run_damper(crank: Crank | Chain, kind: str = "rubber", mu: float = DEFAULT_INERTIA_RATIO, optimise: bool = True,
               objective: str = "stress", at: str = "front", hub_inertia: float = 0.0, mode: int = 0,
               scf: SCFSet | None = None, rpm: Sequence[float] | np.ndarray | None = None,
               partition: int = DEFAULT_PARTITION, setup: ResponseSetup | None = None,
               fillets: list[Fillet] | None = None, utilisation: Callable[[np.ndarray], np.ndarray] | None = None,
               **setup_options) -> DamperResult:
    """Den Hartog start and numeric optimum of a damper on the whole crank.

    Parameters
    ----------
    crank : Crank or Chain
        With ``[excitation]``; its own ``[[dampers]]`` are left out (this designs one).
    kind : str
        ``viscous``, ``rubber`` or ``tuned``.
    mu : float
        Ring inertia over the equivalent inertia of the damped mode at the station (-).
    optimise : bool
        Run the numeric optimisation after the Den Hartog start.
    objective : str
        ``stress`` (largest fillet shear stress, Pa; a crank only), ``twist`` (pulley twist, deg)
        or ``fatigue`` (the fatigue verdict's utilisation σ_V/σ_DW = 1/safety, from
        ``utilisation``; minimising its largest value maximises the governing safety).
    at : str
        ``front`` (pulley end) or ``rear``.
    hub_inertia : float
        Hub or housing inertia, kg·m².
    mode : int
        0-based elastic mode the Den Hartog start tunes to.
    scf : SCFSet, optional
        Fillet SCFs for ``stress`` (default :func:`fetorsion.design.scf.fillet_scfs`).
    rpm : array_like, optional
        Speeds, rpm (default the response's).
    partition : int
        Lumped partition (5, 6, 17, 19, 21) of the response model; ignored for a chain.
    setup : ResponseSetup, optional
        The crank's :func:`~fetorsion.response.forced.response_setup` when the caller has it
        (then ``rpm``, ``partition`` and ``setup_options`` are its own).
    fillets : list of Fillet, optional
        :func:`fetorsion.design.stress.fillets_of` the crank, when the caller has them.
    utilisation : callable, optional
        For ``fatigue``: (speeds, sections) alternating section torques (N·m, half peak-to-peak)
        → (speeds,) utilisation (:func:`fetorsion.design.m53.m53_utilisation`).
    **setup_options
        To :func:`~fetorsion.response.forced.response_setup` when ``setup`` is not given.

    Returns
    -------
    DamperResult
        The Den Hartog and optimised dampers (inertia kg·m², stiffness N·m/rad, damping
        N·m·s/rad) and the response with each.

    Examples
    --------
    >>> import fetorsion
    >>> res = fetorsion.run_damper(fetorsion.load("geometry/peugeot_glx_engine.toml"), optimise=False)
    >>> res.kind, res.mu, res.den_hartog is not None
    ('rubber', 0.25, True)
    """
    if objective not in OBJECTIVES:
        raise ParameterError("objective", f"{objective!r}: choose {' or '.join(OBJECTIVES)}")
    if at not in DAMPER_STATIONS:
        raise ParameterError("at", f"{at!r}: choose {' or '.join(DAMPER_STATIONS)}")
    if objective in ("stress", "fatigue") and isinstance(crank, Chain):
        raise ParameterError("objective", f"{objective}: a chain file has no shaft sections; use twist")
    if objective == "fatigue" and utilisation is None:
        raise ParameterError("objective", "fatigue: needs the verdict's utilisation (σ_V/σ_DW from the section torques)")
    setup = response_setup(crank, partition, rpm, **setup_options) if setup is None else setup
    station = setup.damper_station(Damper(kind, at, 0.0, 1.0))
    J_eq, omega_n = equivalent_sdof(setup.M, setup.K, station, mode, setup.torsional_modes)
    start = den_hartog_damper(kind, mu, J_eq, omega_n, at, hub_inertia)
    weights = np.ones(len(setup.section_labels))
    if objective == "stress":
        from .scf import fillet_scfs

        weights = stress_weights(crank, setup, fillet_scfs(crank) if scf is None else scf, fillets)

    def signals(dampers):  # the objective's complex amplitudes by order, and their weights
        theta, _, _ = solve_theta(setup, dampers)
        if objective == "twist":
            return theta[:, :, setup.pulley] - theta[:, :, setup.flywheel], np.degrees(1.0)
        return section_torques(setup, theta), weights[None, :]

    def curve(dampers):  # the objective at each speed
        z, scale = signals(dampers)
        hpp = half_peak_to_peak(z, setup.orders, setup.period) * scale
        if objective == "fatigue":  # the verdict's utilisation 1/safety at each speed
            return utilisation(hpp)
        return hpp if hpp.ndim == 1 else hpp.max(axis=1)

    def peak(dampers):  # its largest value, what the optimiser calls some 80 times
        if objective == "fatigue":
            if getattr(utilisation, "groups", None) is None:
                return float(curve(dampers).max())
            z, _ = signals(dampers)
            return float(utilisation(group_maxima(z, setup.orders, setup.period, utilisation.groups))[0])
        z, scale = signals(dampers)
        return largest_half_peak_to_peak(z, setup.orders, setup.period, scale)

    res = DamperResult(crank.name, kind, mu, objective, omega_n / (2 * np.pi), J_eq, start, None, setup.rpm)
    for key, dampers in (("none", ()), ("den_hartog", (start,))):
        res.curves[key] = curve(dampers)
        res.peaks[key] = float(res.curves[key].max())
    if optimise:
        best, count = optimise_damper(lambda d: peak((d,)), start)
        best = replace(best, name=f"optimised {kind}, mu = {mu:g}")
        res.optimised, res.evaluations = best, count
        res.curves["optimised"] = curve((best,))
        res.peaks["optimised"] = float(res.curves["optimised"].max())
    return res


#: Nelder–Mead's stop in log stiffness and log loss (or damping).
NM_XATOL = 1e-2


def optimise_damper(peak, start: Damper, span: float = 30.0) -> tuple[Damper, int]:
    """The damper minimising ``peak(damper)``, its ring inertia held: a viscous damper's coefficient
    by a bounded scalar search over start/``span`` … start·``span`` (log scale); a tuned or rubber
    damper's stiffness and damping (c, or η) by Nelder–Mead in log scale from ``start``. Returns the
    damper and the number of evaluations."""
    calls = [0]

    def counted(d):
        calls[0] += 1
        return peak(d)

    if start.kind == "viscous":
        c0 = start.damping
        r = scipy.optimize.minimize_scalar(lambda x: counted(replace(start, damping=c0 * np.exp(x))),
                                           bounds=(-np.log(span), np.log(span)), method="bounded",
                                           options={"xatol": 1e-3})
        return replace(start, damping=c0 * float(np.exp(r.x))), calls[0]
    loss_key = "loss_factor" if start.kind == "rubber" else "damping"
    k0, l0 = start.stiffness, getattr(start, loss_key)

    def make(x):
        x = np.clip(x, -np.log(span), np.log(span))
        loss = l0 * float(np.exp(x[1]))
        if start.kind == "rubber":  # as built: a rubber's loss factor stays in its range
            loss = float(np.clip(loss, *RUBBER_LOSS_FACTOR_RANGE))
        return replace(start, stiffness=k0 * float(np.exp(x[0])), **{loss_key: loss})

    # 1 % in stiffness and loss: a tenth of a rubber's production spread (±10 % in shear
    # modulus); the search to 0.1 % took twice the evaluations for no design difference
    r = scipy.optimize.minimize(lambda x: counted(make(x)), np.zeros(2), method="Nelder-Mead",
                                options={"xatol": NM_XATOL, "fatol": 1e-4 * counted(start), "initial_simplex":
                                         np.array([[0.0, 0.0], [0.1, 0.0], [0.0, 0.3]]), "maxfev": 200})
    return make(r.x), calls[0]
