"""``fetorsion kinematics | balance | flywheel``: crank-train mechanics from a small TOML file.

The file format is in :mod:`fetorsion.mechanics.input`; each command prints a table, and
writes ``--json PATH|-`` and ``--plot PATH`` (PNG/PDF/SVG by suffix) when asked.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from ..mechanics import balance as bal
from ..mechanics import flywheel as fw
from ..excitation import kinematics as kin
from ..mechanics import planetary as pl
from ..description.crank import parse_crank
from ..description.model import AttachPoint
from ..description.reader import read_toml
from .options import real
from ..errors import FetorsionError
from ..io import save_figure_atomic
from ..mechanics.input import is_crank_description, parse_mechanics


def _out(args):
    return sys.stderr if args.json == "-" else sys.stdout


def _save_plot(fig, path):
    save_figure_atomic(fig, path, close=True, dpi=130)


def _load(path):
    data = read_toml(Path(path))
    if is_crank_description(data):
        crank = parse_crank(data, source=str(path))
        return crank, None
    return None, parse_mechanics(data, source=str(path))


# ---------------------------------------------------------------------------
# kinematics


def cmd_kinematics(args, emit_json) -> int:
    crank, spec = _load(args.file)
    out = _out(args)
    if crank is not None:
        if args.rpm is None:
            raise FetorsionError(f"{args.file} is a crank description: give the speed with --rpm")
        r, l, rpm, name = crank.engine.crank_radius, crank.engine.rod_length, args.rpm, crank.name
    elif spec.slider_crank is not None:
        sc = spec.slider_crank
        r, l, rpm, name = sc.crank_radius, sc.rod_length, args.rpm or sc.speed_rpm, spec.name
    else:
        spec.need("planetary")
        return _planetary(args, spec, emit_json)
    theta = np.radians(np.arange(0.0, 360.0 + 1e-9, args.step))
    res = kin.kinematics(theta, r, l, rpm * np.pi / 30, name=name)
    print(format_kinematics_table(res), file=out)
    emit_json({"file": args.file, "speed_rpm": rpm, **res.to_dict()}, args.json)
    if args.plot:
        fine = kin.kinematics(np.radians(np.linspace(0, 360, 721)), r, l, rpm * np.pi / 30, name=name)
        _save_plot(fine.plot(), args.plot)
    return 0


def format_kinematics_table(res: kin.KinematicsResult) -> str:
    """Exact and series piston motion at each tabulated crank angle."""
    top = res.crank_radius_m + res.rod_length_m
    head = (f"{'θ [deg]':>8} {'X [mm]':>9} {'X ser':>9} {'v [m/s]':>9} {'v ser':>9} {'a [m/s²]':>10} "
            f"{'a ser':>10} {'β [deg]':>8} {'β̇ [rad/s]':>10}")
    lines = [f"{res.name}: slider crank r = {1e3 * res.crank_radius_m:g} mm, l = {1e3 * res.rod_length_m:g} mm, "
             f"λ = {res.crank_ratio:.4f}, {res.omega_rad_s * 30 / np.pi:g} rpm (X from TDC, v and a towards the head)",
             head, "-" * len(head)]
    for i, t in enumerate(res.theta_rad):
        lines.append(f"{np.degrees(t):8.1f} {1e3 * (top - res.position_m[i]):9.3f} {1e3 * (top - res.position_series_m[i]):9.3f} "
                     f"{res.velocity_m_s[i]:9.3f} {res.velocity_series_m_s[i]:9.3f} {res.acceleration_m_s2[i]:10.1f} "
                     f"{res.acceleration_series_m_s2[i]:10.1f} {np.degrees(res.rod_angle_rad[i]):8.3f} "
                     f"{res.rod_angular_velocity_rad_s[i]:10.3f}")
    return "\n".join(lines)


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


def _planetary(args, spec, emit_json) -> int:
    pairs = planetary_results(spec)
    head = (f"{'mechanism':>38} {'turns':>5} {'strokes/turn':>12} {'stroke [mm]':>11} {'DC geo arm':>11} "
            f"{'DC eff arm':>11} {'max eff arm':>11}")
    lines = [f"{spec.name}: big end on the satellite pitch circle; arms in mm (geometric: O to rod line; "
             "effective: −dx_p/dφ, torque per unit piston force; DC: largest at a dead centre)", head, "-" * len(head)]
    for res, conv in pairs:
        for r in (res, conv):
            dc = r.at_dead_centres()
            lines.append(f"{r.label():>38} {r.turns:5d} {r.strokes_per_turn:12.2f} {1e3 * r.stroke_m:11.3f} "
                         f"{1e3 * dc['max_geometric_arm_m']:11.3f} {1e3 * dc['max_effective_arm_m']:11.3f} "
                         f"{1e3 * np.abs(r.effective_arm_m).max():11.3f}")
    print("\n".join(lines), file=_out(args))
    emit_json({"file": args.file, "mechanisms": [{"planetary": r.summary(), "conventional_same_stroke": c.summary()}
                                                  for r, c in pairs]}, args.json)
    if args.plot:
        _save_plot(plot_planetary(pairs), args.plot)
    return 0


def plot_planetary(pairs):
    """Trajectories (top row) and piston position over carrier angle (bottom row)."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, len(pairs), figsize=(4.2 * len(pairs), 8), squeeze=False)
    for j, (res, conv) in enumerate(pairs):
        res.plot_trajectory(axes[0, j])
        axes[0, j].set_title(res.label(), fontsize=9)
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


# ---------------------------------------------------------------------------
# balance


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


def format_balance_table(rep: dict) -> str:
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
        lines.append(f"  over-balancing min–max (seed 001 eq. 37–39): k = {o['k']:.4f}, α = {o['alpha_deg']:.3f}°, "
                     f"P_max = {o['p_max_over_j']:.4f} J = {o['p_max_over_j'] * rep['primary_force_amplitude_n']:.1f} N "
                     f"(peaks: {peaks})")
    if "overbalance_given" in rep:
        g = rep["overbalance_given"]
        lines.append(f"  given counterweight k = {g['k']:g}, α = {g['alpha_deg']:g}°: P_max = {g['p_max_over_j']:.4f} J = "
                     f"{g['p_max_n']:.1f} N at θ = {g['theta_max_deg']:.1f}°, φ = {g['phi_max_deg']:.2f}°")
    return "\n".join(lines)


def cmd_balance(args, emit_json) -> int:
    _, spec = _load(args.file)
    if spec is None:
        raise FetorsionError(f"{args.file} is a crank description; balance needs a mechanics file "
                             "with [slider_crank], [masses] and [balance] (see geometry/b112_single.toml)")
    rep = balance_report(spec)
    print(format_balance_table(rep), file=_out(args))
    emit_json({"file": args.file, **rep}, args.json)
    if args.plot:
        import matplotlib.pyplot as plt

        lam = rep["lambda"]
        fig, ax = plt.subplots(figsize=(6.5, 6.5))
        o = rep["overbalance_minmax"]
        bal.residual_locus(o["k"], np.radians(o["alpha_deg"]), lam).plot(ax, label="min–max")
        bal.residual_locus(0.5, 0.0, lam).plot(ax, label="k = 0.5 (c = ½)")
        if "overbalance_given" in rep:
            g = rep["overbalance_given"]
            bal.residual_locus(g["k"], np.radians(g["alpha_deg"]), lam).plot(ax, label="given")
        ax.set_title(f"{rep['name']}: residual force, λ = {lam:.3f}", fontsize=9)
        _save_plot(fig, args.plot)
    return 0


# ---------------------------------------------------------------------------
# flywheel


def cmd_flywheel(args, emit_json) -> int:
    crank, spec = _load(args.file)
    if crank is not None:
        return _flywheel_from_engine_torque(crank, args, emit_json)
    spec.need("flywheel")
    f = spec.flywheel
    stroke = f.stroke if f.stroke is not None else (2 * spec.slider_crank.crank_radius if spec.slider_crank else None)
    res = fw.size_flywheel(f.power_w, f.speed_rpm, f.speed_fluctuation, f.outer_diameter, f.inner_diameter, stroke,
                           f.material, f.other_inertia_kgm2, f.cycle_strokes, name=spec.name)
    print(format_flywheel_table(res), file=_out(args))
    emit_json({"file": args.file, **res.to_dict()}, args.json)
    if args.plot:
        import matplotlib.pyplot as plt

        ax = res.plot()
        _save_plot(ax.figure, args.plot)
        plt.close("all")
    return 0


def _flywheel_from_engine_torque(crank, args, emit_json) -> int:
    """Flywheel inertia from the real engine torque of a crank description with [excitation]."""
    from ..excitation.torque import engine_torque

    if args.rpm is None:
        raise FetorsionError(f"{args.file} is a crank description: give the speed with --rpm")
    t = engine_torque(crank, args.rpm)
    theta = np.append(t["theta"], t["theta"][-1] + (t["theta"][1] - t["theta"][0]))
    delta_e, mean = fw.fluctuation_energy(theta, np.append(t["total"], t["total"][0]))
    omega = args.rpm * 2 * np.pi / 60
    inertia = fw.flywheel_inertia(delta_e, args.speed_fluctuation, omega)
    have = sum(a.polar_inertia for a in crank.attachments_at(AttachPoint.REAR))
    res = {"file": args.file, "rpm": args.rpm, "mean_torque_nm": mean, "delta_e_j": delta_e,
           "speed_fluctuation": args.speed_fluctuation, "inertia_kgm2": inertia, "rear_attachments_kgm2": have}
    print(f"{crank.name}: flywheel from the engine torque at {args.rpm:g} rpm\n"
          f"  mean torque {mean:10.2f} N m\n  ΔE          {delta_e:10.2f} J\n"
          f"  I = ΔE/(C_s ω²), C_s = {args.speed_fluctuation:g}: {inertia:.5f} kg m^2 "
          f"(the description's rear attachments: {have:.5f})", file=_out(args))
    emit_json(res, args.json)
    return 0


def format_flywheel_table(res: fw.FlywheelSizing) -> str:
    rows = [("work per cycle W [J]", res.cycle_work_j), ("expansion work W_E [J]", res.expansion_work_j),
            ("T_max [N·m]", res.torque_max_nm), ("T_mean [N·m]", res.torque_mean_nm), ("T_ex [N·m]", res.torque_excess_nm),
            ("ΔE closed form [J]", res.delta_e_j), ("ΔE from the torque curve [J]", res.delta_e_curve_j),
            (f"I = ΔE/(C_s ω²), C_s = {res.speed_fluctuation:g} [kg·m²]", res.inertia_kgm2)]
    if res.mass_kg is not None:
        rows += [("mass 2I/(R1² + R2²) [kg]", res.mass_kg), ("mass with I rounded to 2 digits [kg]", res.mass_at_rounded_inertia_kg)]
    lines = [f"{res.name}: flywheel, {res.power_w / 1e3:g} kW at {res.speed_rpm:g} rpm (seed 000 energy method)"]
    lines += [f"  {label:<48} {value:12.4f}" for label, value in rows]
    for key, c in res.checks.items():
        vals = list(c.values())
        lines.append(f"  check {key:<42} {vals[0]:12.4f}  limits {vals[1][0]:g}–{vals[1][1]:g}  {'ok' if vals[2] else 'OUTSIDE'}")
    return "\n".join(lines)


def add_parsers(sub, emit_json) -> None:
    """Register the three subcommands on an argparse subparsers object."""
    def common(p):
        p.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
        p.add_argument("--plot", metavar="PATH", help="write a figure (PNG, PDF or SVG by suffix)")

    kp = sub.add_parser("kinematics", help="slider-crank or planetary-crank kinematics (seeds 002, 004)")
    kp.add_argument("file", help="mechanics file (.toml) with [slider_crank] or [planetary], or a crank description")
    kp.add_argument("--rpm", type=real(0.0, unit="rpm"), help="crank speed, rev/min (overrides the file's)")
    kp.add_argument("--step", type=real(0.0, 360.0, high_open=False, unit="deg"), default=30.0,
                    help="table step in crank angle, deg (default %(default)s)")
    common(kp)
    kp.set_defaults(func=lambda a: cmd_kinematics(a, emit_json))

    bp = sub.add_parser("balance", help="single-cylinder balancing: masses, counterweight, shafts, over-balancing (seeds 000, 001)")
    bp.add_argument("file", help="mechanics file (.toml) with [slider_crank], [masses], [balance]")
    common(bp)
    bp.set_defaults(func=lambda a: cmd_balance(a, emit_json))

    fp = sub.add_parser("flywheel", help="flywheel sizing by the energy method (seed 000)")
    fp.add_argument("file", help="mechanics file (.toml) with [flywheel], or a crank description with [excitation]")
    fp.add_argument("--rpm", type=real(0.0, unit="rpm"), help="speed for a crank description, rev/min")
    fp.add_argument("--speed-fluctuation", type=real(0.0, 1.0), default=0.04,
                    help="C_s = 2 (N1 − N2)/(N1 + N2) for a crank description (default %(default)s, seed 000)")
    common(fp)
    fp.set_defaults(func=lambda a: cmd_flywheel(a, emit_json))
