"""Reports of the crank-train mechanics: the numbers each command prints and plots, computed
from the input file (:mod:`.input`) by the mechanics modules. No command-line code here."""

from __future__ import annotations

import numpy as np

from . import balance as bal
from . import planetary as pl


def planetary_results(spec) -> list:
    """The planetary mechanisms of a file, plus a conventional crank of the same stroke for each."""
    p = spec.planetary
    out = []
    for d in p.planet_diameters:
        res = pl.planetary(p.kind, p.fixed_diameter, d, p.rod_length, p.eccentricity, np.radians(p.pin_phase_deg),
                           name=spec.name)
        conv = pl.planetary("conventional", res.stroke_m, 0.0, p.rod_length, name="conventional, same stroke")
        out.append((res, conv))
    return out


def planetary_table(name: str, pairs) -> str:
    """One line per mechanism and its conventional crank of the same stroke; arms in mm."""
    head = (f"{'mechanism':>38} {'turns':>5} {'strokes/turn':>12} {'stroke [mm]':>11} {'DC geo arm':>11} "
            f"{'DC eff arm':>11} {'max eff arm':>11}")
    lines = [f"{name}: big end on the satellite pitch circle; arms in mm (geometric: O to rod line; "
             "effective: −dx_p/dφ, torque per unit piston force; DC: largest at a dead centre)", head, "-" * len(head)]
    for res, conv in pairs:
        for r in (res, conv):
            dc = r.at_dead_centres()
            lines.append(f"{r.label():>38} {r.turns:5d} {r.strokes_per_turn:12.2f} {1e3 * r.stroke_m:11.3f} "
                         f"{1e3 * dc['max_geometric_arm_m']:11.3f} {1e3 * dc['max_effective_arm_m']:11.3f} "
                         f"{1e3 * np.abs(r.effective_arm_m).max():11.3f}")
    return "\n".join(lines)


def plot_planetary(pairs):
    """Trajectories (top row) and piston position over carrier angle (bottom row)."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, len(pairs), figsize=(4.2 * len(pairs), 8), squeeze=False)
    for j, (res, conv) in enumerate(pairs):
        res.plot(axes[0, j])
        axes[0, j].set_title(res.label(), fontsize=9, wrap=True)
        ax = axes[1, j]
        deg = np.degrees(res.phi_rad)
        ax.plot(deg, 1e3 * res.piston_m, label="planetary")
        ax.plot(np.degrees(conv.phi_rad), 1e3 * conv.piston_m, "--", label="conventional, same stroke")
        ax.plot(deg[res.tdc_index], 1e3 * res.piston_m[res.tdc_index], "^k", ms=4)
        ax.set_xlabel("carrier (crank) angle [deg]")
        ax.set_ylabel("piston pin from crank axis [mm]")
        ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def balance_report(spec, minmax=True) -> dict:
    """All balancing numbers of a mechanics file (SI), as a JSON-ready dict."""
    spec.need("slider_crank", "masses", "balance")
    sc, m, b = spec.slider_crank, spec.masses, spec.balance
    masses = bal.CrankMasses.from_parts(m.rod_kg, m.rod_centroid_to_big_end, m.rod_centroid_to_small_end,
                                        m.piston_kg, m.crank_kg, m.crank_centroid_radius, sc.crank_radius)
    omega = sc.speed_rpm * np.pi / 30
    lam = sc.crank_radius / sc.rod_length
    unb = bal.unbalanced_mass(masses.reciprocating_kg, masses.rotating_kg, b.share_c)
    j = masses.reciprocating_kg * sc.crank_radius * omega**2
    out = {"name": spec.name, "lambda": lam, "speed_rpm": sc.speed_rpm, "masses_kg": masses.__dict__,
           "unbalanced_mass_kg": unb, "share_c": b.share_c,
           "counterweight_kg": bal.counterweight_mass(unb, sc.crank_radius, b.counterweight_radius),
           "counterweight_radius_m": b.counterweight_radius,
           "primary_force_amplitude_n": j, "secondary_force_amplitude_n": j * lam,
           "rotating_force_n": masses.rotating_kg * sc.crank_radius * omega**2}
    if b.shaft_radius is not None:
        out["balance_shaft_kg"] = bal.primary_shaft_mass(masses.reciprocating_kg, sc.crank_radius, b.share_c, b.shaft_radius)
        out["balance_shaft_radius_m"] = b.shaft_radius
        out["secondary_shafts_mass_radius_kgm_each"] = lam / 8 * masses.reciprocating_kg * sc.crank_radius
    if minmax:
        out["overbalance_minmax"] = bal.minmax_overbalance(lam).to_dict()
    if b.overbalance_k is not None:
        loc = bal.residual_locus(b.overbalance_k, np.radians(b.overbalance_alpha_deg), lam, j_newton=j)
        out["overbalance_given"] = {k: v for k, v in loc.to_dict().items() if not isinstance(v, list)}
    return out


def balance_table(rep: dict) -> str:
    m = rep["masses_kg"]
    rows = [("rod big end M'_c [kg]", m["rod_big_end_kg"]), ("rod small end M'_p [kg]", m["rod_small_end_kg"]),
            ("crank at pin M''_c [kg]", m["crank_at_pin_kg"]), ("reciprocating m1 [kg]", m["reciprocating_kg"]),
            ("rotating m2 [kg]", m["rotating_kg"]), (f"M = c m1 + m2, c = {rep['share_c']:g} [kg]", rep["unbalanced_mass_kg"]),
            (f"counterweight B at {1e3 * rep['counterweight_radius_m']:g} mm [kg]", rep["counterweight_kg"])]
    if "balance_shaft_kg" in rep:
        rows.append((f"balance shaft (1×, counter-rotating) at {1e3 * rep['balance_shaft_radius_m']:g} mm [kg]",
                     rep["balance_shaft_kg"]))
        rows.append(("secondary shafts (2×, pair) m_c r_c each [kg·m]", rep["secondary_shafts_mass_radius_kgm_each"]))
    rows += [(f"primary force amplitude m1 r ω² at {rep['speed_rpm']:g} rpm [N]", rep["primary_force_amplitude_n"]),
             ("secondary force amplitude λ m1 r ω² [N]", rep["secondary_force_amplitude_n"]),
             ("rotating force m2 r ω² [N]", rep["rotating_force_n"])]
    lines = [f"{rep['name']}: single-cylinder balancing, λ = {rep['lambda']:.4f}"]
    lines += [f"  {label:<58} {value:12.4f}" for label, value in rows]
    if "overbalance_minmax" in rep:
        o = rep["overbalance_minmax"]
        peaks = ", ".join(f"θ {t:.1f}° φ {p:.1f}°" for t, p in zip(o["peaks_theta_deg"], o["peaks_phi_deg"]))
        lines.append(f"  over-balancing min–max ([Wang] eq. 37–39): k = {o['k']:.4f}, α = {o['alpha_deg']:.3f}°, "
                     f"P_max = {o['p_max_over_j']:.4f} J = {o['p_max_over_j'] * rep['primary_force_amplitude_n']:.1f} N "
                     f"(peaks: {peaks})")
    if "overbalance_given" in rep:
        g = rep["overbalance_given"]
        lines.append(f"  given counterweight k = {g['k']:g}, α = {g['alpha_deg']:g}°: P_max = {g['p_max_over_j']:.4f} J = "
                     f"{g['p_max_n']:.1f} N at θ = {g['theta_max_deg']:.1f}°, φ = {g['phi_max_deg']:.2f}°")
    return "\n".join(lines)
