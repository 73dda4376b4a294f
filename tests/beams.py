"""Independent closed-form references for the modal tests (1D beam and shaft theory)."""

from __future__ import annotations

import numpy as np
import scipy.linalg
import scipy.optimize


def cowper_circle(nu: float) -> float:
    """Cowper's shear coefficient of a solid circular section."""
    return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)


def timoshenko_free_free_hz(E, nu, rho, L, D, count=3, kappa=None):
    """Lowest ``count`` bending frequencies (Hz) of a free-free Timoshenko beam of solid round section.

    Frequency equation: with state y = [w, ψ, M, Q] along x,
        w' = ψ + Q / (κGA),  ψ' = M / (EI),  M' = -ρIω²ψ - Q,  Q' = -ρAω² w,
    and free ends (M = Q = 0 at x = 0 and L), the 2 × 2 block of exp(A L) mapping (w, ψ)(0)
    to (M, Q)(L) is singular. Variables are scaled (x by L, forces by EI/L²) so exp stays
    well conditioned.
    """
    G = E / (2 * (1 + nu))
    A, I = np.pi * D**2 / 4, np.pi * D**4 / 64
    kappa = cowper_circle(nu) if kappa is None else kappa

    def det(omega):
        # dimensionless: ξ = x/L, w̄ = w/L, M̄ = M L/(EI), Q̄ = Q L²/(EI)
        s = E * I / (kappa * G * A * L**2)
        a = rho * A * omega**2 * L**4 / (E * I)
        b = rho * I * omega**2 * L**2 / (E * I)
        Amat = np.array([[0, 1, 0, s], [0, 0, 1, 0], [0, -b, 0, -1], [-a, 0, 0, 0]], float)
        Phi = scipy.linalg.expm(Amat)
        return np.linalg.det(Phi[2:, :2])

    # Euler-Bernoulli roots bracket from above; scan upward from a small ω.
    f_eb = np.array([4.7300407448627, 7.8532046240958, 10.995607838002, 14.137165491257])**2 \
        / (2 * np.pi * L**2) * np.sqrt(E * I / (rho * A))
    grid = np.linspace(0.05 * f_eb[0], 1.05 * f_eb[count - 1], 600) * 2 * np.pi
    vals = np.array([det(o) for o in grid])
    roots = [scipy.optimize.brentq(det, grid[i], grid[i + 1], xtol=1e-12)
             for i in np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0]]
    return np.array(roots[:count]) / (2 * np.pi)


def euler_bernoulli_free_free_hz(E, rho, L, D, count=3):
    beta = np.array([4.7300407448627, 7.8532046240958, 10.995607838002])[:count]
    A, I = np.pi * D**2 / 4, np.pi * D**4 / 64
    return beta**2 / (2 * np.pi * L**2) * np.sqrt(E * I / (rho * A))


def shaft_with_end_disk_hz(G, rho, L, D, disk_inertia, count=3):
    """Torsion of a free shaft (polar inertia ρJL) carrying a rigid disk at x = L.

    θ = cos(kx) is free at x = 0; the disk's balance GJ θ'(L) = I_d ω² θ(L) gives
    tan(kL) = -μ kL with μ = I_d / (ρJL); f = kL c / (2πL), c = √(G/ρ).
    """
    J = np.pi * D**4 / 32
    mu = disk_inertia / (rho * J * L)
    c = np.sqrt(G / rho)
    g = lambda z: np.sin(z) + mu * z * np.cos(z)  # noqa: E731  (tan z + μz = 0 without poles)
    roots = [scipy.optimize.brentq(g, (n - 0.5) * np.pi + 1e-12, n * np.pi) for n in range(1, count + 1)]
    return np.array(roots) * c / (2 * np.pi * L)


def timoshenko_pinned_midload(E, nu, rho, L, D, omega, force, disc_mass=0.0, kappa=None):
    """A simply supported Timoshenko beam of solid round section, a harmonic force at mid-span on a
    point mass there: (deflection, bending moment at mid-span, support reaction), magnitudes.

    State y = [w, ψ, M, Q] as in :func:`timoshenko_free_free_hz`; by symmetry the half span
    0 ≤ x ≤ L/2 with w = M = 0 at the support and ψ = 0, Q = P/2 at mid-span, where the net
    point load is P = force + m ω² w(L/2) (the mass's inertia). Exact for the beam model.
    """
    G = E / (2 * (1 + nu))
    A, I = np.pi * D**2 / 4, np.pi * D**4 / 64
    kappa = cowper_circle(nu) if kappa is None else kappa
    a = L / 2
    # dimensionless: ξ = x/L, w̄ = w/L, M̄ = M L/(EI), Q̄ = Q L²/(EI)
    s = E * I / (kappa * G * A * L**2)
    m_a = rho * A * omega**2 * L**4 / (E * I)
    m_i = rho * I * omega**2 * L**2 / (E * I)
    Amat = np.array([[0, 1, 0, s], [0, 0, 1, 0], [0, -m_i, 0, -1], [-m_a, 0, 0, 0]], float)
    T = scipy.linalg.expm(Amat * a / L)
    f = force * L**2 / (E * I)
    md = disc_mass * omega**2 * L**3 / (E * I)
    # unknowns (ψ0, Q0): ψ(a) = 0; Q(a) − md w̄(a)/2 = f/2
    lhs = np.array([[T[1, 1], T[1, 3]], [T[3, 1] - 0.5 * md * T[0, 1], T[3, 3] - 0.5 * md * T[0, 3]]])
    psi0, q0 = np.linalg.solve(lhs, [0.0, 0.5 * f])
    w_mid = (T[0, 1] * psi0 + T[0, 3] * q0) * L
    m_mid = (T[2, 1] * psi0 + T[2, 3] * q0) * E * I / L
    return abs(w_mid), abs(m_mid), abs(q0 * E * I / L**2)
