"""IACS UR M53 §3: the rule's empirical stress concentration factors, where their formulas hold,
and fetorsion's FE factors in the rule's convention (its Appendix III) beside them.

Every function takes one throw's dimensions ``g``, a :class:`fetorsion.design.m53.M53Geometry`:
named here in words, not imported, because :mod:`fetorsion.design.m53` (the rule as a whole)
imports its factors from this module. The rule's text is [KR-M53]'s, as there.
"""

from __future__ import annotations

import math

from .scfset import SCFSet

#: [KR-M53] §3.(1)(G): the ranges of the related dimensions inside which the SCF formulas hold
#: (s has no lower bound: §3.(1)(H) extends it with s = −0.5 in f(s, w) and f(r, s) below −0.5).
VALIDITY = {"r": (0.03, 0.13), "s": (-math.inf, 0.5), "w": (0.2, 0.8), "b": (1.1, 2.2), "d_O": (0.0, 0.2),
            "d_G": (0.0, 0.8), "d_H": (0.0, 0.8)}
#: The related dimensions each factor's formula reads (r of α: R_H/D; of β_B, β_Q: R_G/D; of β_T: R_G/D_G).
FACTOR_RATIOS = {"alpha_B": ("r_H", "s", "w", "b", "d_G", "d_H"), "alpha_T": ("r_H", "s", "w", "b"),
                 "beta_B": ("r_G", "s", "w", "b", "d_G", "d_H"), "beta_Q": ("r_G", "s", "w", "b", "d_H"),
                 "beta_T": ("r_GG", "s", "w", "b"), "gamma_B": ("d_O",), "gamma_T": ("d_O",)}
FACTORS = tuple(FACTOR_RATIOS)


def out_of_range(g) -> dict:
    """{factor: ["name = value outside [lo, hi]", ...]} for every SCF formula whose related
    dimensions leave :data:`VALIDITY` (an empty dict: every formula holds)."""
    q = g.ratios()
    limits = {"r_H": VALIDITY["r"], "r_G": VALIDITY["r"], "r_GG": VALIDITY["r"], **VALIDITY}
    out = {}
    for factor, names in FACTOR_RATIOS.items():
        if factor.startswith("gamma") and not g.D_O > 0:
            continue
        bad = [f"{n} = {q[n]:.4g} outside [{limits[n][0]:g}, {limits[n][1]:g}]" for n in names
               if not limits[n][0] <= q[n] <= limits[n][1]]
        if bad:
            out[factor] = bad
    return out


def _recess(q: dict) -> float:
    """f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s), not below 1 ([KR-M53] §3.(1)(H))."""
    return max(1.0, 1.0 + (q["t_H"] + q["t_G"]) * (1.8 + 3.2 * q["s"]))


def _s_low(s: float) -> float:
    """s for f(s, w) and f(r, s): −0.5 where s < −0.5 ([KR-M53] §3.(1)(H))."""
    return max(s, -0.5)


def alpha_B(g) -> float:
    """Bending SCF of the pin fillet, [KR-M53] §3.(2)(A)."""
    q = g.ratios()
    s, w, b, r, dg, dh = _s_low(q["s"]), q["w"], q["b"], q["r_H"], q["d_G"], q["d_H"]
    f_sw = (-4.1883 + 29.2004 * w - 77.5925 * w**2 + 91.9454 * w**3 - 40.0416 * w**4
            + (1 - s) * (9.5440 - 58.3480 * w + 159.3415 * w**2 - 192.5846 * w**3 + 85.2916 * w**4)
            + (1 - s) ** 2 * (-3.8399 + 25.0444 * w - 70.5571 * w**2 + 87.0328 * w**3 - 39.1832 * w**4))
    f_w = 2.1790 * w**0.7171
    f_b = 0.6840 - 0.0077 * b + 0.1473 * b**2
    f_r = 0.2081 * r**-0.5231
    f_dg = 0.9993 + 0.27 * dg - 1.0211 * dg**2 + 0.5306 * dg**3
    f_dh = 0.9978 + 0.3145 * dh - 1.5241 * dh**2 + 2.4147 * dh**3
    return 2.6914 * f_sw * f_w * f_b * f_r * f_dg * f_dh * _recess(q)


def _alpha_T_form(r: float, s: float, b: float, w: float) -> float:
    """0.8 f(r, s) f(b) f(w) of [KR-M53] §3.(2)(B), as that text prints f(r, s) = r^(−0.322 +
    0.1015 (1 − s)) and the cubic term of f(b) as −0.85 b³."""
    s = _s_low(s)
    return 0.8 * r ** (-0.322 + 0.1015 * (1 - s)) * (7.8955 - 10.654 * b + 5.3482 * b**2 - 0.85 * b**3) * w**-0.145


def alpha_T(g) -> float:
    """Torsion SCF of the pin fillet, [KR-M53] §3.(2)(B)."""
    q = g.ratios()
    return _alpha_T_form(q["r_H"], q["s"], q["b"], q["w"])


def beta_B(g) -> float:
    """Bending SCF of the journal fillet, [KR-M53] §3.(3)(A) (r = R_G/D)."""
    q = g.ratios()
    s, w, b, r, dg, dh = _s_low(q["s"]), q["w"], q["b"], q["r_G"], q["d_G"], q["d_H"]
    f_sw = (-1.7625 + 2.9821 * w - 1.527 * w**2 + (1 - s) * (5.1169 - 5.8089 * w + 3.1391 * w**2)
            + (1 - s) ** 2 * (-2.1567 + 2.3297 * w - 1.2952 * w**2))
    f_w = 2.2422 * w**0.7548
    f_b = 0.5616 + 0.1197 * b + 0.1176 * b**2
    f_r = 0.1908 * r**-0.5568
    f_dg = 1.0012 - 0.6441 * dg + 1.2265 * dg**2
    f_dh = 1.0022 - 0.1903 * dh + 0.0073 * dh**2
    return 2.7146 * f_sw * f_w * f_b * f_r * f_dg * f_dh * _recess(q)


def beta_Q(g) -> float:
    """Compression (radial force) SCF of the journal fillet, [KR-M53] §3.(3)(B) (r = R_G/D)."""
    q = g.ratios()
    s, w, b, r, dh = q["s"], q["w"], q["b"], q["r_G"], q["d_H"]
    f_s = 0.4368 + 2.1630 * (1 - s) - 1.5212 * (1 - s) ** 2
    f_w = w / (0.0637 + 0.9369 * w)
    f_b = -0.5 + b
    f_r = 0.5331 * r**-0.2038
    f_dh = 0.9937 - 1.1949 * dh + 1.7373 * dh**2
    return 3.0128 * f_s * f_w * f_b * f_r * f_dh * _recess(q)


def beta_T(g) -> float:
    """Torsion SCF of the journal fillet, [KR-M53] §3.(3)(C): α_T when pin and journal have the
    same diameter and fillet radius, else α_T's formula with r = R_G/D_G."""
    q = g.ratios()
    if math.isclose(g.D, g.D_G) and math.isclose(g.R_H, g.R_G):
        return alpha_T(g)
    return _alpha_T_form(q["r_GG"], q["s"], q["b"], q["w"])


def gamma_B(g) -> float:
    """Bending SCF of the pin oil-bore outlet, [KR-M53] §3.(3)(D): 3 − 5.88 d_O + 34.6 d_O²."""
    d = g.D_O / g.D
    return 3.0 - 5.88 * d + 34.6 * d * d


def gamma_T(g) -> float:
    """Torsion SCF of the pin oil-bore outlet, [KR-M53] §3.(3)(D): 4 − 6 d_O + 30 d_O²."""
    d = g.D_O / g.D
    return 4.0 - 6.0 * d + 30.0 * d * d


FORMULAS = {"alpha_B": alpha_B, "alpha_T": alpha_T, "beta_B": beta_B, "beta_Q": beta_Q, "beta_T": beta_T,
            "gamma_B": gamma_B, "gamma_T": gamma_T}


def empirical_scfs(g) -> dict:
    """Every SCF of [KR-M53] §3 for ``g`` (γ only with an oil bore), whether or not its formula
    holds there (:func:`out_of_range` says which do not)."""
    return {k: f(g) for k, f in FORMULAS.items() if not (k.startswith("gamma") and not g.D_O > 0)}


def web_section_per_pin_section(g, journal: bool = False) -> float:
    """σ_N(web) / σ_nom(pin or journal section) for one bending moment: (32 D/(π (D⁴ − D_B⁴))) ·
    (B W²/6), the factor that takes a bending SCF against the pin's (or journal's) own section to
    M53's web-section convention."""
    d, bore = (g.D_G, g.D_BG) if journal else (g.D, g.D_BH)
    return 32.0 * d / (math.pi * (d**4 - bore**4)) * g.B * g.W**2 / 6.0


def fe_scfs_m53(g, scf: SCFSet) -> dict:
    """fetorsion's FE SCFs in M53's convention (its Appendix III): α_B, β_B the peak von Mises
    stress in the fillet under a pure couple over the web-section stress M/(B W²/6); α_T, β_T the
    peak largest shear over τ_N of the section; γ_B, γ_T the oil bore's peak principal stress over
    the pin section's nominal stresses (Appendix II's definition, as computed). ``scf``: the run's
    SCFs (:func:`fetorsion.design.scf.fillet_scfs`, each against its own section, and the oil
    bores'). β_Q has no FE counterpart here (its 3-point-bending case is not computed)."""
    out = {"alpha_T": scf.torsion["pin"], "beta_T": scf.torsion["journal"]}
    if "pin" in scf.bending_vm:
        out["alpha_B"] = scf.bending_vm["pin"] * web_section_per_pin_section(g)
    if "journal" in scf.bending_vm:
        out["beta_B"] = scf.bending_vm["journal"] * web_section_per_pin_section(g, journal=True)
    if "pin" in scf.oil_bore:
        out["gamma_B"], out["gamma_T"] = scf.oil_bore["pin"]
    return out


def scf_comparison(g, scf: SCFSet) -> dict:
    """{factor: {"fe", "empirical", "difference" (fe/empirical − 1), "in_range", "outside"}}: the
    FE in M53's convention beside the rule's formula ("scf_m53" of results.json)."""
    emp, fe, bad = empirical_scfs(g), fe_scfs_m53(g, scf), out_of_range(g)
    out = {}
    for k in FACTORS:
        if k not in emp and k not in fe:
            continue
        e, f = emp.get(k), fe.get(k)
        out[k] = {"fe": f, "empirical": e, "difference": (f / e - 1.0) if (e and f) else None,
                  "in_range": k not in bad, "outside": bad.get(k, [])}
    return out

