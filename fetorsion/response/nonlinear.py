"""The nonlinear time domain: the slider-crank's variable inertia and a network's nonlinear
elements (multi-stage clutch dampers, dual-mass flywheel arc springs, both with friction).

**Variable inertia.** Cylinder c's reciprocating mass m moves with the piston, S(θ) its distance
from the crank axis (:func:`fetorsion.excitation.kinematics.piston_position`, exact rod geometry);
its kinetic energy ½ m Ṡ² = ½ m S'(θ)² θ̇² is that of an inertia J_c(θ) = m S'(θ)² about the crank
axis. A chain's station already holds the mean ⟨m S'²⟩ (≈ m R²/2), so the model adds the
fluctuation δJ_c(θ) = m (S'(θ)² − ⟨S'²⟩). Lagrange's equation for the station's angle then reads

    (J + δJ_c(θ)) θ̈ + ½ δJ_c'(θ) θ̇² + (elastic and damping torques) = gas torque,

(derived here: d/dt(J θ̇) − ½ J' θ̇² = J θ̈ + ½ J' θ̇²). At constant speed ½ δJ_c' ω² = m S' S'' ω² is exactly the
reciprocating inertia torque of the constant-inertia model (:func:`~fetorsion.excitation.torque.cylinder_torque`'s
"inertia" part, with the sign of a load), so with variable inertia that torque is no longer a load: it
comes out of the equation, evaluated at the crank's actual angle θ = φ(t) − φ_c + wᵀq and speed.
The gas torque is still read at the mean angle (as the linear time domain reads it: the gas
torque's dependence on the vibration angle, Draminsky's "impulse distortion", is left out).

**Nonlinear elements** (:class:`~fetorsion.description.chain_model.NonlinearSpring`): torque
g(x0 + x) − P + T_f(z) across the twist x, with g the piecewise-linear elastic curve, P the preload
(g(x0) = P) and an elastic-perfectly-plastic (Jenkins) friction element: a spring k_s in series with
a Coulomb slider of limit T_f, its state z (the spring's twist) following ż = ẋ while
|k_s z| < T_f or the twist turns back, ż = 0 while it slides. Under a harmonic twist of amplitude A
its loop is a parallelogram of area 4 T_f (A − T_f/k_s), the Coulomb loop 4 T_f A as k_s → ∞.

**Integrators.** With either, the equations have a state-dependent mass matrix and a non-smooth
restoring force, so the exact propagator of the linear case does not apply. The default,
:func:`integrate_compiled`, is the compiled Dormand–Prince kernel of
:mod:`fetorsion.response.compiled` with the friction elements as exact Jenkins elements (about
six evaluations a sample). :func:`integrate_nonlinear`, the cross-check, writes them as a
first-order system y = (q, q̇, z) and integrates it by :func:`scipy.integrate.solve_ivp` with LSODA
(Adams while non-stiff, BDF when the friction's stick spring makes the system stiff; the linear
part's Jacobian is supplied), error-controlled (``rtol``), and sampled on the same time grid as the
linear scheme so that the same envelope and order-tracking code reads it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.integrate

from ..description.defaults import NONLINEAR_METHODS
from ..errors import FetorsionError
from ..excitation.kinematics import piston_velocity
from .transient_load import own_table, read_table, table_load, torque_table

#: Relative tolerance of the error-controlled integration: the slider-crank's inertia terms and the
#: element torques are resolved to this fraction of themselves per step.
RTOL = 1e-6
#: Samples integrated per call of solve_ivp (the memory of a long record is the output's only).
SPAN = 1 << 14
#: Integrators offered (scipy's stiff and switching ones).
METHODS = NONLINEAR_METHODS
#: The friction elements' corner exponent n: the loop is the Jenkins parallelogram but for a rounding
#: of about z_s ln(n)/n at each slip onset (0.15 z_s: loop areas within (T_f/k_s A) × 0.15 of it).
SLIP_EXPONENT = 20
#: Samples of the crank angle over which the mean of S'² is taken.
MEAN_SAMPLES = 4096


def mean_square_slope(r: float, l: float) -> float:
    """⟨S'(θ)²⟩ over a revolution, m²/rad² (the rectangle rule on a periodic function is spectral)."""
    grid = np.arange(MEAN_SAMPLES) * (2 * np.pi / MEAN_SAMPLES)
    return float(np.mean(piston_velocity(grid, r, l, 1.0) ** 2))


def slider_inertia(theta, r: float, l: float, m: float, mean: float | None = None):
    """The fluctuating part of a slider-crank's inertia about the crank axis and its derivative.

    Parameters
    ----------
    theta : array_like
        Crank angle from TDC, rad.
    r, l : float
        Crank radius and rod length, m.
    m : float
        Reciprocating mass, kg.
    mean : float, optional
        ⟨S'²⟩, m² (:func:`mean_square_slope`; computed when not given).

    Returns
    -------
    dJ, dJ_dtheta : ndarray
        δJ(θ) = m (S'(θ)² − ⟨S'²⟩), kg·m², and δJ'(θ) = 2 m S' S'', kg·m²/rad (S' = dS/dθ, m/rad).

    Examples
    --------
    >>> dJ, _ = slider_inertia(np.pi / 2, 0.05, 0.2, 1.0)   # S' = -r at 90°; ⟨S'²⟩ = r²(1/2 + λ²/8 + …)
    >>> round(float(dJ) / (0.05**2), 3)
    0.492
    """
    # S' and S'' as kinematics.piston_velocity/acceleration at ω = 1, written out once: this runs at
    # every evaluation of the equations
    lam = r / l
    sn, cs = np.sin(theta), np.cos(theta)
    D = 1.0 - (lam * sn) ** 2
    rD = np.sqrt(D)
    s1 = -r * (sn + lam * sn * cs / rD)
    s2 = -r * (cs + lam * (cs * cs - sn * sn + lam * lam * sn**4) / (D * rD))
    mean = mean_square_slope(r, l) if mean is None else mean
    return m * (s1**2 - mean), 2 * m * s1 * s2


@dataclass(frozen=True)
class SliderCranks:
    """The cylinders' variable inertia on a model's coordinates: ``weights`` (cylinders × coordinates,
    the pin's angle is wᵀq), ``fire`` (rad), crank radius ``r`` and rod ``l`` (m), mass ``m`` (kg)."""

    weights: np.ndarray
    fire: np.ndarray
    r: float
    l: float
    m: float

    def __post_init__(self):
        object.__setattr__(self, "mean", mean_square_slope(self.r, self.l))


@dataclass(frozen=True)
class ElementWork:
    """What a nonlinear element did over a run: ``name``; its plates' slip (a clutch with
    ``slip_torque``): total slip angle ``slip_rad`` (rad, both ways added), time slipping
    ``slip_time_s`` (s), energy the plates turned into heat ``slip_energy_j`` (J: the capacity times
    the slip angle) and ``slip_events`` (separate slips); the damper friction's heat
    ``friction_energy_j`` (J: its torque times its slider's travel)."""

    name: str
    slip_rad: float
    slip_time_s: float
    slip_energy_j: float
    slip_events: int
    friction_energy_j: float

    def to_dict(self) -> dict:
        return {"name": self.name, "slip_rad": self.slip_rad, "slip_time_s": self.slip_time_s,
                "slip_energy_j": self.slip_energy_j, "slip_events": self.slip_events,
                "friction_energy_j": self.friction_energy_j}


def element_work(springs, x, z, slip, h: float) -> list:
    """Each element's :class:`ElementWork` from its twist ``x``, friction state ``z`` and slip
    (rad, arrays (elements, N)) sampled every ``h`` seconds."""
    out = []
    for e, xe, ze, se in zip(springs, x, z, slip):
        ds = np.abs(np.diff(se))
        moving = ds > 1e-12 * max(1.0, float(np.abs(se).max()))
        starts = int(np.count_nonzero(moving[1:] & ~moving[:-1]) + (1 if moving.size and moving[0] else 0))
        slider = np.abs(np.diff(xe - se - ze)).sum() if e.friction > 0 else 0.0  # the friction slider's travel
        out.append(ElementWork(e.name, float(ds.sum()), float(h * np.count_nonzero(moving)),
                               float(e.slip_torque * ds.sum()), starts, float(e.friction * slider)))
    return out


@dataclass(frozen=True)
class Elements:
    """A network's nonlinear elements on its coordinates: ``rows`` (elements × coordinates, the
    twist per unit q), the :class:`~fetorsion.description.chain_model.NonlinearSpring` of each."""

    rows: np.ndarray
    springs: tuple

    def _each(name: str) -> property:  # one array over the elements of a NonlinearSpring field
        return property(lambda self: np.array([getattr(e, name) for e in self.springs]),
                        doc=f"Each element's ``{name}``.")

    x0 = _each("operating_twist")
    friction = _each("friction")
    stick = _each("stick_stiffness")
    tangent = _each("tangent")
    del _each

    def torque(self, x, z) -> np.ndarray:
        """Each element's vibratory torque (its preload taken off), N·m, at twists ``x`` and friction
        states ``z`` (rad; arrays (elements,) or (elements, samples))."""
        x, z = np.asarray(x, float), np.asarray(z, float)
        shape = (-1,) + (1,) * (x.ndim - 1)
        x0, tf = self.x0.reshape(shape), self.friction.reshape(shape)
        elastic = np.stack([e.elastic(x0[i] + x[i]) - e.preload for i, e in enumerate(self.springs)])
        return elastic + np.clip(self.stick.reshape(shape) * z, -tf, tf)

    def friction_rate(self, z, xdot) -> np.ndarray:
        """ż of the friction elements: the twist rate while sticking, falling to 0 as the stick
        spring reaches the slip limit while the twist goes on the same way (Bouc–Wen's form
        ż = ẋ (1 − H(ẋz) |z/z_s|^n) [Bouc], z_s = T_f/k_s, n = :data:`SLIP_EXPONENT`: the
        Jenkins element with its corner rounded so that ż is continuous, which a stiff integrator
        needs); 0 for an element without friction."""
        limit = self.friction / self.stick
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(limit > 0, np.abs(z) / limit, 0.0)
        loading = z * xdot > 0
        return np.where(self.friction > 0, xdot * (1.0 - np.where(loading, ratio**SLIP_EXPONENT, 0.0)), 0.0)


def stick_damping_changes(M, K, ratio: float, rows, stick, size: int) -> np.ndarray:
    """What the modal damping adds in each stick state of friction elements: for each mask m (bit b:
    element b sticks), C_modal(K + Σ_b∈m k_s,b d_b d_bᵀ) − C_modal(K), padded to ``size`` coordinates.

    The modal damping ratio is set on the modes of the structure as it moves: a friction element
    that sticks adds its stick spring, and its mode is then the stiff one; without this a stuck
    clutch's mode kept the damping matrix of the sliding state's lower frequency (ζ 0.03 fell to
    0.010 there). Sliding, the friction itself dissipates.

    Parameters
    ----------
    M, K : ndarray (n, n)
        The mean inertia (kg·m²) and the stiffness with the elements at their operating stage
        (N·m/rad) on which the modal damping was set.
    ratio : float
        The modal damping ratio ζ.
    rows : ndarray (f, ≥ n)
        Each friction element's twist per unit coordinate (its first n columns are read).
    stick : ndarray (f,)
        The stick springs, N·m/rad.
    size : int
        Coordinates of the integrated model (a damper's rings after the first n: no change there).

    Returns
    -------
    ndarray (2^f, size, size)
        The corrections, N·m·s/rad (mask 0, all sliding: zero).
    """
    from ..modes import modal_damping_matrix

    n, f = M.shape[0], len(stick)
    base = modal_damping_matrix(M, K, ratio)
    out = np.zeros((1 << f, size, size))
    for mask in range(1, 1 << f):
        Ks = K + sum(stick[b] * np.outer(rows[b, :n], rows[b, :n]) for b in range(f) if mask >> b & 1)
        out[mask, :n, :n] = modal_damping_matrix(M, Ks, ratio) - base
    return out


def integrate_nonlinear(M, K, C, t, phi, omega, alpha: float, force, cranks: SliderCranks | None = None,
                        elements: Elements | None = None, v0=None, method: str = "LSODA", rtol: float = RTOL,
                        stuck_damping=None):
    """Integrate M(q, t) q̈ + (slider-crank terms) + C q̇ + K q + Σ dᵀ T_e = F(t) (module docs).

    Parameters
    ----------
    M, K, C : ndarray (r, r)
        Mean inertia (kg·m²), the linear stiffness without the nonlinear elements (N·m/rad), damping
        (N·m·s/rad).
    t : ndarray (N,)
        Sample times, s, uniform.
    phi, omega : callable
        The mean motion φ(t), rad, and its speed, rad/s, of station 1.
    alpha : float
        The mean motion's angular acceleration, rad/s² (0 in a steady run).
    force : callable
        F(t) → (r,) the loads on the coordinates, N·m.
    cranks : SliderCranks, optional
        The cylinders' variable inertia (None: constant).
    elements : Elements, optional
        The nonlinear elements.
    v0 : ndarray (r,), optional
        Initial q̇, rad/s (rest otherwise).
    method : str
        One of :data:`METHODS`.
    rtol : float
        Relative tolerance of the error control.
    stuck_damping : ndarray (2^f, r, r), optional
        The damping for each stick state of the f elements with friction, as in
        :func:`integrate_compiled` (Bouc–Wen's z never sits strictly inside its limit while it slides:
        an element sticks here while its state is below 0.99 of it).

    Returns
    -------
    q : ndarray (r, N)
        The vibration angles, rad.
    z : ndarray (elements, N)
        The friction states, rad.
    nfev : int
        Right-hand-side evaluations.
    """
    if elements is not None and any(e.slip_torque > 0 for e in elements.springs):
        raise ValueError(f"{method}: a clutch's slip (slip_torque) is integrated by the compiled kernel only")
    r = M.shape[0]
    ne = 0 if elements is None else elements.rows.shape[0]
    D = np.zeros((0, r)) if elements is None else elements.rows
    Minv = np.linalg.inv(M)
    jac = _linear_jacobian(Minv, K, C, D, elements)
    fidx = np.flatnonzero(elements.friction > 0) if ne else np.zeros(0, int)
    zlim = elements.friction[fidx] / elements.stick[fidx] if ne else np.zeros(0)
    bits = 1 << np.arange(fidx.size)

    def rhs(tt, y):
        q, v, z = y[:r], y[r:2 * r], y[2 * r:]
        Cm = C if stuck_damping is None else stuck_damping[int(bits[np.abs(z[fidx]) < 0.99 * zlim].sum())]
        F = force(tt) - Cm @ v - K @ q
        Meff = M
        if cranks is not None:
            W = cranks.weights
            th = phi(tt) - cranks.fire + W @ q
            thd = omega(tt) + W @ v
            dJ, dJp = slider_inertia(th, cranks.r, cranks.l, cranks.m, cranks.mean)
            F = F - W.T @ (0.5 * dJp * thd**2 + dJ * alpha)
            Meff = M + (W.T * dJ) @ W
        if ne:
            x, xd = D @ q, D @ v
            F = F - D.T @ elements.torque(x, z)
            zdot = elements.friction_rate(z, xd)
        else:
            zdot = np.zeros(0)
        a = Minv @ F if cranks is None else np.linalg.solve(Meff, F)
        return np.concatenate([v, a, zdot])

    N = t.size
    q = np.empty((r, N))
    zs = np.empty((ne, N))
    y = np.zeros(2 * r + ne)
    if v0 is not None:
        y[r:2 * r] = v0
    nfev = 0
    start = 0
    q[:, 0], zs[:, 0] = y[:r], y[2 * r:]
    while start < N - 1:
        stop = min(N - 1, start + SPAN)
        sol = scipy.integrate.solve_ivp(rhs, (t[start], t[stop]), y, method=method, t_eval=t[start:stop + 1],
                                        rtol=rtol, atol=_atol(r, ne),
                                        jac=None if ne else (lambda tt, yy: jac))
        if sol.status < 0:
            raise RuntimeError(f"the {method} integration failed at t = {sol.t[-1]:.6g} s: {sol.message}")
        q[:, start:stop + 1] = sol.y[:r]
        zs[:, start:stop + 1] = sol.y[2 * r:]
        y = sol.y[:, -1]
        nfev += sol.nfev
        start = stop
    return q, zs, nfev


def _linear_jacobian(Minv, K, C, D, elements: Elements | None) -> np.ndarray:
    """d(q̇, q̈, ż)/d(q, q̇, z) with the elements at their tangent stiffness and their friction stuck."""
    r, ne = Minv.shape[0], D.shape[0]
    sticking = np.zeros(ne) if elements is None else np.where(elements.friction > 0, elements.stick, 0.0)
    K_t = K + (0 if elements is None else D.T @ ((elements.tangent + sticking)[:, None] * D))
    jac = np.zeros((2 * r + ne, 2 * r + ne))
    jac[:r, r:2 * r] = np.eye(r)
    jac[r:2 * r, :r] = -Minv @ K_t
    jac[r:2 * r, r:2 * r] = -Minv @ C
    if ne:
        jac[2 * r:, r:2 * r] = np.where(elements.friction[:, None] > 0, D, 0.0)
    return jac


def _atol(r: int, ne: int) -> np.ndarray:
    # absolute floors far below any angle (1e-10 rad) or speed (1e-7 rad/s) a result is read to
    return np.concatenate([np.full(r, 1e-10), np.full(r, 1e-7), np.full(ne, 1e-10)])


def integrate_compiled(M, K, C, t, phi, omega, load, cranks: SliderCranks | None = None,
                       elements: Elements | None = None, v0=None, rtol: float = RTOL, stuck_damping=None):
    """Integrate the equations of :func:`integrate_nonlinear` by the compiled Dormand–Prince kernel
    of :mod:`fetorsion.response.compiled`, its friction elements as exact Jenkins elements and a
    clutch's plates (``slip_torque``) as a slider in series with its damper.

    Parameters
    ----------
    M, K, C, t, cranks, elements, v0, rtol
        As :func:`integrate_nonlinear`.
    phi, omega : ndarray (N,)
        The mean motion of station 1 at the samples: angle, rad, and speed, rad/s (read linearly
        between them).
    load : callable
        ``load(a, b)`` → (r, b − a): the loads on the coordinates at samples a … b − 1, N·m (read
        linearly between samples).
    stuck_damping : ndarray (2^f, r, r), optional
        The damping matrix for each stick state of the f elements with friction (in their order;
        bit b set: the b-th sticks), N·m·s/rad; None: ``C`` throughout.

    Returns
    -------
    q : ndarray (r, N)
        The vibration angles, rad.
    z : ndarray (elements, N)
        The friction states (the stick springs' twists), rad.
    slip : ndarray (elements, N)
        The plates' slip of each element since the start, rad (0 for one that cannot slip).
    nfev : int
        Evaluations of the accelerations.
    """
    from .compiled import run_kernel

    r, N = M.shape[0], t.size
    h = float(t[1] - t[0])
    Minv = np.linalg.inv(M)
    if cranks is None:
        W, fire, geometry = np.zeros((0, r)), np.zeros(0), (1.0, 1.0, 0.0, 0.0)
    else:
        W, fire = np.ascontiguousarray(cranks.weights, float), np.asarray(cranks.fire, float)
        geometry = (cranks.r, cranks.l, cranks.m, cranks.mean)
    B = np.ascontiguousarray(Minv @ W.T)
    P = np.ascontiguousarray(W @ B)
    springs = () if elements is None else elements.springs
    ne = len(springs)
    D = np.zeros((0, r)) if elements is None else np.ascontiguousarray(elements.rows, float)
    stages = max([len(e.curve(c)[0]) for e in springs for c in (False, True)], default=1)
    kst, edges = np.zeros((ne, 2, stages)), np.full((ne, 2, stages), np.inf)
    nst = np.zeros((ne, 2), dtype=np.int64)
    for i, e in enumerate(springs):
        for side in (0, 1):
            k, angles = e.curve(bool(side))
            kst[i, side, :len(k)], edges[i, side, :len(k)], nst[i, side] = k, (0.0, *angles), len(k)
    x0, tf, ks = (np.zeros(0), np.zeros(0), np.zeros(0)) if elements is None else \
        (elements.x0, elements.friction, elements.stick)
    preload = np.array([e.preload for e in springs], float)
    cap = np.array([e.slip_torque for e in springs], float)
    # the stick states select the damping only where it was given for them
    fidx = np.zeros(0, np.int64) if stuck_damping is None else np.flatnonzero(tf > 0).astype(np.int64)
    Cs = np.ascontiguousarray(C[None] if stuck_damping is None else stuck_damping, float)
    if Cs.shape[0] != 1 << fidx.size:
        raise ValueError(f"stuck_damping: needs 2^{fidx.size} matrices, got {Cs.shape[0]}")
    q, zs, ss = np.empty((r, N)), np.empty((ne, N)), np.empty((ne, N))
    y = np.zeros(2 * r)
    if v0 is not None:
        y[r:] = v0
    z, slip = np.zeros(ne), np.zeros(ne)
    nfev, h_try, start = 0, h, 0
    atol = _atol(r, 0)
    while start < N - 1:
        stop = min(N - 1, start + SPAN)
        n = stop + 1 - start
        F = np.ascontiguousarray(np.asarray(load(start, stop + 1), float).T)
        qo, zo, so = np.empty((r, n)), np.empty((ne, n)), np.empty((ne, n))
        done, h_try, status = run_kernel(y, z, slip, h, F, np.ascontiguousarray(phi[start:stop + 1], float),
                                         np.ascontiguousarray(omega[start:stop + 1], float), Minv, K, Cs, fidx, W,
                                         fire, *geometry, B, P, D, x0, preload, tf, ks, kst, edges, nst, cap, rtol,
                                         atol[0], atol[r], qo, zo, so, h_try)
        nfev += done
        if status:
            raise RuntimeError(f"the compiled integration failed between t = {t[start]:.6g} and {t[stop]:.6g} s: "
                               "its step control found no step that met the tolerance")
        q[:, start:stop + 1], zs[:, start:stop + 1], ss[:, start:stop + 1] = qo, zo, so
        start = stop
    return q, zs, ss, nfev


def nonlinear_run(model, M, K, C, rows, W, fire, prop, rigid_speed, t, n_of_t, phi_of_t, run, rate, lo, top,
                  elements, variable_inertia, method, setup):
    """A time-domain run (:func:`fetorsion.response.transient.run_transient`) with variable inertia or
    nonlinear elements, by :func:`integrate_compiled` or :func:`integrate_nonlinear`.

    Parameters
    ----------
    model : Chain or Network
        The model run (its engine and excitation).
    M, K, C : ndarray (r, r)
        Inertia (kg·m²), the stiffness with the elements at their operating stage (N·m/rad) and
        damping (N·m·s/rad) of the model's coordinates.
    rows : ndarray (sections, r)
        Each section's torque per unit coordinate, N·m/rad (the elements' sections last).
    W : ndarray (cylinders, r)
        Where each cylinder acts on the coordinates.
    fire : ndarray (cylinders,)
        The firing angles, rad.
    prop : Propagator
        The linear model's propagator (:func:`fetorsion.response.transient.propagator`): its rigid-body mode.
    rigid_speed : float
        The rigid-body mode's start speed, rad/s of η₀.
    t : ndarray (N,)
        Sample times, s, uniform.
    n_of_t, phi_of_t : callable
        The mean motion: speed (rpm) and angle (rad) at times t (s).
    run : (float, float) or None
        A run's start and end speed, rpm; None: steady running.
    rate : float or None
        The run's |dn/dt|, rpm/s.
    lo, top : float
        The lowest and highest speed of the torque table, rpm.
    elements : tuple of NonlinearSpring
        The network's nonlinear elements.
    variable_inertia : bool
        The slider-cranks' crank-angle-dependent inertia on their stations.
    method : str
        One of :data:`METHODS`.
    setup : ResponseSetup
        The model's response setup: the modal damping of each stick state is set on its M and K.

    Returns
    -------
    q : ndarray (r, N)
        The vibration angles, rad.
    torque : ndarray (sections, N)
        The section torques, N·m.
    scheme : str
        The integrator, its tolerance and evaluations, and what was nonlinear.
    work : list of ElementWork
        Each element's slip and friction heat over the run.
    """
    ne = len(elements)
    tangent = np.array([e.tangent for e in elements])
    D = rows[rows.shape[0] - ne:] / tangent[:, None] if ne else np.zeros((0, M.shape[0]))
    K_lin = K - D.T @ (tangent[:, None] * D)  # the elements' operating stiffness out: they act as they are
    cranks = None
    if variable_inertia:
        if np.any(np.abs(W.sum(axis=1) - 1) > 1e-9):
            raise FetorsionError(f"{model.name}: variable inertia needs every cylinder on a station that turns at "
                                 "the engine's speed (its weights summing to 1)")
        e, ex = model.engine, model.excitation
        cranks = SliderCranks(W, fire, e.crank_radius, e.rod_length, ex.reciprocating_mass)
    grid, step, table = torque_table(model, lo, top, part="gas" if variable_inertia else "total")
    alpha = 0.0 if run is None else math.copysign(rate, run[1] - run[0]) * math.pi / 30
    # the modal damping on the modes of each stick state of the friction elements
    rubbing = [i for i, e in enumerate(elements) if e.friction > 0]
    stuck = None
    if rubbing and setup.zeta > 0:
        stuck = C[None] + stick_damping_changes(np.real(setup.M), np.real(setup.K), setup.zeta, D[rubbing],
                                                Elements(D, elements).stick[rubbing], M.shape[0])

    v0 = None if prop.rigid is None else rigid_speed * prop.rigid
    parts = Elements(D, elements) if ne else None
    slip = np.zeros((ne, t.size))
    if method == "compiled":
        phi, n_t = phi_of_t(t), n_of_t(t)

        load = table_load(W, fire, grid, step, table, phi, n_t)
        q, z, slip, nfev = integrate_compiled(M, K_lin, C, t, phi, n_t * (math.pi / 30), load, cranks, parts, v0,
                                              stuck_damping=stuck)
    else:
        def force(tt):
            phi_t, n_t = phi_of_t(tt), n_of_t(tt)
            return W.T @ np.array([read_table(grid, step, own_table(table, c), phi_t - f, n_t) for c, f in enumerate(fire)])

        q, z, nfev = integrate_nonlinear(M, K_lin, C, t, phi_of_t, lambda tt: n_of_t(tt) * math.pi / 30, alpha,
                                         force, cranks, parts, v0, method, stuck_damping=stuck)
    torque = rows @ q
    work = []
    if ne:
        x = D @ q
        torque[rows.shape[0] - ne:] = parts.torque(x - slip, z)
        work = element_work(elements, x, z, slip, float(t[1] - t[0]))
    what = " and ".join(w for w, on in (("variable inertia", variable_inertia),
                                        (f"{ne} nonlinear element{'s' * (ne > 1)}", ne)) if on)
    how = ("compiled Dormand-Prince 5(4), friction as exact Jenkins elements" if method == "compiled"
           else f"{method} (scipy solve_ivp)")
    if stuck is not None:
        what += ", modal damping on each stick state's modes"
    return q, torque, f"{how}, rtol {RTOL:g}, {nfev} evaluations: {what}", work
