"""The linear time domain's model (:mod:`fetorsion.response.transient`): the response setup's
matrices with the ``[[dampers]]`` as coordinates (a rubber table as Maxwell branches), the loss
factors' viscous equivalent, and the pieces of the exact propagator: the undamped modes with the
free rigid-body mode apart, and the first-order-hold recursion's coefficients.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg


#: Speeds at which a heat-following rubber damper's temperature is found for a run (its
#: dissipation's largest value over them sets it, as in the frequency domain).
HEAT_SPEEDS = 60


def with_dampers(model, setup, dampers, speeds, partition, damping_ratio, web_method, notes):
    """The model's matrices with its ``[[dampers]]`` (:mod:`fetorsion.response.transient`'s docs):
    (M, K complex, C, branches, ring labels). A ring is a coordinate; a viscous or tuned damper's
    dashpot joins C, its spring (with any loss factor, on ``K``'s imaginary part) K; a rubber damper
    with a dynamic table is its :func:`fetorsion.lumped_model.damped.maxwell_fit`: k∞ joins K, each
    branch is one of ``branches`` = (D, k, c, k at the band's middle) for
    :func:`fetorsion.response.transient.propagator`, or None without any. A heat-following rubber is
    read at the temperature the frequency domain finds for ``speeds`` (lowest, highest rpm: one
    speed when equal), with the default orders. Appends what it did to ``notes``."""
    from ..lumped_model.damped import DampedSystem, maxwell_fit
    from .forced import response_setup, solve_theta

    if not dampers:
        return setup.M, setup.K, np.real(setup.C), None, []
    if any(d.follows_heat for d in dampers):
        lo, hi = speeds
        grid = [lo] if hi == lo else np.linspace(lo, hi, HEAT_SPEEDS)
        hot = response_setup(model, partition, rpm=grid, damping_ratio=damping_ratio, web_method=web_method)
        dampers = solve_theta(hot, dampers)[2].dampers
        notes.extend(f"damper '{d.name}': rubber at {d.temperature_c:.1f} °C, the temperature its heat holds "
                     f"over {lo:g}-{hi:g} rpm in the frequency domain" for d in dampers if d.follows_heat)
    n = len(setup.labels)
    system = DampedSystem(setup.M, setup.K, np.real(setup.C), dampers, stations=n, at=setup.damper_station,
                          scale=setup.damper_factor)
    M, K, C = system.M, system.K.astype(complex), system.C
    rows, kb, cb, kmid = [], [], [], []
    for d, (s, r) in zip(system.dampers, system.joints):
        u = np.zeros(len(M))
        u[s], u[r] = 1.0, -1.0
        if d.kind == "rubber" and d.table:
            fit = maxwell_fit(d)
            K = K + fit.k_inf * np.outer(u, u)
            mid = 2 * np.pi * np.sqrt(fit.band_hz[0] * fit.band_hz[1])
            for k, c in zip(fit.stiffness, fit.damping):
                rows.append(u)
                kb.append(k)
                cb.append(c)
                kmid.append(np.real(k * 1j * mid * c / k / (1 + 1j * mid * c / k)))
            notes.append(f"damper '{d.name}': its dynamic table as k_inf = {fit.k_inf:.4g} N m/rad and "
                         f"{fit.stiffness.size} Maxwell branches fitted over {fit.band_hz[0]:g}-{fit.band_hz[1]:g} Hz; "
                         f"at the table's rows |k*| within {100 * fit.stiffness_error:.2f} %, the loss factor "
                         f"within {fit.loss_error:.4f} (held at the end rows outside in the frequency domain, "
                         "the model's own relaxation here)")
        else:
            K = K + d.stiffness * (1 + 1j * d.loss_factor) * np.outer(u, u)
    labels = [f"damper '{d.name}' ring" for d in dampers]
    if not kb:
        return M, K, C, None, labels
    return M, K, C, (np.array(rows), np.array(kb), np.array(cb), np.array(kmid)), labels


def hysteretic_equivalent(M, K, H) -> np.ndarray:
    """Viscous C_η = MΦ diag(φ_jᵀHφ_j/ω_j)ΦᵀM: the loss factors' dissipation at each elastic
    mode's resonance (:mod:`fetorsion.response.transient`'s docs); the rigid-body mode gets none."""
    lam, Phi = scipy.linalg.eigh(K, M)
    elastic = lam > 1e-8 * np.abs(lam).max()
    c = np.zeros_like(lam)
    c[elastic] = np.einsum("ij,ik,kj->j", Phi[:, elastic], H, Phi[:, elastic]) / np.sqrt(lam[elastic])
    return M @ Phi @ np.diag(c) @ Phi.T @ M


def transient_matrices(model, speeds: tuple[float, float], partition: int, damping_ratio: float | None,
                       web_method: str):
    """The model's response setup and the time domain's matrices of it with its dampers.

    Parameters
    ----------
    model : Crank, Chain or Network
        With ``[engine]`` and ``[excitation]``.
    speeds : (float, float)
        The run's lowest and highest speed, rpm (the setup is made at the highest; a heat-following
        rubber's temperature is found over both).
    partition, web_method
        The lumped model of a crank (ignored for a chain or network).
    damping_ratio : float, optional
        Modal damping ratio ζ; default the description's.

    Returns
    -------
    tuple
        (the :class:`~fetorsion.response.forced.ResponseSetup`, M, K (real), C (the loss factors'
        viscous equivalent in it), the Maxwell branches (D, k, c) or None, the rings' labels, the
        notes of what was done).
    """
    from .forced import response_setup

    lo, top = speeds
    setup = response_setup(model, partition, rpm=[top], orders=[1.0], damping_ratio=damping_ratio,
                           web_method=web_method)
    dampers = tuple(getattr(model, "dampers", ()))
    notes = []
    M, Kc, C, branches, ring_labels = with_dampers(model, setup, dampers, (lo, top), partition, damping_ratio,
                                                   web_method, notes)
    K, H = np.real(Kc), np.imag(Kc)
    if np.any(H):
        # the Maxwell branches' stiffness at the middle of their band joins K for the modes C_η is set on
        Kmid = K if branches is None else K + branches[0].T @ (branches[3][:, None] * branches[0])
        C = C + hysteretic_equivalent(M, Kmid, H)
        notes.append("loss factors enter as the viscous damping that dissipates as much at each mode's "
                     "resonance (exact there, not between)")
    if branches is not None:
        branches = branches[:3]
    return setup, M, K, C, branches, ring_labels, notes


def rigid_and_elastic_modes(M, K, C, Kb, grounded: bool):
    """The undamped modes (ΦᵀMΦ = I) with a free rigid-body mode apart.

    Parameters
    ----------
    M, K, C : ndarray (r, r)
        Inertia (kg·m²), stiffness (N·m/rad) and damping (N·m·s/rad).
    Kb : ndarray (r, r)
        The Maxwell branches' springs on the coordinates, N·m/rad (they too hold a mode).
    grounded : bool
        A grounded model has no rigid-body mode.

    Returns
    -------
    rigid : ndarray (r,) or None
        The rigid-body mode that nothing damps, mass-normalised.
    Phi : ndarray (r, m)
        The other modes.
    lam : ndarray (m,)
        Their ω², (rad/s)².
    """
    lam_u, Phi = scipy.linalg.eigh(K, M)  # ΦᵀMΦ = I
    rigid = None
    if not grounded:
        # A rigid-body mode: zero stiffness, and neither damping nor a Maxwell branch on it. Zero
        # stiffness may have several shapes (a viscous damper's ring turns freely on its fluid):
        # within them, the one that nothing damps.
        zero = np.abs(lam_u) <= 1e-8 * abs(lam_u[-1])
        if zero.any():
            Z = Phi[:, zero]
            s_, R = np.linalg.eigh(Z.T @ (C + Kb) @ Z)
            Z = Z @ R
            phi0 = Z[:, 0]
            if s_[0] <= 1e-12 * max(np.abs(C).max(initial=0.0), np.abs(Kb).max(initial=0.0)) * (phi0 @ phi0):
                rigid, Phi, lam_u = phi0, np.hstack([Z[:, 1:], Phi[:, ~zero]]), np.concatenate(
                    [np.zeros(zero.sum() - 1), lam_u[~zero]])
    return rigid, Phi, lam_u


def hold_coefficients(lam, h: float):
    """The first-order-hold recursion's coefficients of each modal state at step ``h`` (s):
    (e^{λh}, I₀ − I₁/h, I₁/h), I₀ = (e^{λh} − 1)/λ, I₁ = (e^{λh} − 1 − λh)/λ², by their series
    where λh is small.

    Parameters
    ----------
    lam : ndarray
        The states' eigenvalues, 1/s.
    h : float
        The step, s.
    """
    lh = lam * h
    E = np.exp(lh)
    small = np.abs(lh) < 1e-5  # series: the closed forms lose digits as λh → 0
    with np.errstate(divide="ignore", invalid="ignore"):
        I0 = np.where(small, h * (1 + lh / 2 + lh**2 / 6), (E - 1) / lam)
        I1 = np.where(small, h * h * (0.5 + lh / 6 + lh**2 / 24), (E - 1 - lh) / lam**2)
    return E, I0 - I1 / h, I1 / h
