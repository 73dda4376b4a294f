"""Steady-state forced torsional response of a lumped crank model, summed over orders.

For each speed Ω and order q the cylinders' torque harmonics load the stations that hold
the pins, F_q = Wᵀ (T_q e^{−i q φ_c}), and

    (K − (qΩ)² M + i qΩ C) Θ_q = F_q

is solved for all speeds and orders at once (batched dense solves: the chains are small).
A chain file's hysteretic springs enter as the complex stiffness K + iH (H assembled from
η_i k_i), the same for every frequency, so the solve stays one batched call.
The angle of station s over a cycle is Σ_q Re(Θ_q,s e^{i q θ}); its vibratory amplitude
is half its peak-to-peak, found exactly by :mod:`fetorsion.response.synthesis`. Damping: a modal damping ratio ζ on every elastic mode,
C = M Φ diag(2 ζ ω_j / m_j) Φᵀ M, plus a chain file's absolute and relative dampers. The
section torque is the elastic torque k Δθ of each spring (what a strain gauge on the shaft reads).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..excitation.campbell import response_orders
from ..description.model import Crank
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError, ParameterError
from ..excitation.loads import cylinder_loads
from ..lumped_model.lumped import lumped, stated_damping
from ..modes import modal_damping_matrix
from ..lumped_model.network import network_damper_dof, rear_coordinate
from ..lumped_model.damped import DampedSystem, complex_times, damper_station
from .forced_plots import compare_lines, plot_response
from ..results import from_fields
from .synthesis import grouped_extremes, waveform
from ..description.defaults import DEFAULT_PARTITION, DEFAULT_SPEED_STEPS, DEFAULT_WEB_METHOD

if TYPE_CHECKING:
    from ..description.model import Damper
    from ..lumped_model.parts import PartChain


@dataclass
class ResponseResult:
    """Vibratory response versus engine speed.

    Attributes
    ----------
    rpm : ndarray
        Engine speeds.
    pulley_angle_deg : ndarray
        Vibratory angle (half peak-to-peak) of the pulley-end station, degrees.
    pulley_twist_deg : ndarray
        The same for the pulley relative to the flywheel-end station (elastic twist).
    section_torque_nm : ndarray, shape (speeds, springs)
        Vibratory torque (half peak-to-peak) in each shaft section, N·m.
    order_pulley_deg : ndarray, shape (speeds, orders)
        Each order's own pulley amplitude, degrees.
    section_torque_peak_nm : ndarray, shape (speeds, springs)
        Largest ``|vibratory torque|`` over the cycle (the orders summed with their phases), N·m.
    pulley_angle_peak_deg : ndarray
        The same for the pulley angle, degrees.
    theta : ndarray, shape (speeds, orders, DOF), complex
        Each order's complex angle amplitude of every station (and damper ring), rad.
    damper_power_w : ndarray, shape (speeds, dampers, orders)
        Mean power each damper dissipates, per order (orders add: they are orthogonal), W.
    misfire : int or None
        0-based cylinder that does not fire, if any.
    pulley, flywheel : int
        The DOF of the pulley-end and the flywheel-end station (a chain's first and last
        station; the condensed crank's front and rear master θx).
    """

    name: str
    labels: list[str]
    orders: np.ndarray
    rpm: np.ndarray
    pulley_angle_deg: np.ndarray
    pulley_twist_deg: np.ndarray
    section_torque_nm: np.ndarray
    order_pulley_deg: np.ndarray
    damping_ratio: float
    damping: str = ""
    compare: dict[str, float | str | list[float]] | None = None
    section_torque_peak_nm: np.ndarray | None = None
    pulley_angle_peak_deg: np.ndarray | None = None
    theta: np.ndarray | None = None
    stiffnesses_nm_per_rad: np.ndarray | None = None
    cycle_rad: float = 4 * np.pi
    damper_names: list = field(default_factory=list)
    damper_power_w: np.ndarray | None = None
    #: Each damper's rubber temperature, °C (a heat-following one's as its heat holds it; NaN: none stated).
    damper_temperatures_c: list = field(default_factory=list)
    misfire: int | None = None
    positions_m: np.ndarray | None = None
    section_labels: list = field(default_factory=list)
    section_rows: np.ndarray | None = None  # (sections, DOF), N·m per unit DOF
    section_x: np.ndarray | None = None
    model: str = "lumped chain"
    pulley: int = 0
    flywheel: int = -1

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        out = {"name": self.name, "model": self.model, "labels": self.labels, "sections": self.section_labels,
               "orders": self.orders.tolist(),
               "rpm": self.rpm.tolist(), "modal_damping_ratio": self.damping_ratio,
               "pulley_angle_deg": self.pulley_angle_deg.tolist(),
               "pulley_twist_deg": self.pulley_twist_deg.tolist(),
               "section_torque_nm": self.section_torque_nm.tolist(),
               "order_pulley_deg": self.order_pulley_deg.tolist(), "damping": self.damping_text(),
               "compare": self.compare, "misfire_cylinder": None if self.misfire is None else self.misfire + 1}
        if self.section_torque_peak_nm is not None:
            out.update(section_torque_peak_nm=self.section_torque_peak_nm.tolist(),
                       section_torque_peak_to_peak_nm=(2 * self.section_torque_nm).tolist(),
                       pulley_angle_peak_deg=self.pulley_angle_peak_deg.tolist(),
                       pulley_angle_peak_to_peak_deg=(2 * self.pulley_angle_deg).tolist())
        if self.damper_names:
            out.update(dampers=self.damper_names, damper_power_w=self.damper_power_w.sum(axis=2).tolist(),
                       damper_power_per_order_w=self.damper_power_w.tolist(),
                       damper_temperatures_c=[None if t != t else t for t in self.damper_temperatures_c])
        return out

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "ResponseResult":
        """The result back from its :meth:`to_dict` (not ``theta`` nor the rows behind :meth:`waveform`)."""
        modal, misfire, power = f"zeta = {d['modal_damping_ratio']:g}", d.get("misfire_cylinder"), d.get("damper_power_per_order_w")
        return from_fields(cls, d, {"damping_ratio": "modal_damping_ratio", "section_labels": "sections",
                                    "damper_names": "dampers"}, misfire=None if misfire is None else misfire - 1,
                           damping="" if d["damping"] == modal else d["damping"].removesuffix(f", {modal}"),
                           damper_power_w=None if power is None else np.array(power, dtype=float),
                           damper_temperatures_c=[np.nan if t is None else t for t in d.get("damper_temperatures_c", [])])

    def waveform(self, speed: int, samples: int = 720) -> dict:
        """The synthesised signals over one cycle at ``rpm[speed]``: ``angle_deg`` (crank angle),
        ``pulley_deg`` (pulley vibratory angle) and ``section_torque_nm`` (springs × angles)."""
        theta = np.linspace(0.0, self.cycle_rad, samples, endpoint=False)
        z = self.theta[speed]  # (orders, DOF)
        torque = self.section_rows @ z[:, :self.section_rows.shape[1]].T  # (sections, orders)
        return {"angle_deg": np.degrees(theta), "pulley_deg": np.degrees(waveform(z[:, self.pulley], self.orders, theta)),
                "section_torque_nm": waveform(torque, self.orders, theta)}

    def damping_text(self) -> str:
        """How the response is damped, in words."""
        modal = f"zeta = {self.damping_ratio:g}"
        return f"{self.damping}, {modal}" if self.damping else modal

    def table(self) -> str:
        """The largest pulley angle and twist and section torque, with where they occur."""
        i, a = self.pulley_twist_deg.argmax(), self.pulley_angle_deg.argmax()
        return "\n".join([
            f"{self.name}: forced response {self.rpm[0]:.0f}-{self.rpm[-1]:.0f} rpm, {self.damping_text()}",
            f"  largest pulley twist   {self.pulley_twist_deg[i]:.4f} deg at {self.rpm[i]:.0f} rpm",
            f"  largest pulley angle   {self.pulley_angle_deg[a]:.4f} deg at {self.rpm[a]:.0f} rpm",
            f"  {self.worst_torque_text()}"] + self._extra_lines() + compare_lines(self.compare))

    def worst_torque_text(self) -> str:
        """"largest section torque … N m at … rpm (section)": the alternating torque (half
        peak-to-peak) of the most loaded section, as every command prints it."""
        s, k = np.unravel_index(self.section_torque_nm.argmax(), self.section_torque_nm.shape)
        return (f"largest section torque {self.section_torque_nm[s, k]:.1f} N m at {self.rpm[s]:.0f} rpm "
                f"({self.section_labels[k]})")

    def _extra_lines(self) -> list[str]:
        lines = []
        if self.section_torque_peak_nm is not None:
            s, k = np.unravel_index(self.section_torque_peak_nm.argmax(), self.section_torque_peak_nm.shape)
            lines.append(f"  largest section torque peak {self.section_torque_peak_nm[s, k]:.1f} N m (peak-to-peak "
                         f"{2 * self.section_torque_nm[s, k]:.1f}) at {self.rpm[s]:.0f} rpm")
        if self.misfire is not None:
            lines.append(f"  misfire: cylinder {self.misfire + 1} does not fire (compression and expansion only)")
        for j, name in enumerate(self.damper_names):
            p = self.damper_power_w[:, j].sum(axis=1)
            lines.append(f"  damper '{name}': dissipates up to {p.max():.1f} W (at {self.rpm[p.argmax()]:.0f} rpm)")
        return lines

    def plot(self, ax=None):
        """Pulley angle and twist, and the most loaded section's torque, against speed.

        On a given ``ax`` only the angles are drawn; without one, a figure with both panels.
        Returns the Axes of the angles.
        """
        return plot_response(self, ax)


def run_response(crank: Crank | Chain, partition: int = DEFAULT_PARTITION,
                 rpm: Sequence[float] | np.ndarray | None = None, orders: Sequence[float] | np.ndarray | None = None,
                 damping_ratio: float | None = None, web_method: str = DEFAULT_WEB_METHOD,
                 dampers: Sequence[Damper] | None = None, misfire: int | None = None) -> ResponseResult:
    """Forced torsional response of a lumped crank model, or of a chain file, over the operating range.

    Parameters
    ----------
    crank : Crank or Chain
        With an ``[excitation]`` table (a chain also with ``[engine]`` and ``cylinder_stations``).
    partition : int
        Lumped partition (5, 6, 17, 19, 21); ignored for a chain.
    rpm : array_like, optional
        Speeds, rpm; default :data:`DEFAULT_SPEED_STEPS` steps over the description's speed range.
    orders : array_like, optional
        Orders summed; default 0.5 … 24 (4-stroke;
        :data:`fetorsion.excitation.campbell.RESPONSE_HIGHEST_ORDER`).
    damping_ratio : float, optional
        Modal damping ratio; default the description's. A chain's absolute, relative and
        hysteretic dampers act in addition.
    web_method : str
        Web-stiffness method of the lumped model (a key of
        :data:`fetorsion.webs.methods.WEB_METHODS`); ignored for a chain.
    dampers : sequence of Damper, optional
        Torsional dampers (:class:`fetorsion.description.model.Damper`); default the
        description's ``[[dampers]]``; ``()`` for none.
    misfire : int, optional
        0-based cylinder that does not fire (compression and expansion only).

    Examples
    --------
    >>> import fetorsion
    >>> from fetorsion.response.forced import run_response
    >>> r = run_response(fetorsion.load("geometry/renault21.toml"), rpm=[1000.0, 2000.0])
    >>> r.pulley_angle_deg.shape
    (2,)
    """
    setup = response_setup(crank, partition, rpm, orders, damping_ratio, web_method, misfire)
    return solve_response(setup, crank.dampers if dampers is None else tuple(dampers))


@dataclass
class ResponseSetup:
    """What a forced response needs before its dampers are chosen: the model's matrices, the
    forces of every speed and order, the sections whose torque is read, and the damping text
    (:func:`response_setup` for a lumped chain, :func:`fetorsion.response.coupled.condensed_setup`
    for the condensed crank in its bearings); solving it with any set of dampers
    (:func:`solve_response`) reuses the costly force harmonics.

    The forces are the cylinders' own, ``cylinder_harmonics`` (speeds, orders, cylinders,
    components: each cylinder's torque for a chain; its tangential and radial pin force for the
    condensed crank; :class:`fetorsion.excitation.loads.CylinderLoads`), put on the model's DOF by
    ``load_map`` (cylinders, components, DOF) with each cylinder's firing phase ``phasors``
    (orders, cylinders): a misfire changes one cylinder's share.
    """

    name: str
    labels: list  # one per DOF
    M: np.ndarray
    K: np.ndarray
    C: np.ndarray
    forces: np.ndarray  # (speeds, orders, DOF)
    rpm: np.ndarray
    orders: np.ndarray
    period: float
    zeta: float
    stated: str
    misfire: int | None
    cylinder_harmonics: np.ndarray  # (speeds, orders, cylinders, components): each firing cylinder's, N·m or N
    phasors: np.ndarray  # (orders, cylinders): e^{−i q φ_c}
    load_map: np.ndarray  # (cylinders, components, DOF)
    section_rows: np.ndarray  # (sections, DOF): torque through each section per unit DOF, N·m
    section_labels: list
    #: Where each section lies: a chain's station positions (a section is the spring between
    #: two, m) or, for cut sections, the x of each cut (``section_x``).
    positions_m: np.ndarray | None = None
    section_x: np.ndarray | None = None
    pulley: int = 0
    flywheel: int = -1
    damper_dof: dict[str, int] | None = None  # {"front": DOF, "rear": DOF}; None: the chain's end stations
    #: {at: f²} for a damper on a network's station turning f times its DOF's speed; None: all 1
    damper_scale: dict[str, float] | None = None
    #: How many leading DOF are the condensed crank's (a driveline's other coordinates follow); None: all
    crank_dofs: int | None = None
    #: Indices (in ascending order of the undamped modes) of the modes a damper is tuned on;
    #: None: every elastic mode of a free chain (all but the first, rigid one).
    torsional_modes: np.ndarray | None = None
    model: str = "lumped chain"
    load_kind: str = "torque"  # "torque" (a chain) or "pin forces" (tangential, radial)
    projected: bool = False  # solve in the modes' basis (a large reduced model)
    stiffnesses: np.ndarray | None = None  # a chain's springs, N·m/rad
    #: Coriolis matrix per unit spin speed (DOF × DOF, skew): a model in the crank's rotating
    #: frame (the condensed crank); None for a chain (torsion about the spin axis has none).
    gyroscopic: np.ndarray | None = None
    #: [(order indices, period rad)] of sources whose periods differ (:mod:`.propulsion`); None: one
    order_groups: tuple | None = None
    #: (speeds, DOF) viscous damping to ground added at each speed to ``C``'s, N·m·s/rad: a
    #: propeller's law damping at that speed less the one ``C`` holds (its linearisation speed's,
    #: :func:`fetorsion.response.propulsion.with_propellers`); None: ``C`` at every speed.
    speed_damping: np.ndarray | None = None

    def at_speeds(self, index) -> "ResponseSetup":
        """The same setup at a subset of its speeds (``index`` into ``rpm``: a slice or indices),
        exactly: each speed's forces are its own."""
        from dataclasses import replace

        out = replace(self, rpm=self.rpm[index], forces=self.forces[index],
                      cylinder_harmonics=self.cylinder_harmonics[index],
                      speed_damping=None if self.speed_damping is None else self.speed_damping[index])
        if "free_response" in self.__dict__:  # solved already: each speed's solve is its own
            out.free_response = self.free_response[index]
        if "unit_response" in self.__dict__:
            out.unit_response = (self.unit_response[0][index], self.unit_response[1])
        return out

    def with_misfire(self, cylinder: int, motored: np.ndarray) -> "ResponseSetup":
        """The same engine with ``cylinder`` (0-based) not firing: its force harmonics replaced by
        its own of ``motored`` (speeds, orders, cylinders, components; :func:`misfire_harmonics`),
        the others' unchanged."""
        from dataclasses import replace

        delta = np.einsum("sok,o,kd->sod", motored[:, :, cylinder] - self.cylinder_harmonics[:, :, cylinder],
                          self.phasors[:, cylinder], self.load_map[cylinder])
        out = replace(self, forces=self.forces + delta, misfire=cylinder)
        if "unit_response" in self.__dict__:  # the same matrices and speeds
            out.unit_response = self.unit_response
        return out

    def with_misfires(self, motored: np.ndarray) -> list["ResponseSetup"]:
        """:meth:`with_misfire` of every cylinder, in order. A projected setup's misfire responses
        come from one projected solve: each is the firing response plus the response to its
        cylinder's change of force (the same matrices: superposition), the changes a block of
        right-hand sides on each frequency's one factorisation, not a solve per cylinder."""
        out = [self.with_misfire(c, motored) for c in range(self.phasors.shape[1])]
        if self.projected:
            change = self._projected(np.stack([o.forces - self.forces for o in out], axis=2))
            for c, o in enumerate(out):
                o.free_response = self.free_response + change[:, :, c]
        return out

    def damper_station(self, damper) -> int:
        """The DOF a damper at ``damper.at`` (front or rear) acts on."""
        if self.damper_dof is None:
            return damper_station(damper, len(self.labels))
        return self.damper_dof[damper.at]

    def damper_factor(self, damper) -> float:
        """f² of a damper on a station that turns f times as fast as its DOF (1 elsewhere)."""
        return 1.0 if self.damper_scale is None else self.damper_scale.get(damper.at, 1.0)

    @functools.cached_property
    def free_response(self) -> np.ndarray:
        """θ (speeds, orders, DOF) of a projected setup without dampers: one projected solve."""
        return self._projected(self.forces[:, :, None, :])[:, :, 0]

    @functools.cached_property
    def unit_response(self) -> tuple[np.ndarray, list]:
        """(the response to a unit torque at each DOF a damper can act on (speeds, orders, places,
        DOF), those DOFs) of a projected setup: one projected solve with the unit torques as a
        block of right-hand sides. With :attr:`free_response`, any set of dampers follows by a
        small exact update (:func:`fetorsion.lumped_model.damped.with_dampers`): the damper
        designs and the heat iteration solve the large model once, not once per trial damper. It
        depends on the matrices and speeds only, so a misfire or a subset of speeds reuses it."""
        n = len(self.labels)
        places = sorted({0, n - 1} if self.damper_dof is None else set(self.damper_dof.values()))
        from ..lumped_model.damped import unit_torques

        return self._projected(unit_torques(self.forces.shape[:2], n, places)), places

    def _projected(self, rhs: np.ndarray) -> np.ndarray:
        """Projected solve of the undamped model for a block of right-hand sides (speeds, orders, r, DOF)."""
        from ..lumped_model.damped import DampedSystem, projected_solve

        omegas = self.orders[None, :] * self.rpm[:, None] * 2 * np.pi / 60
        spin = self.rpm[:, None] * 2 * np.pi / 60
        return projected_solve(DampedSystem(self.M, self.K, self.C, (), stations=len(self.labels)), rhs, omegas,
                               self.gyroscopic, spin)


def response_setup(crank: Crank | Chain, partition: int = DEFAULT_PARTITION,
                   rpm: Sequence[float] | np.ndarray | None = None, orders: Sequence[float] | np.ndarray | None = None,
                   damping_ratio: float | None = None, web_method: str = DEFAULT_WEB_METHOD,
                   misfire: int | None = None, parts: PartChain | None = None) -> ResponseSetup:
    """The chain, its damping and the cylinders' forces for :func:`run_response` (arguments as there;
    ``parts``: the crank's :class:`~fetorsion.lumped_model.parts.PartChain` for ``web_method``
    when the caller has it)."""
    ex = crank.excitation
    if ex is None:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [excitation] table")
    lo, hi = ex.checked_range
    rpm = np.linspace(lo, hi, DEFAULT_SPEED_STEPS) if rpm is None else np.asarray(rpm, dtype=float)
    orders = response_orders(crank) if orders is None else np.asarray(orders, dtype=float)
    zeta = ex.modal_damping_ratio if damping_ratio is None else damping_ratio
    if misfire is not None and not 0 <= misfire < crank.engine.cylinders:
        raise FetorsionError(f"misfire cylinder {misfire + 1}: the engine has cylinders 1..{crank.engine.cylinders}")
    res = lumped(crank, partition, web_method, parts=parts)
    M, K = res.matrices()
    # The modal damping ratio stands for the crank's own losses: it is set on the chain's modes
    # without the dampers, which bring their own damping.
    C = modal_damping_matrix(M, K, zeta)
    stated = ""
    if isinstance(crank, (Chain, Network)):
        C_stated, H = stated_damping(crank, res)
        C, K = C + C_stated, K + 1j * H
        stated = f"stated dampers of the {'network' if res.network else 'chain'}" if crank.has_dampers else ""
    if res.pin_weights is None:
        res.torsional_modes()  # raises the message that says what the chain file lacks
    W = res.pin_weights  # (cylinders, stations)
    loads = cylinder_loads(crank)
    period = loads.period
    Tq = loads.torque_harmonics(rpm, orders)  # (speeds, orders, cylinders)
    phasors = loads.phasors(orders)  # (orders, cylinders)
    forces = np.einsum("soc,oc,cd->sod", Tq, phasors, W)  # (speeds, orders, stations)
    n = len(res.labels)
    if res.network is not None:
        rows, section_labels = res.network.section_rows, list(res.network.section_labels)
        # the pulley twist is read against the last station that turns at the pulley's speed
        # and is a coordinate of its own (factor 1 in its column)
        flywheel = rear_coordinate(crank, res.network.masters)
        # a network's rear damper sits on the last coordinate at the engine's speed
        dampers_at, dampers_scale = network_damper_dof(crank, res.network, flywheel)
        model_name = f"network of {len(res.network.labels)} stations"
    else:
        k = np.real(res.stiffnesses_nm_per_rad)
        rows = np.zeros((n - 1, n))
        rows[np.arange(n - 1), np.arange(n - 1)], rows[np.arange(n - 1), np.arange(1, n)] = k, -k  # k (θ_i − θ_i+1)
        section_labels = [f"{a}-{b}" for a, b in zip(res.labels, res.labels[1:])]
        flywheel, model_name = n - 1, f"lumped {res.dof}-DOF chain ({web_method})"
        dampers_at = dampers_scale = None
    setup = ResponseSetup(crank.name, res.labels, M, K, C, forces, rpm, orders, period, zeta, stated, None,
                          Tq[..., None], phasors, W[:, None, :], rows,
                          section_labels, positions_m=res.positions_m,
                          pulley=0, flywheel=flywheel, model=model_name,
                          stiffnesses=res.stiffnesses_nm_per_rad,
                          damper_dof=dampers_at, damper_scale=dampers_scale)
    if misfire is not None:  # that cylinder's firing torque replaced by its motored one
        return setup.with_misfire(misfire, misfire_harmonics(crank, setup))
    return setup


def misfire_harmonics(crank: Crank | Chain | Network, setup: ResponseSetup) -> np.ndarray:
    """(speeds, orders, cylinders, components) force harmonics of each cylinder when it is the one
    that does not fire (compression and expansion only, plus its reciprocating inertia), in the form
    of ``setup.cylinder_harmonics`` (its torque, or its tangential and radial pin force):
    :meth:`fetorsion.excitation.loads.CylinderLoads.motored_torque_harmonics`."""
    loads = cylinder_loads(crank)
    if setup.load_kind == "torque":
        return loads.motored_torque_harmonics(setup.rpm, setup.orders)[..., None]
    return loads.motored_pin_force_harmonics(setup.rpm, setup.orders)


#: A heat-following damper's temperature is settled when an iteration moves it less than this, K.
HEAT_TOLERANCE_K = 0.05
#: Iterations allowed (each a whole solve); relaxed by :data:`HEAT_RELAXATION` against overshoot.
HEAT_ITERATIONS = 60
HEAT_RELAXATION = 0.5


def solve_theta(setup: ResponseSetup, dampers: Sequence[Damper] = ()):
    """(theta (speeds, orders, DOF) complex, ω (speeds, orders) rad/s, the DampedSystem) of a
    setup with ``dampers``: the solve without the synthesis. A chain is solved directly; a large
    reduced model in the basis of its modes (:func:`fetorsion.lumped_model.damped.projected_solve`).

    A heat-following rubber damper (``Damper.follows_heat``) is put at the temperature its own
    heat holds: T = T_air + P/G, P its largest mean dissipation over the speed range (all orders)
    and G its heat path to the air. Rubber softens and loses damping when hot, so the hot damper
    is the design case; a damper's thermal time is minutes, so it sits at the steady temperature
    of a sustained speed. Found by relaxed fixed-point iteration (a fixed point exists: the table
    is held above its top temperature, so P is bounded); the returned system's dampers carry it.
    """
    dampers = tuple(dampers)
    if not any(d.follows_heat for d in dampers):
        return _solve_theta(setup, dampers)
    temps = np.array([d.ambient_c if d.follows_heat else np.nan for d in dampers])
    hot = np.isfinite(temps)
    for _ in range(HEAT_ITERATIONS):
        current = tuple(d.at_temperature(T) if h else d for d, T, h in zip(dampers, temps, hot))
        theta, omegas, system = _solve_theta(setup, current)
        power = system.dissipated_power(theta, omegas).sum(axis=1).max(axis=0)  # (dampers,)
        held = np.array([d.ambient_c + p / d.thermal_conductance if h else np.nan
                         for d, p, h in zip(dampers, power, hot)])
        if np.all(np.abs(held[hot] - temps[hot]) < HEAT_TOLERANCE_K):
            return theta, omegas, system
        temps[hot] += HEAT_RELAXATION * (held[hot] - temps[hot])
    raise FetorsionError(f"{setup.name}: the rubber dampers' temperatures did not settle in {HEAT_ITERATIONS} "
                         f"iterations (last {', '.join(f'{T:.1f}' for T in temps[hot])} °C)")


def _solve_theta(setup: ResponseSetup, dampers):
    from ..lumped_model.damped import with_dampers

    n = len(setup.labels)
    system = DampedSystem(setup.M, setup.K, setup.C, dampers, stations=n, at=setup.damper_station,
                          scale=setup.damper_factor)
    omegas = setup.orders[None, :] * setup.rpm[:, None] * 2 * np.pi / 60
    if setup.projected:
        if not dampers:
            return setup.free_response, omegas, system
        return with_dampers(setup.free_response, *setup.unit_response, system, omegas), omegas, system
    N = len(system.M)
    forces = np.concatenate([setup.forces, np.zeros(setup.forces.shape[:2] + (N - n,))], axis=2)
    A = system.matrix(omegas)
    if setup.speed_damping is not None:  # each speed's own damping to ground (a propeller's law)
        k = np.arange(n)
        A[..., k, k] += 1j * omegas[..., None] * setup.speed_damping[:, None, :]
    return np.linalg.solve(A, forces[..., None])[..., 0], omegas, system


def section_torques(setup: ResponseSetup, theta: np.ndarray) -> np.ndarray:
    """(speeds, sections, orders) complex torque through each section, N·m."""
    n = len(setup.labels)
    return np.moveaxis(complex_times(theta[:, :, :n], np.ascontiguousarray(setup.section_rows.T)), 2, 1)


def solve_response(setup: ResponseSetup, dampers: Sequence[Damper] = ()) -> ResponseResult:
    """The forced response of a setup (:func:`response_setup`, or the condensed crank's) with ``dampers``."""
    stated = setup.stated
    if dampers:
        stated = ", ".join([stated] * bool(stated) + [f"{d.kind} damper '{d.name}' at the {d.at}" for d in dampers])
    orders, period = setup.orders, setup.period
    theta, omegas, system = solve_theta(setup, dampers)

    def synth(z):  # z: (..., orders) complex -> (half peak-to-peak, largest |value|) over a cycle
        top, bottom = grouped_extremes(z, orders, period, setup.order_groups)
        return 0.5 * (top - bottom), np.maximum(top, -bottom)

    p, f = setup.pulley, setup.flywheel
    torque_amp, torque_peak = synth(section_torques(setup, theta))
    pulley_amp, pulley_peak = synth(theta[:, :, p])
    return ResponseResult(
        name=setup.name, labels=setup.labels, orders=orders, rpm=setup.rpm,
        pulley_angle_deg=np.degrees(pulley_amp),
        pulley_twist_deg=np.degrees(synth(theta[:, :, p] - theta[:, :, f])[0]),
        section_torque_nm=torque_amp,
        order_pulley_deg=np.degrees(np.abs(theta[:, :, p])),
        damping_ratio=setup.zeta, damping=stated,
        section_torque_peak_nm=torque_peak, pulley_angle_peak_deg=np.degrees(pulley_peak), theta=theta,
        stiffnesses_nm_per_rad=None if setup.stiffnesses is None else np.real(setup.stiffnesses),
        cycle_rad=period, damper_names=[d.name for d in dampers],
        damper_temperatures_c=[float(d.temperature_c) for d in system.dampers],
        damper_power_w=np.moveaxis(system.dissipated_power(theta, omegas), 2, 1), misfire=setup.misfire,
        positions_m=setup.positions_m, section_labels=list(setup.section_labels), section_rows=setup.section_rows,
        section_x=setup.section_x, model=setup.model, pulley=p, flywheel=f,
    )


# Units a compared curve may carry: (quantity of ResponseResult it is compared with, factor to that quantity's unit).
COMPARE_UNITS = {"N m": ("section_torque_nm", 1.0), "Nm": ("section_torque_nm", 1.0),
                 "kN m": ("section_torque_nm", 1e3), "kNm": ("section_torque_nm", 1e3),
                 "deg": ("pulley_angle_deg", 1.0), "mrad": ("pulley_angle_deg", np.degrees(1e-3)),
                 "rad": ("pulley_angle_deg", np.degrees(1.0))}


def compare_curve(result: ResponseResult, rpm: Sequence[float] | np.ndarray, value: Sequence[float] | np.ndarray,
                  name: str, unit: str, section: int | None = None) -> dict:
    """Set a published or measured curve beside a response and measure the difference at the peaks.

    Parameters
    ----------
    result : ResponseResult
    rpm, value : array_like
        The curve: engine speed (rpm) and its value in ``unit``.
    name : str
        What the curve is (shown in the plot legend and table).
    unit : str
        A key of :data:`COMPARE_UNITS`: a torque is compared with a section's vibratory torque, an
        angle with the pulley's vibratory angle.
    section : int, optional
        0-based spring whose torque is compared; default the most loaded one.

    Returns
    -------
    dict
        The curve and both peaks: ``curve_peak_rpm``, ``curve_peak`` (in the quantity's unit),
        ``model_peak_rpm``, ``model_peak``, ``peak_difference_percent`` (model against curve) and
        ``model_at_curve_peak_rpm``; stored on ``result.compare``.
    """
    quantity, to_si = COMPARE_UNITS[unit]
    rpm, value = np.asarray(rpm, dtype=float), np.asarray(value, dtype=float)
    if quantity == "section_torque_nm":
        section = int(np.argmax(result.section_torque_nm.max(axis=0))) if section is None else section
        model = result.section_torque_nm[:, section]
        where = f"section {result.section_labels[section]}"
    else:
        model, where = result.pulley_angle_deg, "pulley angle"
    # Peaks compared inside the speeds both cover, so a curve reaching past the model's range is not misread.
    both = (rpm >= result.rpm.min()) & (rpm <= result.rpm.max())
    mine = (result.rpm >= rpm.min()) & (result.rpm <= rpm.max())
    if not both.any() or not mine.any():
        raise ParameterError("compare", f"{name}: the curve ({rpm.min():.0f}-{rpm.max():.0f} rpm) does not overlap "
                             f"the response's speeds ({result.rpm.min():.0f}-{result.rpm.max():.0f} rpm)")
    c = int(np.flatnonzero(both)[np.argmax(value[both])])
    m = int(np.flatnonzero(mine)[np.argmax(model[mine])])
    curve_peak = float(value[c] * to_si)
    out = {"name": name, "unit": unit, "quantity": quantity, "to_si": float(to_si), "where": where,
           "section": section, "rpm": rpm.tolist(), "value": value.tolist(),
           "curve_peak_rpm": float(rpm[c]), "curve_peak": curve_peak,
           "model_peak_rpm": float(result.rpm[m]), "model_peak": float(model[m]),
           "peak_difference_percent": float(100 * (model[m] - curve_peak) / curve_peak),
           "model_at_curve_peak_rpm": float(np.interp(rpm[c], result.rpm, model))}
    result.compare = out
    return out
