"""Plausible crank descriptions drawn at random, seeded: a test tool.

A new user's crank is not one of the shipped ones. :func:`plausible_crank` draws one the way a
designer would size it, from the bore and stroke, by the layout rules the reference geometries
cite (``geometry/renault21.toml``'s [N] notes): the cylinder pitch p = bore + 5..11 mm plus a
share of the bore, journal and pin diameters and lengths as shares of the bore, webs filling
the pitch, fillets r = (0.035-0.08) d, drillings, hollow pins and counterweights on or off.
Every draw lies inside the ranges :func:`~fetorsion.description.plausibility.plausibility_warnings`
accepts (it warns on none), so a failure downstream is fetorsion's, not the crank's.

The draws are returned as the TOML tables a user writes (lengths in mm, ``[units] length =
"mm"``), so they go through the reader and every check like a file. In-line engines of 1-8
cylinders, and vees of 6-12 (two rods side by side on each pin).

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
    3: ([0.0, 240.0, 120.0], [1, 2, 3]),
    4: ([0.0, 180.0, 180.0, 0.0], [1, 3, 4, 2]),
    5: ([0.0, 144.0, 288.0, 72.0, 216.0], [1, 2, 3, 4, 5]),
    6: ([0.0, 120.0, 240.0, 240.0, 120.0, 0.0], [1, 5, 3, 6, 2, 4]),
    8: ([0.0, 180.0, 90.0, 270.0, 270.0, 90.0, 180.0, 0.0], [1, 6, 2, 5, 8, 3, 7, 4]),
}

#: Vee layouts drawn: cylinders -> (the throws' TDC lags, deg; the bank angle, deg; a firing order,
#: numbered by bank): a 60° V6 and a 60° V12 on an in-line three's and six's throws, a 72° V10 on a
#: five's (the first bank fires as that in-line engine, each second-bank cylinder a bank angle after
#: the first bank's on its throw), a 90° cross-plane V8 firing 1-5-4-2-6-3-7-8 (tests/test_vee.py).
VEE_LAYOUTS = {6: (LAYOUTS[3][0], 60.0, [1, 4, 2, 5, 3, 6]), 8: ([0.0, 270.0, 90.0, 180.0], 90.0, [1, 5, 4, 2, 6, 3, 7, 8]),
               10: (LAYOUTS[5][0], 72.0, [1, 6, 2, 7, 3, 8, 4, 9, 5, 10]),
               12: (LAYOUTS[6][0], 60.0, [1, 7, 5, 11, 3, 9, 6, 12, 2, 8, 4, 10])}

#: Shares of each feature's presence among the draws.
FILLET_SHARE = 0.8
DRILLING_SHARE = 0.6
HOLLOW_PIN_SHARE = 0.2
COUNTERWEIGHT_SHARE = 0.5


def plausible_crank(rng: np.random.Generator, cylinders: int | None = None, layout: str = "in-line") -> dict:
    """One crank description (TOML tables, mm) drawn from ``rng``.

    Parameters
    ----------
    rng : numpy.random.Generator
        The source of every draw: the same seed gives the same crank.
    cylinders : int, optional
        A key of :data:`LAYOUTS` (in-line) or :data:`VEE_LAYOUTS`; drawn among them when omitted.
    layout : str
        ``"in-line"`` or ``"vee"`` (two rods side by side on each pin, numbered by bank).
    """
    table = VEE_LAYOUTS if layout == "vee" else LAYOUTS
    n = int(rng.choice(sorted(table))) if cylinders is None else cylinders
    if layout == "vee":
        angles, bank, firing = table[n]
    else:
        angles, firing = table[n]
    throws = len(angles)
    u = rng.uniform
    stroke = u(50.0, 160.0)                  # motorcycle to heavy truck
    bore = stroke * u(0.8, 1.3)
    rod = 0.5 * stroke / u(0.24, 0.33)       # lambda = R / l
    d_j = bore * u(0.55, 0.8)
    d_p = d_j * u(0.75, 0.95)
    l_j = d_j * u(0.3, 0.55)
    l_p = d_p * u(0.35, 0.6) if layout != "vee" else 2 * d_p * u(0.35, 0.45) + u(1.0, 3.0)  # two big ends
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
    engine = {"cylinders": n, "cycle_strokes": 4, "bore": bore, "stroke": stroke, "rod_length": rod,
              "crank_angles_deg": list(angles), "firing_order": list(firing)}
    if layout == "vee":
        engine.update(layout="vee", bank_angle_deg=bank, numbering="by-bank", rods="side-by-side",
                      rod_spacing=0.5 * l_p)
    raw = {
        "meta": {"name": f"plausible {layout} {n}"},
        "units": {"length": "mm"},
        "material": {"youngs_modulus_pa": 210e9, "poisson_ratio": 0.3, "density_kgm3": 7850.0},
        "engine": engine,
        "journals": [{"diameter": d_j, "length": l_j} for _ in range(throws + 1)],
        "pins": [dict(pin) for _ in range(throws)],
        "webs": [dict(webs) for _ in range(2 * throws)],
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
            return {k: (x if k in ("youngs_modulus_pa", "poisson_ratio", "density_kgm3", "crank_angles_deg",
                                   "bank_angle_deg")
                        else r(x)) for k, x in v.items()}
        if isinstance(v, list):
            return [r(x) for x in v]
        return v

    return {k: r(v) for k, v in raw.items()}


def plausible_cranks(seed: int, count: int, layout: str = "in-line") -> list[dict]:
    """``count`` cranks from one seed, the cylinder counts taken in turn over :data:`LAYOUTS` (or
    :data:`VEE_LAYOUTS`) so that a small sample still holds short and long cranks."""
    rng = np.random.default_rng(seed)
    counts = sorted(VEE_LAYOUTS if layout == "vee" else LAYOUTS)
    return [plausible_crank(rng, counts[(i + seed) % len(counts)], layout) for i in range(count)]

