"""Mode identification by rigid-body fits to axial slabs of the shaft.

For each mode and each slab (a main journal of a crank, an axial slice of a bar, or an
attached rigid body on the axis) the displacement of the slab's nodes is fitted in the
mass-weighted least-squares sense by a rigid motion

    u(X) ≈ t + θ × (X - c),      c = the slab's centre of mass,

and the kinetic energy of that rigid motion (up to the common factor ω²/2) is split into

    torsion   J_xx θ_x²                           (twist about the crank axis),
    bending   m (t_y² + t_z²) + J_yy θ_y² + J_zz θ_z²   (transverse translation, tilt),
    axial     m t_x²,

summed over the slabs and normalised to fractions that add up to 1. Why not the share of
tangential kinetic energy of the whole solid: on a crank, torsion drags the webs and pins
into bending, so that share stays low for the unmistakable first torsional mode (at most
0.62 measured on the reference cranks); the journals themselves still turn as rigid bodies.

``rigid_fit`` is the share of the slabs' motion that the rigid fits capture: low values
mean the slabs themselves deform (breathing/ovalising and local modes), labelled
``other``.
"""

from __future__ import annotations

import numpy as np

from .rigid import rigid_rows

KINDS = ("torsional", "bending", "axial")
#: A kind wins the label when it holds more than this share of the fitted kinetic energy.
DOMINANT = 0.5
#: Below this share of the slabs' motion captured by the rigid fits, the mode is "other".
MIN_RIGID_FIT = 0.5


def axial_slabs(xyz: np.ndarray, count: int) -> list[np.ndarray]:
    """Node indices of ``count`` equal-length slices of the x range of ``xyz`` (m)."""
    x = xyz[:, 0]
    edges = np.linspace(x.min(), x.max(), count + 1)
    which = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, count - 1)
    order = np.argsort(which, kind="stable")
    return np.split(order, np.cumsum(np.bincount(which, minlength=count))[:-1])


def slab_fit(U: np.ndarray, xyz: np.ndarray, w: np.ndarray):
    """Mass-weighted rigid fit of every mode over one slab.

    Parameters
    ----------
    U : ndarray, shape (k, n, 3)
        Displacements of the slab's n nodes in k modes (any unit).
    xyz : ndarray, shape (n, 3)
        Node positions, m.
    w : ndarray, shape (n,)
        Node masses, kg.

    Returns
    -------
    p : ndarray, shape (k, 6)
        (t, θ) of the fitted motion about the slab's centre of mass.
    m : float
        Slab mass, kg.
    J : ndarray, shape (3, 3)
        Slab inertia tensor about its centre of mass, kg·m².
    norm2, resid2 : ndarray, shape (k,)
        Σ w |u|² and Σ w |u - fit|² per mode.
    """
    m = w.sum()
    c = (w[:, None] * xyz).sum(axis=0) / m
    A = rigid_rows(xyz, c)  # (n, 3, 6)
    AtWA = np.einsum("n,nip,niq->pq", w, A, A)
    rhs = np.einsum("n,nip,kni->kp", w, A, U)
    p = np.linalg.solve(AtWA, rhs.T).T
    resid = U - np.einsum("nip,kp->kni", A, p)
    J = AtWA[3:, 3:]  # Σ w [r]ₓᵀ[r]ₓ = Σ w (|r|² I - r rᵀ)
    norm2 = np.einsum("n,kni->k", w, U * U)
    return p, m, J, norm2, np.einsum("n,kni->k", w, resid * resid)


def energy_split(p: np.ndarray, m: float, J: np.ndarray) -> np.ndarray:
    """(torsion, bending, axial) kinetic energies (× 2/ω²) of rigid motions p (k, 6), shape (k, 3)."""
    t, th = p[:, :3], p[:, 3:]
    return np.stack([J[0, 0] * th[:, 0] ** 2,
                     m * (t[:, 1] ** 2 + t[:, 2] ** 2) + J[1, 1] * th[:, 1] ** 2 + J[2, 2] * th[:, 2] ** 2,
                     m * t[:, 0] ** 2], axis=1)


def classify(energies: np.ndarray, rigid_fit: np.ndarray):
    """Fractions (k, 3) summing to 1 and labels from summed slab energies (k, 3) and fit shares (k,)."""
    total = energies.sum(axis=1, keepdims=True)
    fractions = energies / np.where(total > 0, total, 1.0)
    best = fractions.argmax(axis=1)
    labels = [KINDS[b] if (f[b] > DOMINANT and q >= MIN_RIGID_FIT) else "other"
              for b, f, q in zip(best, fractions, rigid_fit)]
    return fractions, labels


def identify(U: np.ndarray, xyz: np.ndarray, w: np.ndarray, slabs: list[np.ndarray],
             bodies: list[tuple[np.ndarray, float, np.ndarray]] = ()):
    """Torsion / bending / axial fractions and labels of k modes.

    Parameters
    ----------
    U : ndarray, shape (k, N, 3)
        Nodal displacements of k modes.
    xyz : ndarray, shape (N, 3)
        Node positions, m.
    w : ndarray, shape (N,)
        Node masses, kg.
    slabs : list of int arrays
        Node indices of each slab (journals, or axial slices).
    bodies : list of (p, m, J)
        Rigid bodies on the axis taken as extra slabs: their motion p (k, 6) at the centre of
        mass, mass (kg) and inertia tensor (kg·m²); they fit exactly.

    Returns
    -------
    fractions : ndarray, shape (k, 3)
        Torsional, bending, axial shares, each row summing to 1.
    labels : list of str
        ``torsional``, ``bending``, ``axial`` or ``other``.
    rigid_fit : ndarray, shape (k,)
        Share of the slabs' motion (mass-weighted, squared) captured by the rigid fits.
    """
    k = U.shape[0]
    energies = np.zeros((k, 3))
    norm2, resid2 = np.zeros(k), np.zeros(k)
    for idx in slabs:
        p, m, J, n2, r2 = slab_fit(U[:, idx], xyz[idx], w[idx])
        energies += energy_split(p, m, J)
        norm2 += n2
        resid2 += r2
    for p, m, J in bodies:
        energies += energy_split(p, m, J)
    rigid_fit = 1.0 - resid2 / np.where(norm2 > 0, norm2, 1.0)
    fractions, labels = classify(energies, rigid_fit)
    return fractions, labels, rigid_fit
