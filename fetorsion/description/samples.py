"""Plausible crank descriptions drawn at random, seeded: a test tool.

A new user's crank is not one of the shipped ones. :func:`plausible_crank` draws one the way a
designer would size it, from the bore and stroke, by the layout rules the reference geometries
cite (``geometry/renault21.toml``'s [N] notes): the cylinder pitch p = bore + 5..11 mm plus a
share of the bore, journal and pin diameters and lengths as shares of the bore, webs filling
the pitch, fillets r = (0.035-0.08) d, drillings, hollow pins and counterweights on or off.
Every draw lies inside the ranges :func:`~fetorsion.description.plausibility.plausibility_warnings`
accepts (it warns on none), so a failure downstream is fetorsion's, not the crank's.

The draws are returned as the TOML tables a user writes (lengths in mm, ``[units] length =
"mm"``), so they go through the reader and every check like a file. In-line engines only
while the description knows no other layout.

Example
-------
>>> import numpy as np
>>> from fetorsion.description.crank import parse_crank
>>> raw = plausible_crank(np.random.default_rng(1))
>>> parse_crank(raw).engine.cylinders in LAYOUTS
True
"""

from __future__ import annotations

import math

import numpy as np

#: In-line layouts drawn: cylinders -> (crank angles in degrees, a 4-stroke firing order they fire).
LAYOUTS = {
    1: ([0.0], [1]),
    2: ([0.0, 180.0], [1, 2]),
    3: ([0.0, 240.0, 120.0], [1, 3, 2]),
    4: ([0.0, 180.0, 180.0, 0.0], [1, 3, 4, 2]),
    5: ([0.0, 144.0, 288.0, 72.0, 216.0], [1, 2, 3, 4, 5]),
    6: ([0.0, 120.0, 240.0, 240.0, 120.0, 0.0], [1, 5, 3, 6, 2, 4]),
    8: ([0.0, 180.0, 90.0, 270.0, 270.0, 90.0, 180.0, 0.0], [1, 6, 2, 5, 8, 3, 7, 4]),
}

#: Shares of each feature's presence among the draws.
FILLET_SHARE = 0.8
DRILLING_SHARE = 0.6
HOLLOW_PIN_SHARE = 0.2
COUNTERWEIGHT_SHARE = 0.5


def plausible_crank(rng: np.random.Generator, cylinders: int | None = None) -> dict:
    """One crank description (TOML tables, mm) drawn from ``rng``.

    Parameters
    ----------
    rng : numpy.random.Generator
        The source of every draw: the same seed gives the same crank.
    cylinders : int, optional
        A key of :data:`LAYOUTS`; drawn among them when omitted.
    """
    n = int(rng.choice(sorted(LAYOUTS))) if cylinders is None else cylinders
    angles, firing = LAYOUTS[n]
    u = rng.uniform
    stroke = u(50.0, 160.0)                  # motorcycle to heavy truck
    bore = stroke * u(0.8, 1.3)
    rod = 0.5 * stroke / u(0.24, 0.33)       # lambda = R / l
    d_j = bore * u(0.55, 0.8)
    d_p = d_j * u(0.75, 0.95)
    l_j = d_j * u(0.3, 0.55)
    l_p = d_p * u(0.35, 0.6)
    pitch = bore + u(5.0, 11.0) + bore * u(0.0, 0.2)
    web = max(0.5 * (pitch - l_j - l_p), 0.15 * stroke)
    width_pin = d_p + 2.0 * stroke * u(0.06, 0.15)
    width_journal = min(d_j + 2.0 * stroke * u(0.08, 0.2), width_pin + 1.8 * 0.5 * stroke)
    width_journal = max(width_journal, d_j)
    webs = {"thickness": web, "width_journal": width_journal, "width_pin": width_pin}
    if rng.random() < COUNTERWEIGHT_SHARE:
        webs.update(counterweight_radius=0.5 * width_journal + 0.5 * stroke * u(0.1, 0.5),
                    counterweight_angle_deg=u(90.0, 160.0))
    pin = {"diameter": d_p, "length": l_p}
    if rng.random() < HOLLOW_PIN_SHARE:
        pin["bore"] = d_p * u(0.3, 0.5)
    raw = {
        "meta": {"name": f"plausible in-line {n}"},
        "units": {"length": "mm"},
        "material": {"youngs_modulus_pa": 210e9, "poisson_ratio": 0.3, "density_kgm3": 7850.0},
        "engine": {"cylinders": n, "cycle_strokes": 4, "bore": bore, "stroke": stroke, "rod_length": rod,
                   "crank_angles_deg": list(angles), "firing_order": list(firing)},
        "journals": [{"diameter": d_j, "length": l_j} for _ in range(n + 1)],
        "pins": [dict(pin) for _ in range(n)],
        "webs": [dict(webs) for _ in range(2 * n)],
        "front": [{"diameter": 0.6 * d_j, "length": 0.8 * d_j}],
        "rear": [{"diameter": 1.4 * d_j, "length": 0.25 * d_j}],
    }
    if rng.random() < FILLET_SHARE:
        raw["fillets"] = {"journal": min(d_j * u(0.035, 0.08), 0.45 * web),
                          "pin": min(d_p * u(0.035, 0.08), 0.45 * web)}
    if rng.random() < DRILLING_SHARE:
        where = rng.integers(1, 4)  # 1: journals, 2: pins, 3: both
        raw["oil_holes"] = {"diameter": d_p * u(0.08, 0.15), "in_journals": bool(where & 1), "in_pins": bool(where & 2)}
    return _rounded(raw)


def _rounded(raw: dict) -> dict:
    """Lengths to 0.1 mm, as a drawing gives them."""

    def r(v):
        if isinstance(v, float) and not math.isclose(v, 210e9) and v < 1e4:
            return round(v, 1)
        if isinstance(v, dict):
            return {k: (x if k in ("youngs_modulus_pa", "poisson_ratio", "density_kgm3", "crank_angles_deg")
                        else r(x)) for k, x in v.items()}
        if isinstance(v, list):
            return [r(x) for x in v]
        return v

    return {k: r(v) for k, v in raw.items()}


def plausible_cranks(seed: int, count: int) -> list[dict]:
    """``count`` cranks from one seed, the cylinder counts taken in turn over :data:`LAYOUTS` so
    that a small sample still holds short and long cranks."""
    rng = np.random.default_rng(seed)
    counts = sorted(LAYOUTS)
    return [plausible_crank(rng, counts[(i + seed) % len(counts)]) for i in range(count)]

