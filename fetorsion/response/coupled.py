"""Forced response of the condensed FE crank in its bearings: torsion and bending together.

Each pin carries the slider-crank force of its cylinder (gas force and reciprocating inertia
along the cylinder axis, taken through the exact rod geometry into a tangential and a radial
component, :meth:`fetorsion.excitation.loads.CylinderLoads.pin_force_harmonics`), with its firing phase. The
crank is modelled in its own rotating frame, where each pin force has fixed directions: with
isotropic bearings this is exact for the linear model. The Coriolis term of that frame
(Ω G ż, :mod:`fetorsion.fe.rotating`) is included; the centrifugal spin softening is left out
with the stress stiffening of the centrifugal prestress that cancels it to first order (for
torsion exactly, docs/condensed-crank.md).

Each order q at speed Ω is a harmonic load at ω = qΩ; the reduced model (supports and
attachments on the masters, :class:`fetorsion.fe.condensed.CondensedCrank`) is solved in the
basis of its modes below three times the highest excitation frequency with a static correction
above (:func:`fetorsion.lumped_model.damped.projected_solve`), one damping ratio on every mode
of the crank (the rigid rotation responds as a free inertia). Outputs are synthesised over the
orders (:mod:`.synthesis`): pulley angle and twist, torque and bending moment through every
journal and pin mid-plane (recovered exactly from the reduced coordinates), and the bearing
forces (spring forces, or the reactions of rigid bearings), each as the vibratory amplitude
(half peak-to-peak) or the largest magnitude over the cycle, against speed.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..description.defaults import DEFAULT_SPEED_STEPS
from ..errors import FetorsionError
from ..excitation.campbell import Crossing, default_orders, response_orders
from ..excitation.loads import cylinder_loads
from ..fe.condensed import CondensedCrank
from ..fe.couplings import DOF_NAMES
from ..fe.substructure import reduced_modes, supported_matrices
from ..modes import modal_damping
from .pin_loads import journal_mean_loads, master_loads, pin_load_map
from .synthesis import half_peak_to_peak, waveform

if TYPE_CHECKING:
    from ..description.model import Crank
    from .forced import ResponseSetup


def harmonic_solution(cc: CondensedCrank, support: str, loads: np.ndarray, omegas: np.ndarray,
                      damping_ratio: float) -> np.ndarray:
    """Reduced coordinates z (..., r) for master loads (..., 6·masters) at ω (...) rad/s, by modal
    superposition over every mode of the reduced model with ``damping_ratio``; held DOF are 0."""
    Dk, Dm, held = cc.support_terms(support)
    w2, V, keep = reduced_modes(cc.reduced, Dk, Dm, held)
    w2 = np.where(np.abs(w2) < 1e-8 * np.abs(w2).max(), 0.0, w2)
    Vfull = np.zeros((cc.reduced.size, V.shape[1]))
    Vfull[keep] = V
    F = np.zeros(loads.shape[:-1] + (cc.reduced.size,), complex)
    F[..., :cc.n_master_dofs] = loads
    P = F @ Vfull  # modal forces
    om = np.asarray(omegas)[..., None]
    den = w2 - om**2 + 2j * damping_ratio * np.sqrt(w2) * om
    free = den == 0  # a static load on a motion the supports leave free (rotation, axial motion)
    if np.any(np.abs(P[free]) > 1e-9 * max(np.abs(P).max(), 1e-300)):
        raise FetorsionError("a static load moves the crank as a rigid body (torque about the axis, or axial force "
                             "without a thrust bearing); it has no steady static response")
    return np.divide(P, den, out=np.zeros_like(P), where=~free) @ Vfull.T


def bending_damping(crank: Crank, damping_ratio: float | None = None) -> dict:
    """The condensed crank's bending damping and where it comes from: ``ratio`` (ζ_b of its
    bending modes), ``source`` (a phrase) and ``assumed`` (True where nothing in the description
    gives it: the torsional ζ is then carried onto the bending, which the oil film or the
    engine's structure damp differently). ``damping_ratio``: the torsional ζ (default the
    description's)."""
    ex = crank.excitation
    zeta = ex.modal_damping_ratio if damping_ratio is None else damping_ratio
    if ex.bending_damping_ratio is not None:
        return {"ratio": ex.bending_damping_ratio, "source": ex.bending_damping_ratio_source, "assumed": False}
    b = crank.main_bearings
    if not b.rigid and b.oil_film is not None:
        return {"ratio": zeta, "assumed": False,
                "source": "the main bearings' oil film (its linearised damping, [bearings]) beside ζ on every mode"}
    return {"ratio": zeta, "assumed": True,
            "source": "assumed: the torsional ζ on the bending modes too (no bending_damping_ratio, no oil film)"}


def mode_damping_ratios(fractions: np.ndarray, damping_ratio: float, bending_ratio: float) -> np.ndarray:
    """ζ of each mode from its torsion share s of kinetic energy (``fractions[:, 0]``):
    ζ_b + (ζ_t − ζ_b) s. The modal strain-energy rule's weighting of each part's loss by its
    share of the mode's energy [Johnson1982], with the kinetic share standing for the strain
    energy's (they are equal over the whole mode, not per part: a stated approximation)."""
    s = np.clip(np.asarray(fractions, float)[:, 0], 0.0, 1.0)
    return bending_ratio + (damping_ratio - bending_ratio) * s


def supported_damping(cc: CondensedCrank, support: str, damping_ratio: float, bending_ratio: float | None = None):
    """(K, M, C, kept DOF) of the reduced crank in ``support`` with the held DOF removed: the
    crank's own losses as ``damping_ratio`` on its torsional modes and ``bending_ratio`` on its
    bending ones (:func:`mode_damping_ratios`; default the description's
    ``bending_damping_ratio``, else ``damping_ratio``), plus the bearings' dampers."""
    Dk, Dm, held = cc.support_terms(support)
    m = cc.n_master_dofs
    K, M = supported_matrices(cc.reduced, Dk, Dm)
    keep = np.setdiff1d(np.arange(cc.reduced.size), held)
    Kk, Mk = K[np.ix_(keep, keep)], M[np.ix_(keep, keep)]
    w2, V, _ = reduced_modes(cc.reduced, Dk, Dm, held)
    ex = cc.crank.excitation
    if bending_ratio is None:
        bending_ratio = damping_ratio if ex is None or ex.bending_damping_ratio is None else ex.bending_damping_ratio
    zeta = damping_ratio
    if bending_ratio != damping_ratio:
        full = np.zeros((cc.reduced.size, V.shape[1]))
        full[keep] = V
        zeta = mode_damping_ratios(cc.classify(full)[0], damping_ratio, bending_ratio)
    Ck = modal_damping(Mk, V, np.sqrt(np.clip(w2, 0.0, None)), zeta)
    if support == "bearings":
        Cb = np.zeros_like(K)
        Cb[:m, :m] = cc.bearing_damping
        Ck = Ck + Cb[np.ix_(keep, keep)]
    return Kk, Mk, Ck, keep


def damped_solution(cc: CondensedCrank, support: str, loads: np.ndarray, omegas: np.ndarray, damping_ratio: float,
                    dampers, spin=None):
    """Reduced coordinates z (..., r) with torsional dampers on the front or rear master's
    twist, and each damper's dissipated power (..., dampers) in W.

    The crank's own modal damping (``damping_ratio`` on its undamped modes) and the bearings'
    dampers stay as in :func:`harmonic_solution`; the crank without its dampers is solved by
    :func:`fetorsion.lumped_model.damped.projected_solve` (non-proportional damping) for the
    loads and a unit torque at each damper place in one block, and the dampers, their rings
    condensed exactly, follow by :func:`fetorsion.lumped_model.damped.with_dampers`. ``spin``
    (rad/s, broadcast against ``omegas``): the crank's speed, for the Coriolis term of its
    rotating frame (``cc.gyroscopic``); None leaves it out.
    """
    from ..lumped_model.damped import DampedSystem, projected_solve, unit_torques, with_dampers

    Kk, Mk, Ck, keep = supported_damping(cc, support, damping_ratio)
    where = {label: int(np.flatnonzero(keep == cc.dof(label, "rx"))[0]) for label in ("front", "rear")}
    system = DampedSystem(Mk, Kk, Ck, dampers, stations=len(keep), at=lambda d: where[d.at])
    om = np.asarray(omegas, float)
    G = None if spin is None or cc.gyroscopic is None else cc.gyroscopic[np.ix_(keep, keep)]
    F = loads_on(cc, loads, keep)
    places = sorted(set(system.carriers))
    rhs = np.concatenate([F[..., None, :], unit_torques(F.shape[:-1], len(keep), places)], axis=-2)
    sol = projected_solve(DampedSystem(Mk, Kk, Ck, (), stations=len(keep)), rhs, om, G, spin)
    x = with_dampers(sol[..., 0, :], sol[..., 1:, :], places, system, om) if dampers else sol[..., 0, :]
    z = np.zeros(loads.shape[:-1] + (cc.reduced.size,), complex)
    z[..., keep] = x[..., :len(keep)]
    return z, system.dissipated_power(x, om)


def loads_on(cc: CondensedCrank, loads: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """Master loads (..., 6·masters) as forces on the kept reduced DOF (..., kept)."""
    F = np.zeros(loads.shape[:-1] + (cc.reduced.size,), complex)
    F[..., :cc.n_master_dofs] = loads
    return F[..., keep]


def bearing_forces(cc: CondensedCrank, support: str, z: np.ndarray, loads: np.ndarray, omegas: np.ndarray,
                   spin=None) -> np.ndarray:
    """Force of each main bearing on the crank (..., journals, 2: y, z), N.

    Springs: −K_b z − iω C_b z. Rigid bearings: the reactions, from the equations of the held
    DOF, r = (K − ω² M) z − F on those rows (z is zero there).
    """
    Dk, Dm, held = cc.support_terms(support)
    m = cc.n_master_dofs
    K, M = supported_matrices(cc.reduced, Dk, Dm)
    om = np.asarray(omegas)[..., None]
    F = np.zeros(loads.shape[:-1] + (cc.reduced.size,), complex)
    F[..., :m] = loads
    out = np.zeros(z.shape[:-1] + (len(cc.crank.journals), 2), complex)
    react = np.zeros(z.shape, complex)
    if len(held):
        react[..., held] = (z @ K[held].T) - om**2 * (z @ M[held].T) - F[..., held]
        if spin is not None and cc.gyroscopic is not None:  # the Coriolis forces the bearings hold too
            react[..., held] += 1j * om * np.asarray(spin)[..., None] * (z @ cc.gyroscopic[held].T)
    spring = -(z[..., :m] @ cc.bearing_stiffness.T) - 1j * om * (z[..., :m] @ cc.bearing_damping.T)
    for j in range(len(cc.crank.journals)):
        for d, name in enumerate(("ty", "tz")):
            i = cc.dof(f"J{j + 1}", name)
            out[..., j, d] = react[..., i] if i in set(held.tolist()) else spring[..., i]
    return out


@dataclass
class CoupledResponse:
    """Forced response of the condensed crank over speed (see the module docstring).

    Amplitudes are half the peak-to-peak of the signal synthesised over the orders; force and
    moment magnitudes are the largest ``|vector|`` over the cycle.
    """

    name: str
    support: str
    rpm: np.ndarray
    orders: np.ndarray
    damping_ratio: float
    pulley_angle_deg: np.ndarray
    pulley_twist_deg: np.ndarray
    journal_torque_nm: np.ndarray  # (speeds, journals)
    pin_torque_nm: np.ndarray  # (speeds, pins)
    pin_bending_nm: np.ndarray  # (speeds, pins)
    journal_bending_nm: np.ndarray  # (speeds, journals)
    bearing_force_n: np.ndarray  # (speeds, journals)
    timings_s: dict[str, float] = field(default_factory=dict)
    dampers: str = ""
    damper_heat_w: np.ndarray | None = None  # (speeds, dampers), W

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        def worst(a):
            k = np.unravel_index(np.argmax(a), a.shape)
            return {"value": float(a[k]), "rpm": float(self.rpm[k[0]]), "index": int(k[1]) + 1 if a.ndim > 1 else None}

        return {"name": self.name, "support": self.support, "damping_ratio": self.damping_ratio,
                "rpm": self.rpm.tolist(), "orders": self.orders.tolist(),
                "pulley_angle_deg": self.pulley_angle_deg.tolist(), "pulley_twist_deg": self.pulley_twist_deg.tolist(),
                "journal_torque_nm": self.journal_torque_nm.tolist(), "pin_torque_nm": self.pin_torque_nm.tolist(),
                "pin_bending_nm": self.pin_bending_nm.tolist(), "journal_bending_nm": self.journal_bending_nm.tolist(),
                "timings_s": dict(self.timings_s),
                "bearing_force_n": self.bearing_force_n.tolist(), "dampers": self.dampers,
                "damper_heat_w": None if self.damper_heat_w is None else self.damper_heat_w.tolist(),
                "worst": {"journal_torque_nm": worst(self.journal_torque_nm), "pin_bending_nm": worst(self.pin_bending_nm),
                          "journal_bending_nm": worst(self.journal_bending_nm), "bearing_force_n": worst(self.bearing_force_n),
                          "pulley_twist_deg": worst(self.pulley_twist_deg)}}

    @classmethod
    def from_dict(cls, d) -> "CoupledResponse":
        """The response back from its :meth:`to_dict` (one written before it kept the pins' torque
        and the journals' bending is refused by name)."""
        from ..results import from_fields

        if "journal_bending_nm" not in d:
            raise FetorsionError(f"{d['name']}: the coupled response was written before results.json kept its pin "
                                 "torque and journal bending")
        return from_fields(cls, d)

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        w = self.to_dict()["worst"]
        lines = [f"coupled forced response of the condensed crank ({self.support}, ζ = {self.damping_ratio:g}"
                 + (f", {self.dampers}" if self.dampers else "") + ", "
                 f"{len(self.rpm)} speeds {self.rpm[0]:.0f}-{self.rpm[-1]:.0f} rpm, orders {self.orders[0]:g}-{self.orders[-1]:g})",
                 *([f"largest damper heat         {self.damper_heat_w.sum(axis=1).max():10.1f} W    at "
                    f"{self.rpm[int(self.damper_heat_w.sum(axis=1).argmax())]:.0f} rpm"] if self.damper_heat_w is not None else []),
                 f"largest pulley twist        {w['pulley_twist_deg']['value']:10.4f} deg  at {w['pulley_twist_deg']['rpm']:.0f} rpm"]
        for key, what, unit in (("journal_torque_nm", "journal torque", "N m"), ("journal_bending_nm", "journal bending", "N m"),
                                ("pin_bending_nm", "pin bending", "N m"), ("bearing_force_n", "bearing force", "N")):
            lines.append(f"largest {what:<19} {w[key]['value']:10.1f} {unit:<4} at {w[key]['rpm']:.0f} rpm "
                         f"({'J' if 'journal' in key or 'bearing' in key else 'P'}{w[key]['index']})")
        return "\n".join(lines)

    def plot(self, ax=None):
        """Largest vibratory journal torque and largest bearing force against speed."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4))
        ax.plot(self.rpm, self.journal_torque_nm.max(axis=1), label="largest journal torque (N m)")
        ax.plot(self.rpm, self.pin_bending_nm.max(axis=1), label="largest pin bending moment (N m)")
        ax.set_xlabel("speed (rpm)")
        ax.set_ylabel("N m")
        ax2 = ax.twinx()
        ax2.plot(self.rpm, self.bearing_force_n.max(axis=1) / 1e3, "k--", label="largest bearing force (kN)")
        ax2.set_ylabel("kN")
        ax.legend(loc="upper left", fontsize=8)
        ax2.legend(loc="upper right", fontsize=8)
        ax.set_title(f"{self.name}: condensed crank, {self.support}", wrap=True)
        ax.figure.tight_layout()
        return ax


def run_coupled_response(cc: CondensedCrank, support: str = "bearings",
                         rpm: Sequence[float] | np.ndarray | None = None,
                         orders: Sequence[float] | np.ndarray | None = None,
                         damping_ratio: float | None = None) -> CoupledResponse:
    """Forced response of a condensed crank over speed (see the module docstring).

    Parameters
    ----------
    cc : CondensedCrank
        From :func:`fetorsion.fe.condensed.run_condensed`; its crank needs ``[excitation]``.
    support : str
        ``bearings`` (default) or ``free``.
    rpm : array_like, optional
        Speeds, rpm (default :data:`DEFAULT_SPEED_STEPS` over the description's range).
    orders : array_like, optional
        Orders (default 0.5 … 24 for a four-stroke: :func:`fetorsion.excitation.campbell.response_orders`).
    damping_ratio : float, optional
        Modal damping ratio of every mode (default the description's).

    Examples
    --------
    >>> import fetorsion
    >>> cc = fetorsion.run_condensed(fetorsion.load("geometry/renault21.toml"), mesh_size=0.02)  # doctest: +SKIP
    >>> res = fetorsion.run_coupled_response(cc, support="bearings")  # doctest: +SKIP
    >>> print(res.table())  # doctest: +SKIP
    """
    import time

    crank = cc.crank
    ex = crank.excitation
    if ex is None:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [excitation] table")
    t0 = time.perf_counter()
    rpm = np.linspace(*ex.checked_range, DEFAULT_SPEED_STEPS) if rpm is None else np.asarray(rpm, float)
    orders = response_orders(crank) if orders is None else np.asarray(orders, float)
    zeta = ex.modal_damping_ratio if damping_ratio is None else damping_ratio
    loads = master_loads(cc, rpm, orders)  # (speeds, orders, 6m)
    t1 = time.perf_counter()
    omegas = orders[None, :] * rpm[:, None] * 2 * np.pi / 60
    dampers = tuple(getattr(crank, "dampers", ()))
    z, heat = damped_solution(cc, support, loads, omegas, zeta, dampers, spin=rpm[:, None] * np.pi / 30)
    period = cylinder_loads(crank).period

    def amp(x):  # (..., orders) -> (...)
        return half_peak_to_peak(x, orders, period)

    front, rear = cc.dof("front", "rx"), cc.dof("rear", "rx")
    res = np.einsum("sor,mcr->smco", z, cc.sections)  # (speeds, masters, 6, orders)
    J = [cc.labels.index(f"J{j + 1}") for j in range(len(crank.journals))]
    P = [cc.labels.index(f"P{c + 1}") for c in range(crank.throws)]
    theta = np.linspace(0.0, period, int(np.ceil(24 * orders.max() * period / (2 * np.pi))), endpoint=False)

    def largest_magnitude(vec):  # vec: (..., 2, orders) -> (...), the largest |v(θ)| over the cycle
        w = waveform(vec, orders, theta)  # (..., 2, angles)
        return np.sqrt((w**2).sum(axis=-2)).max(axis=-1)

    fb = bearing_forces(cc, support, z, loads, omegas, rpm[:, None] * np.pi / 30)  # (speeds, orders, journals, 2)
    out = CoupledResponse(
        crank.name, support, rpm, orders, zeta,
        pulley_angle_deg=np.degrees(amp(z[..., front])),
        pulley_twist_deg=np.degrees(amp(z[..., front] - z[..., rear])),
        journal_torque_nm=amp(res[:, J, 3]), pin_torque_nm=amp(res[:, P, 3]),
        pin_bending_nm=largest_magnitude(res[:, P, 4:6]), journal_bending_nm=largest_magnitude(res[:, J, 4:6]),
        bearing_force_n=largest_magnitude(np.moveaxis(fb, 1, -1)),
    )
    out.timings_s = {"loads": t1 - t0, "solve_and_synthesis": time.perf_counter() - t1}
    if dampers:
        out.dampers = ", ".join(f"{d.kind} damper '{d.name}' at the {d.at}" for d in dampers)
        out.damper_heat_w = heat.sum(axis=1)  # (speeds, dampers): all orders together
    return out


def condensed_setup(cc: CondensedCrank, support: str = "bearings", rpm: Sequence[float] | np.ndarray | None = None,
                    orders: Sequence[float] | np.ndarray | None = None, damping_ratio: float | None = None,
                    section_labels: Sequence[str] | None = None, rotating: bool = True):
    """The condensed crank as a :class:`~fetorsion.response.forced.ResponseSetup`: the engine
    model that the forced response, the fillet stress, the damper design and the verdict run on.

    Its DOF are the reduced coordinates left free by ``support``; its sections the cuts of
    ``cc.cut_rows`` (the fillets; torque about the x-parallel axis through each cut's centre:
    the crank axis for a journal, the pin's axis for a pin), else the journal and pin
    mid-planes; the pulley angle is the front master's θx, the twist front − rear; a damper
    acts on the front or rear master's θx; the damper is tuned on the torsional modes
    (torsion share of the journals' kinetic energy above one half).

    Parameters
    ----------
    cc : CondensedCrank
    support : str
        ``bearings`` (default) or ``free``.
    rpm, orders : array_like, optional
        Speeds (rpm; default :data:`DEFAULT_SPEED_STEPS` over the checked range, to overspeed) and
        orders (default 0.5 … 24 for a four-stroke: :func:`fetorsion.excitation.campbell.response_orders`).
    damping_ratio : float, optional
        The crank's modal damping ratio (default the description's).
    section_labels : list of str, optional
        Names of the cuts (default ``cut 1`` …).
    rotating : bool
        Include the Coriolis term of the crank's rotating frame (``cc.gyroscopic``, default).
    """
    from .forced import ResponseSetup

    crank = cc.crank
    ex = crank.excitation
    if ex is None:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [excitation] table")
    rpm = np.linspace(*ex.checked_range, DEFAULT_SPEED_STEPS) if rpm is None else np.asarray(rpm, float)
    orders = response_orders(crank) if orders is None else np.asarray(orders, float)
    zeta = ex.modal_damping_ratio if damping_ratio is None else damping_ratio
    Kk, Mk, Ck, keep = supported_damping(cc, support, zeta)
    loads = cylinder_loads(crank)
    harm = loads.pin_force_harmonics(rpm, orders)  # (speeds, orders, cylinders, 2)
    phasors = loads.phasors(orders)
    m = cc.n_master_dofs
    load_map = np.zeros((crank.engine.cylinders, 2, cc.reduced.size))
    load_map[:, :, :m] = pin_load_map(cc)
    load_map = load_map[:, :, keep]
    forces = np.einsum("sock,oc,ckd->sod", harm, phasors, load_map)
    if cc.cut_rows is not None:
        rows, x = cc.cut_rows[:, 3, keep], cc.cut_centres[:, 0]
        names = section_labels or [f"cut {k + 1} at x = {v * 1e3:.1f} mm" for k, v in enumerate(x)]
    else:
        inner = list(range(1, len(cc.labels) - 1))
        rows, x, names = cc.sections[inner, 3][:, keep], cc.positions[inner, 0], [cc.labels[k] for k in inner]
    md = cc.modes(support)  # elastic modes, after the support's zero-frequency motions
    torsional = np.array([md.free_motions + j for j, k in enumerate(md.kinds) if k == "torsional"])
    dof_names = [f"{lb} {d}" for lb in cc.labels for d in DOF_NAMES] + \
        [f"interior {j + 1}" for j in range(cc.reduced.size - m)]
    where = {label: int(np.flatnonzero(keep == cc.dof(label, "rx"))[0]) for label in ("front", "rear")}
    return ResponseSetup(crank.name, [dof_names[k] for k in keep], Mk, Kk, Ck, forces, rpm, orders,
                         loads.period, zeta, "", None, harm, phasors, load_map, rows, list(names),
                         section_x=np.asarray(x), pulley=where["front"], flywheel=where["rear"], damper_dof=where,
                         torsional_modes=torsional, model=f"condensed crank, {support} ({cc.reduced.size} DOF)",
                         load_kind="pin forces", projected=True,
                         gyroscopic=cc.gyroscopic[np.ix_(keep, keep)] if rotating and cc.gyroscopic is not None else None)


def assembly_modes(M, K) -> tuple[np.ndarray, np.ndarray]:
    """(ω² ascending, M-orthonormal shapes) of the undamped assembly (real part of ``K``)."""
    Linv = np.linalg.inv(np.linalg.cholesky(M))
    lam, Y = np.linalg.eigh(Linv @ np.real(K) @ Linv.T)
    return lam, Linv.T @ Y


def redamped(setup, damping_ratio: float):
    """A :func:`~fetorsion.response.driveline.driveline_setup` at another modal damping ratio: the modal part is linear in ζ,
    so C + (ζ_new − ζ) M Φ diag(2ω) Φᵀ M; the bearings' and the shafts' dampers stay."""
    import dataclasses

    lam, Phi = assembly_modes(setup.M, setup.K)
    change = modal_damping(setup.M, Phi, np.sqrt(np.clip(lam, 0.0, None)), damping_ratio - setup.zeta)
    return dataclasses.replace(setup, C=setup.C + change, zeta=damping_ratio)


def with_damping_ratio(setup: ResponseSetup, cc: CondensedCrank, support: str, damping_ratio: float,
                       bending_ratio: float | None = None):
    """``setup`` (:func:`condensed_setup` of ``cc`` in ``support``) at another modal damping
    ratio (and ``bending_ratio`` on the bending modes, default as :func:`supported_damping`): its
    forces and sections kept (they do not depend on it), only C made anew."""
    import dataclasses

    if setup.crank_dofs is not None:  # the crank in a driveline (:mod:`.driveline`): ζ on the whole assembly's modes
        return redamped(setup, damping_ratio)
    _, _, Ck, _ = supported_damping(cc, support, damping_ratio, bending_ratio)
    return dataclasses.replace(setup, C=Ck, zeta=damping_ratio)


def peak_of_phasor(v: np.ndarray) -> np.ndarray:
    """max over t of |Re(v e^{iωt})| for complex vectors v (..., k): the peak length of the ellipse
    a harmonic vector traces, √((|v|² + |v·v|)/2)."""
    return np.sqrt(0.5 * ((np.abs(v) ** 2).sum(axis=-1) + np.abs((v * v).sum(axis=-1))))


def run_coupled_campbell(cc: CondensedCrank, support: str = "bearings",
                         diameters: Sequence[Sequence[float]] | np.ndarray | None = None,
                         orders: Sequence[float] | np.ndarray | None = None, speed_range: Sequence[float] | None = None,
                         damping_ratio: float | None = None, max_modes: int = 20,
                         forces: Callable[[float, float], tuple[np.ndarray, float]] | None = None,
                         section_names: Sequence[str] | None = None):
    """Campbell diagram of the condensed crank: every mode (torsional, bending, axial, coupled)
    that an order can meet in the speed range, each crossing's severity the peak nominal
    equivalent stress √(σ_b² + 3τ²) it drives at the worst fillet cut, MPa.

    At a crossing of mode j (ω_j, unit modal mass, shape φ_j) and order q at n = 60 f_j / q, the
    full pin force of every cylinder — tangential and radial, gas and inertia, with its firing
    phase — gives the modal force P = φ_jᵀ F_q(n), and the resonant modal amplitude is
    |P| / (2 ζ ω_j²). Through each cut (``cc.cut_rows``; else the journal and pin mid-planes) the
    mode's torque T and bending moment M (its peak over the cycle) give τ = 16 T D / (π(D⁴ − d⁴))
    and σ_b = 32 M D / (π(D⁴ − d⁴)): a bending resonance and a torsional one in one unit.

    Parameters
    ----------
    cc : CondensedCrank
    support : str
        ``bearings`` (default) or ``free``.
    diameters : array_like (cuts, 2), optional
        Outer diameter and bore (m) of the section at each cut (default: the journal's or pin's).
    orders : array_like, optional
    speed_range : (float, float), optional
        rpm; default the checked range (to overspeed).
    damping_ratio : float, optional
    max_modes : int
        At most this many of the lowest elastic modes.
    forces : callable, optional
        ``forces(rpm, order)`` → (the complex master-force amplitude (6·masters,) N of that order at
        that speed, a torque harmonic N·m to show beside it); default every cylinder's pin forces
        (:meth:`fetorsion.excitation.loads.CylinderLoads.pin_force_harmonics`) and the largest
        cylinder's torque harmonic. Then ``orders``,
        ``speed_range`` and ``damping_ratio`` are required.
    section_names : list of str, optional
        The name of each cut (a fillet's label): each crossing then names its worst section
        (``worst_section``), else gives its index (``worst_cut``).
    """
    from ..excitation.campbell import CampbellResult, major_orders

    crank = cc.crank
    if forces is None:
        if crank.excitation is None:
            raise FetorsionError(f"{crank.source or crank.name}: the description has no [excitation] table")
        loads, load_map = cylinder_loads(crank), pin_load_map(cc)

        def forces(n, q):  # and the largest cylinder's torque harmonic R |F_t,q|, N·m
            h = loads.pin_force_harmonics([n], [q])[0, 0]  # (cylinders, 2): tangential, radial
            return (np.einsum("c,ck,ckd->d", loads.phasors([q])[0], h, load_map),
                    crank.engine.crank_radius * float(np.abs(h[:, 0]).max()))
        orders = default_orders(crank) if orders is None else np.asarray(orders, float)
        lo, hi = crank.excitation.checked_range if speed_range is None else speed_range
        zeta = crank.excitation.modal_damping_ratio if damping_ratio is None else damping_ratio
    else:
        orders, (lo, hi), zeta = np.asarray(orders, float), speed_range, damping_ratio
    md = cc.modes(support)
    fmax = orders.max() * hi / 60
    k = min(max_modes, int((md.frequencies_hz <= fmax).sum()) or 1)
    f, V = md.frequencies_hz[:k], md.vectors[:, :k]
    rows = cc.cut_rows if cc.cut_rows is not None else cc.sections[1:-1]
    D = np.asarray(diameters, float) if diameters is not None else \
        np.array([[c.diameter, c.bore] for c in _section_parts(cc)])
    modulus = np.pi * (D[:, 0] ** 4 - D[:, 1] ** 4) / (16 * D[:, 0])  # polar section modulus, m³
    m = cc.n_master_dofs
    crossings = []
    for j in range(k):
        w = 2 * np.pi * f[j]
        R = np.einsum("kcr,r->kc", rows, V[:, j])  # (cuts, 6) per unit modal coordinate
        for q in orders:
            n = 60 * f[j] / q
            F, torque = forces(n, q)
            terms = F * V[:m, j]
            P = terms.sum()
            a = abs(P) / (2 * zeta * w**2)
            tau = np.abs(R[:, 3]) * a / modulus
            sigma = peak_of_phasor(R[:, 4:6] * a) / (modulus / 2)
            eq = np.sqrt(sigma**2 + 3 * tau**2)
            worst = int(np.argmax(eq))
            crossings.append(Crossing(
                j + 1, float(f[j]), float(q), float(n), bool(lo <= n <= hi), float(torque),
                float(abs(P) / max(np.abs(terms).sum(), 1e-300)), float(eq[worst] / 1e6),
                f"{md.kinds[j]} ({md.fractions[j, 0]:.2f}/{md.fractions[j, 1]:.2f})",
                worst_section="" if section_names is None else section_names[worst],
                worst_cut=worst if section_names is None else None,
                shear_mpa=float(tau[worst] / 1e6), bending_mpa=float(sigma[worst] / 1e6)))
    return CampbellResult(getattr(crank, "name", ""), f"condensed FE crank, {support} ({cc.reduced.size} DOF), "
                          "full pin forces", f, orders, (lo, hi), zeta, crossings,
                          severity_unit="MPa: peak nominal equivalent stress sqrt(sigma_b^2 + 3 tau^2) at the worst "
                                        "section, resonant, one mode",
                          major=() if getattr(crank, "engine", None) is None else  # forces given without an engine
                          tuple(float(q) for q in major_orders(crank.engine) if np.any(np.isclose(orders, q))))


def _section_parts(cc: CondensedCrank):
    """The journal or pin of each mid-plane section (J1, P1, J2, …)."""
    crank = cc.crank
    return [(crank.journals if lb[0] == "J" else crank.pins)[int(lb[1:]) - 1] for lb in cc.labels[1:-1]]


def with_film_bearings(cc: CondensedCrank) -> CondensedCrank:
    """The condensed crank with its oil-film main bearings at each journal's mean load.

    For a ``[bearings]`` oil film given without ``load_n``: the mean load magnitudes of
    :func:`fetorsion.response.pin_loads.journal_mean_loads` at the film's speed give the
    short-bearing coefficients (:mod:`fetorsion.description.oilfilm`, isotropic equivalents), which
    replace the rigid placeholders; the crank it carries records the loads and eccentricities. Any
    other crank comes back as is.
    """
    import dataclasses

    from ..fe.condensed import bearing_matrices
    from ..description.oilfilm import film_coefficients, isotropic_equivalent

    b = cc.crank.main_bearings
    film = b.oil_film
    if film is None or film.load is not None:
        return cc
    loads = np.hypot(*journal_mean_loads(cc, film.speed * 30 / np.pi).T)
    k, d, ecc, att = [], [], [], []
    for j, (journal, width, clearance, load) in enumerate(zip(cc.crank.journals, b.width, film.clearance, loads)):
        coeff = film_coefficients(float(load), film.speed, journal.diameter, width, clearance, film.viscosity)
        kj, dj = isotropic_equivalent(coeff.stiffness, coeff.damping)
        k.append(kj), d.append(dj), ecc.append(coeff.eccentricity), att.append(coeff.attitude)
    film = dataclasses.replace(film, load=tuple(float(x) for x in loads), eccentricity=tuple(ecc), attitude=tuple(att))
    bearings = dataclasses.replace(b, radial_stiffness=tuple(k), radial_damping=tuple(d), oil_film=film)
    crank = dataclasses.replace(cc.crank, bearings=bearings)
    Kb, Cb, held = bearing_matrices(crank, cc.labels)
    return dataclasses.replace(cc, crank=crank, bearing_stiffness=Kb, bearing_damping=Cb, held=held)
