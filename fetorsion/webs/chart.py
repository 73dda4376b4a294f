"""A computed BICERA web chart: L_e0/D_t of a plain crank web against c and R·D_e³/(L_b·B_e³).

The BICERA chart of [Seyedalian] eq. (8) is not available to us, so this module computes its
counterpart with the static throw FE of :mod:`fetorsion.webs.throwfe` over a parametric web
family, ships the table (``fetorsion/data/web_chart.json``, written by
``scripts/web_chart.py``) and interpolates it: web method ``chart``.

The family (every length a multiple of the main-journal diameter D_t = D_e):

* pin diameter D_m = 0.85 D_t, journal length L_t = 0.40 D_t (a throw holds two halves),
  pin length L_m = 0.38 D_t; solid journal and pin;
* web outline: the hull of a circle B_max about the axis and B_min = 0.78 B_max about
  the pin, no counterweight; effective width B_e from eq. (7);
* chart coordinates (eq. 8): overlap c = (R_m + R_t − R)/R, which fixes the crank radius
  R = (D_m + D_t)/(2 (1 + c)), and q = R D_e³/(L_b B_e³). A point (c, q) leaves one free
  choice, how q splits between web thickness and width: from the reference web
  L_b0 = 0.38 D_t, B_e0 = 1.22 D_t (an automotive inline-4), the thickness takes the share
  ``split`` of the change of log q and B_e³ the rest (``split`` = ½ in the table);
* steel, ν = 0.3 (L_e/D_t depends on ν only, through G/E in the web bending).

L_e0 is the web term of :func:`fetorsion.webs.throwfe.web_term` of a throw without fillets or
drillings; the fillet and oil-hole effects (the corrections of eq. 9–13) are tabulated as
ΔL/D_t against r/D_t and φ/D_t at the chart's centre.
"""

from __future__ import annotations

import json
import math
import warnings
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..description.model import Crank, Cylinder, Engine, Fillets, Material, OilHoles, Web
from ..errors import FetorsionError
from ..extrapolation import richardson

CHART_FILE = Path(__file__).with_name("data") / "web_chart.json"

PIN_DIAMETER = 0.85       # D_m / D_t
JOURNAL_LENGTH = 0.40     # L_t / D_t
PIN_LENGTH = 0.38         # L_m / D_t
WIDTH_RATIO = 0.78        # B_min / B_max
REF_THICKNESS = 0.38      # L_b0 / D_t
REF_WIDTH = 1.22          # B_e0 / D_t
WEB_SPLIT = 0.5           # share of a stiffness change the chart's family takes in thickness (the rest in width)
STEEL = Material(210e9, 0.3, 7850.0, "steel")


def effective_width_factor(ratio: float = WIDTH_RATIO) -> float:
    """B_e / B_max of eq. (7) for B_min = ratio · B_max: (½ (1 + ratio⁻³))^(−1/3)."""
    return (0.5 * (1.0 + ratio**-3)) ** (-1.0 / 3.0)


def crank_radius(c: float, d_t: float = 1.0) -> float:
    """R (units of d_t) for overlap c: R = (D_m + D_t) / (2 (1 + c))."""
    return 0.5 * (PIN_DIAMETER + 1.0) * d_t / (1.0 + c)


def web_dimensions(c: float, q: float, split: float = WEB_SPLIT, d_t: float = 1.0) -> tuple[float, float]:
    """(L_b, B_e) of the family's web at chart point (c, q), units of d_t.

    From the reference web (L_b0, B_e0), q0 = R D_t³/(L_b0 B_e0³); then
    L_b = L_b0 (q0/q)^split and B_e = B_e0 (q0/q)^((1 − split)/3), so that R D_t³/(L_b B_e³) = q.
    """
    R = crank_radius(c, 1.0)
    q0 = R / (REF_THICKNESS * REF_WIDTH**3)
    f = q0 / q
    return REF_THICKNESS * f**split * d_t, REF_WIDTH * f ** ((1.0 - split) / 3.0) * d_t


def chart_throw(c: float, q: float, d_t: float = 0.06, split: float = WEB_SPLIT, fillet: float = 0.0,
                oil_hole: float = 0.0, material: Material = STEEL) -> Crank:
    """The family's throw at chart point (c, q) as a 1-cylinder description (SI units).

    Parameters
    ----------
    c : float
        Overlap ratio (R_m + R_t − R)/R, -.
    q : float
        R·D_e³/(L_b·B_e³), -.
    d_t : float
        Main-journal diameter D_t = D_e, m (the chart is scale-free; only the mesh sees it).
    split : float
        Share of the change of log q taken by the web thickness (see module docs), -.
    fillet : float
        Journal and pin fillet radius, m.
    oil_hole : float
        Diameter of the diametral drillings in both journal halves and the pin, m (0: none).
    material : Material
    """
    L_b, B_e = web_dimensions(c, q, split, d_t)
    b_max = B_e / effective_width_factor()
    web = Web(thickness=L_b, width_journal=b_max, width_pin=WIDTH_RATIO * b_max)
    R = crank_radius(c, d_t)
    engine = Engine(cylinders=1, strokes_per_cycle=4, stroke=2 * R, rod_length=8 * R,
                    crank_angles=(0.0,), firing_order=(1,))
    journal = Cylinder(d_t, 0.5 * JOURNAL_LENGTH * d_t)
    return Crank(name=f"chart c={c:g} q={q:g}", material=material, engine=engine, journals=(journal, journal),
                 pins=(Cylinder(PIN_DIAMETER * d_t, PIN_LENGTH * d_t),), webs=(web, web),
                 fillets=Fillets(fillet, fillet),
                 oil_holes=OilHoles(oil_hole, oil_hole > 0, oil_hole > 0))


#: Global element sizes (shares of D_t) of the two meshes every chart point is computed on.
MESH_SHARES = (1.0 / 8.0, 1.0 / 12.0)


def chart_point_fe(c: float, q: float, mesh_share: float, **kwargs) -> dict:
    """FE L_e0/D_t (web term per web over D_t) of the family's throw at (c, q) on one mesh.

    Parameters
    ----------
    c, q : float
        Chart coordinates, -.
    mesh_share : float
        Global element size over D_t, -.
    **kwargs
        To :func:`chart_throw` (``split``, ``fillet``, ``oil_hole``, ``d_t``).

    Returns
    -------
    dict
        ``le_dt`` (-), ``dofs``, ``seconds`` (s).
    """
    from .throwfe import torsional_stiffness_fe, web_term

    throw = chart_throw(c, q, **kwargs)
    d_t = throw.journals[0].diameter
    res = torsional_stiffness_fe(throw, mesh_share * d_t)
    le = web_term(throw, res.equivalent_length(throw.material.shear_modulus, d_t), d_t)
    return {"le_dt": le / d_t, "dofs": res.dofs, "seconds": res.seconds}


def chart_point(c: float, q: float, rate: float, shares=MESH_SHARES, **kwargs) -> dict:
    """L_e0/D_t at (c, q) on the two meshes ``shares`` and extrapolated with order ``rate``.

    The plain web has sharp re-entrant edges where web meets journal and pin; their stress
    singularity slows mesh convergence to about h^1.4, so each point is extrapolated
    rather than read off one mesh.
    """
    a, b = (chart_point_fe(c, q, s, **kwargs) for s in shares)
    return {"c": c, "q": q, **{k: v for k, v in kwargs.items() if k != "d_t"},
            "le_dt": richardson(a["le_dt"], b["le_dt"], *shares, rate),
            "le_dt_meshes": [a["le_dt"], b["le_dt"]], "dofs": [a["dofs"], b["dofs"]],
            "seconds": a["seconds"] + b["seconds"]}


# ---------------------------------------------------------------------------
# The shipped chart and web method ``chart``


@lru_cache(maxsize=1)
def load_chart(path: str | None = None) -> dict:
    """The chart table (see ``scripts/web_chart.py``) as stored in JSON."""
    p = Path(path) if path else CHART_FILE
    if not p.exists():
        raise FetorsionError(f"the web chart table {p} is missing; run scripts/web_chart.py")
    return json.loads(p.read_text())


@lru_cache(maxsize=4)
def _interpolator(path: str | None = None):
    from scipy.interpolate import RegularGridInterpolator

    ch = load_chart(path)
    grid = ch["grid"]
    # log q: the chart's curves are smooth in log q (q spans a factor 4); cubic in both.
    return RegularGridInterpolator((np.array(grid["c"]), np.log(grid["q"])), np.array(grid["le_dt"]),
                                   method=ch["interpolation"], bounds_error=True)


def le0_dt(c: float, q: float, path: str | None = None) -> float:
    """Interpolated chart value L_e0/D_t at (c, q); FetorsionError outside the table."""
    ch = load_chart(path)
    cs, qs = ch["grid"]["c"], ch["grid"]["q"]
    if not (cs[0] <= c <= cs[-1] and qs[0] <= q <= qs[-1]):
        raise FetorsionError(
            f"web chart: c = {c:.3f}, R·D_e³/(L_b·B_e³) = {q:.3f} lies outside the computed chart "
            f"(c in [{cs[0]:g}, {cs[-1]:g}], q in [{qs[0]:g}, {qs[-1]:g}]); use method 'fe'")
    return float(_interpolator(path)((c, math.log(q))))


def correction_dt(name: str, x: float, path: str | None = None) -> float:
    """ΔL/D_t of the ``fillet`` (x = r/D_t) or ``oil_hole`` (x = φ/D_t) correction, linear in x."""
    cor = load_chart(path)["corrections"][name]
    xs, ys = cor["x"], cor["dle_dt"]
    if not xs[0] <= x <= xs[-1]:
        raise FetorsionError(f"web chart: {name} ratio {x:.3f} lies outside the computed correction "
                             f"[{xs[0]:g}, {xs[-1]:g}]; use method 'fe'")
    return float(np.interp(x, xs, ys))


def chart_coordinates(crank: Crank, web_index: int) -> tuple[float, float]:
    """(c, q) of web ``web_index`` of ``crank`` with D_e = its journal's diameter."""
    from .sections import effective_web_width, overlap_ratio

    web = crank.webs[web_index]
    d_t = crank.journals[crank.journal_of_web(web_index)].diameter
    R = crank.engine.crank_radius
    return overlap_ratio(crank, web_index), R * d_t**3 / (web.thickness * effective_web_width(web) ** 3)


def web_equivalent_length_chart(crank: Crank, web_index: int, d_e: float) -> float:
    """Web method ``chart``: L_eb (m, at D_e) from the computed chart and its corrections.

    L_eb = D_t (L_e0/D_t + ΔL_fillet/D_t + ΔL_hole/D_t) · (D_e/D_t)⁴, with D_t the diameter
    of the web's journal. The fillet correction takes the mean of the journal and pin
    fillet radii; the oil-hole one was computed with journals and pins drilled, and is
    applied when either is. Counterweights are not in the chart (nor in BICERA's).
    """
    journal = crank.journals[crank.journal_of_web(web_index)]
    pin = crank.pins[crank.throw_of_web(web_index)]
    d_t = journal.diameter
    if journal.bore > 0 or pin.bore > 0:
        warnings.warn("web chart: computed for solid journals and pins; the bores enter only "
                      "through eq. (4)-(5)", stacklevel=2)
    c, q = chart_coordinates(crank, web_index)
    value = le0_dt(c, q)
    r = 0.5 * (crank.fillets.journal + crank.fillets.pin)
    if r > 0:
        value += correction_dt("fillet", r / d_t)
    oil = crank.oil_holes
    if oil.diameter > 0 and (oil.in_journals or oil.in_pins):
        value += correction_dt("oil_hole", oil.diameter / d_t)
    return d_t * value * (d_e / d_t) ** 4
