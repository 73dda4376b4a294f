"""The single-cylinder crank train's masses ([Asgari] §2): the two-mass rod, the crank's
unbalance moved to the pin radius, the mass to balance, and the counterweight and balance shaft
that balance it (the derivation: :mod:`.balance`). Masses in kg, lengths in m."""

from __future__ import annotations


def rod_split(m_rod, h_big, h_small):
    """Two-mass equivalent rod: (big-end mass, small-end mass), kg.

    Parameters
    ----------
    m_rod : float
        Rod mass, kg.
    h_big, h_small : float
        Distance of the rod centroid from the big-end and small-end eye centres, m.

    Examples
    --------
    >>> big, small = rod_split(0.625, 33.923e-3, 83.577e-3)    # B112, [Asgari]
    >>> round(big, 3), round(small, 3)
    (0.445, 0.18)
    """
    total = h_big + h_small
    return m_rod * h_small / total, m_rod * h_big / total


def crank_equivalent_mass(m_crank, r_centroid, r):
    """Crank unbalance moved to the pin radius, m_crank r_g / r, kg ([Asgari] eq. 6).

    Parameters
    ----------
    m_crank : float
        Unbalanced crank mass (pin and webs outside the counterweight), kg.
    r_centroid : float
        Radius of its centroid, m.
    r : float
        Crank radius, m.
    """
    return m_crank * r_centroid / r


def unbalanced_mass(m_rec, m_rot, c):
    """Mass to balance at the pin radius, M = c m1 + m2, kg ([Asgari] eq. 9; c in 0.5–0.63)."""
    return c * m_rec + m_rot


def counterweight_mass(m_unbalanced, r, b):
    """Counterweight mass B = M r / b at centroid radius b (m), kg ([Asgari] eq. 12)."""
    return m_unbalanced * r / b


def primary_shaft_mass(m_rec, r, c, r_shaft):
    """Mass of one balance shaft at crank speed, (1 − c) r m1 / r_shaft, kg ([Asgari] eq. 13).

    Parameters
    ----------
    m_rec : float
        Reciprocating mass m1, kg.
    r : float
        Crank radius, m.
    c : float
        Share of m1 already in the crank counterweight.
    r_shaft : float
        Radius of the shaft mass centroid, m.
    """
    return (1.0 - c) * r * m_rec / r_shaft
