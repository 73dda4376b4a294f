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
from ..mechanics import reports
from ..description.crank import parse_crank
from ..description.model import AttachPoint
from ..description.reader import read_toml
from .common import add_json_option, emit_json
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


def cmd_kinematics(args) -> int:
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
        return _planetary(args, spec)
    theta = np.radians(np.arange(0.0, 360.0 + 1e-9, args.step))
    res = kin.kinematics(theta, r, l, rpm * np.pi / 30, name=name)
    print(res.table(), file=out)
    emit_json({"file": args.file, "speed_rpm": rpm, **res.to_dict()}, args.json)
    if args.plot:
        fine = kin.kinematics(np.radians(np.linspace(0, 360, 721)), r, l, rpm * np.pi / 30, name=name)
        _save_plot(fine.plot().figure, args.plot)
    return 0


def _planetary(args, spec) -> int:
    pairs = reports.planetary_results(spec)
    print(reports.planetary_table(spec.name, pairs), file=_out(args))
    emit_json({"file": args.file, "mechanisms": [{"planetary": r.figures(), "conventional_same_stroke": c.figures()}
                                                  for r, c in pairs]}, args.json)
    if args.plot:
        _save_plot(reports.plot_planetary(pairs), args.plot)
    return 0


# ---------------------------------------------------------------------------
# balance


def cmd_balance(args) -> int:
    _, spec = _load(args.file)
    if spec is None:
        raise FetorsionError(f"{args.file} is a crank description; balance needs a mechanics file "
                             "with [slider_crank], [masses] and [balance] (see geometry/b112_single.toml)")
    rep = reports.balance_report(spec)
    print(reports.balance_table(rep), file=_out(args))
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
        ax.set_title(f"{rep['name']}: residual force, λ = {lam:.3f}", fontsize=9, wrap=True)
        _save_plot(fig, args.plot)
    return 0


# ---------------------------------------------------------------------------
# flywheel


def cmd_flywheel(args) -> int:
    crank, spec = _load(args.file)
    if crank is not None:
        return _flywheel_from_engine_torque(crank, args)
    spec.need("flywheel")
    f = spec.flywheel
    stroke = f.stroke if f.stroke is not None else (2 * spec.slider_crank.crank_radius if spec.slider_crank else None)
    res = fw.size_flywheel(f.power_w, f.speed_rpm, f.speed_fluctuation, f.outer_diameter, f.inner_diameter, stroke,
                           f.material, f.other_inertia_kgm2, f.cycle_strokes, name=spec.name)
    print(res.table(), file=_out(args))
    emit_json({"file": args.file, **res.to_dict()}, args.json)
    if args.plot:
        import matplotlib.pyplot as plt

        ax = res.plot()
        _save_plot(ax.figure, args.plot)
        plt.close("all")
    return 0


def _flywheel_from_engine_torque(crank, args) -> int:
    """Flywheel inertia from the real engine torque of a crank description with [excitation]."""
    from ..excitation.loads import engine_torque

    if args.rpm is None:
        raise FetorsionError(f"{args.file} is a crank description: give the speed with --rpm")
    t = engine_torque(crank, args.rpm)
    theta = np.append(t.theta, t.theta[-1] + (t.theta[1] - t.theta[0]))
    delta_e, mean = fw.fluctuation_energy(theta, np.append(t.total, t.total[0]))
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


def add_parsers(sub) -> None:
    """Register the three subcommands on an argparse subparsers object."""
    def common(p):
        add_json_option(p)
        p.add_argument("--plot", metavar="PATH", help="write a figure (PNG, PDF or SVG by suffix)")

    kp = sub.add_parser("kinematics", help="slider-crank or planetary-crank kinematics ([Ismailov], [Kazemi])")
    kp.add_argument("file", help="mechanics file (.toml) with [slider_crank] or [planetary], or a crank description")
    kp.add_argument("--rpm", type=real(0.0, unit="rpm"), help="crank speed, rev/min (overrides the file's)")
    kp.add_argument("--step", type=real(0.0, 360.0, high_open=False, unit="deg"), default=30.0,
                    help="table step in crank angle, deg (default %(default)s)")
    common(kp)
    kp.set_defaults(func=cmd_kinematics)

    bp = sub.add_parser("balance", help="single-cylinder balancing: masses, counterweight, shafts, over-balancing ([Asgari], [Wang])")
    bp.add_argument("file", help="mechanics file (.toml) with [slider_crank], [masses], [balance]")
    common(bp)
    bp.set_defaults(func=cmd_balance)

    fp = sub.add_parser("flywheel", help="flywheel sizing by the energy method ([Asgari])")
    fp.add_argument("file", help="mechanics file (.toml) with [flywheel], or a crank description with [excitation]")
    fp.add_argument("--rpm", type=real(0.0, unit="rpm"), help="speed for a crank description, rev/min")
    fp.add_argument("--speed-fluctuation", type=real(0.0, 1.0), default=0.04,
                    help="C_s = 2 (N1 − N2)/(N1 + N2) for a crank description (default %(default)s, [Asgari])")
    common(fp)
    fp.set_defaults(func=cmd_flywheel)
