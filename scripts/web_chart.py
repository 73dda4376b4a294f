"""Compute the web chart (issue 8): FE L_e0/D_t over (c, q) plus fillet and oil-hole sweeps.

Every FE run (one throw, one mesh) is a sample of a study on the local Dask cluster
(issue 15, :mod:`fetorsion.studies.runner`): runs go to the workers in parallel and each
is stored as it finishes, so an interrupted sweep resumes where it stopped and a point
shared by two uses (the convergence study's two finer meshes are the centre point's) is
computed once. Run from the repository root (one FE job per worker, one BLAS thread each):

    nice -n 10 python scripts/web_chart.py                          # resumes from points.json and the sample store
    nice -n 10 python scripts/web_chart.py --fresh                  # recompute every point
    nice -n 10 python scripts/web_chart.py --scheduler tcp://host:8786   # on an existing cluster

Writes ``fetorsion/data/web_chart.json`` (the table the ``chart`` web method interpolates),
``results/chart/points.json`` (every FE point, both meshes, timings),
``results/chart/web_chart.png`` and ``results/chart/web_chart.md``. The family and the
chart coordinates are defined in :mod:`fetorsion.webs.chart`.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import matplotlib  # noqa: E402
import matplotlib.ticker  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fetorsion.extrapolation import richardson  # noqa: E402
from fetorsion.io import save_figure_atomic, write_text_atomic  # noqa: E402
from fetorsion.studies.runner import ClusterOnDemand, SampleStore, default_store, run_samples  # noqa: E402
from fetorsion.webs import chart as wc  # noqa: E402

OUT = ROOT / "results" / "chart"
POINTS = OUT / "points.json"

C_GRID = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]
Q_GRID = [0.5, 0.7, 1.0, 1.4, 2.0]
CENTRE = (0.3, 1.0)
#: Points not in the grid: the interpolation is judged on them.
HELD_OUT = [(0.05, 0.6), (0.15, 1.2), (0.25, 0.85), (0.35, 1.7), (0.45, 0.6)]
#: Same (c, q), the other free choice (thickness vs width) moved: the chart's own spread.
SPLITS = [(c, q, s) for c, q in ((0.1, 0.5), (0.3, 2.0), (0.4, 0.5)) for s in (0.25, 0.75)]
FILLETS = [0.03, 0.045, 0.06]       # r / D_t, journal and pin alike
OIL_HOLES = [0.05, 0.08, 0.12]      # φ / D_t, journals and pin drilled
#: Where the corrections are checked away from the centre (r/D_t = 0.045, φ/D_t = 0.08).
CORRECTION_CHECKS = [(0.1, 1.4), (0.5, 0.7)]
D_T = 0.06
#: The convergence study's meshes at the centre: the chart's two and a finer one.
RATE_SHARES = [*wc.MESH_SHARES, 1.0 / 16.0]


def key(kind, *args) -> str:
    return kind + ":" + ",".join(f"{a:g}" for a in args)


class ChartMesh:
    """One FE run of the chart family's throw on one mesh: a sample ``{c, q, mesh_share, and
    split / fillet / oil_hole}`` in, ``le_dt``, ``dofs``, ``seconds`` out."""

    key = f"web-chart-mesh/d_t={D_T!r}"
    expensive = True

    def __call__(self, v: dict) -> dict:
        v = dict(v)
        return wc.chart_point_fe(v.pop("c"), v.pop("q"), v.pop("mesh_share"), d_t=D_T, **v)


def jobs() -> list[tuple[str, dict]]:
    """Every chart point: (its key in points.json, its throw's parameters)."""
    out = [(key("grid", c, q), dict(c=c, q=q)) for c in C_GRID for q in Q_GRID]
    out += [(key("held", c, q), dict(c=c, q=q)) for c, q in HELD_OUT]
    out += [(key("split", c, q, s), dict(c=c, q=q, split=s)) for c, q, s in SPLITS]
    out += [(key("fillet", *CENTRE, r), dict(c=CENTRE[0], q=CENTRE[1], fillet=r * D_T)) for r in FILLETS]
    out += [(key("oil", *CENTRE, h), dict(c=CENTRE[0], q=CENTRE[1], oil_hole=h * D_T)) for h in OIL_HOLES]
    out += [(key("base", c, q), dict(c=c, q=q)) for c, q in CORRECTION_CHECKS]
    out += [(key("fillet", c, q, 0.045), dict(c=c, q=q, fillet=0.045 * D_T)) for c, q in CORRECTION_CHECKS]
    out += [(key("oil", c, q, 0.08), dict(c=c, q=q, oil_hole=0.08 * D_T)) for c, q in CORRECTION_CHECKS]
    return out


def sweep(points: list[tuple[str, dict]], store: SampleStore, client, known: dict | None = None) -> tuple[dict, float]:
    """Run every FE mesh of ``points`` (and the convergence study) as study samples, except the
    points (and the convergence study, ``"rate"``) already in ``known`` (an earlier points.json);
    the points.json table and the FE seconds summed over the runs made or found stored."""
    known = dict(known or {})
    todo = [(k, kw) for k, kw in points if k not in known]
    rate_runs = [] if "rate" in known else [dict(c=CENTRE[0], q=CENTRE[1], mesh_share=s) for s in RATE_SHARES]
    samples = rate_runs + [dict(kw, mesh_share=s) for _, kw in todo for s in wc.MESH_SHARES]
    records, _ = run_samples(ChartMesh(), samples, store, client, batch_size=1, label="web chart")
    failed = [(s, r["error"]) for s, r in zip(samples, records) if "error" in r]
    if failed:
        raise SystemExit(f"web chart: {len(failed)} FE runs failed; first {failed[0][0]}: {failed[0][1]}")
    out = [r["outputs"] for r in records]
    done = known
    if rate_runs:
        rate = out[:len(RATE_SHARES)]
        done["rate"] = {"shares": RATE_SHARES, "le_dt": [v["le_dt"] for v in rate],
                        "p": wc.convergence_rate([v["le_dt"] for v in rate], RATE_SHARES),
                        "seconds": sum(v["seconds"] for v in rate)}
    p = done["rate"]["p"]
    for n, (k, kw) in enumerate(todo):
        a, b = out[len(rate_runs) + 2 * n:len(rate_runs) + 2 * n + 2]
        done[k] = {**kw, "le_dt": richardson(a["le_dt"], b["le_dt"], *wc.MESH_SHARES, p),
                   "le_dt_meshes": [a["le_dt"], b["le_dt"]], "dofs": [a["dofs"], b["dofs"]],
                   "seconds": a["seconds"] + b["seconds"]}
    unique = {id(r): r for r in records}.values()  # a shared run is one record
    return done, sum(r.get("seconds", 0.0) for r in unique)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fresh", action="store_true",
                    help="recompute every point (ignore results/chart/points.json, a new temporary sample store)")
    ap.add_argument("--store", help="sample store (default $FETORSION_STORE, else ~/.cache/fetorsion/samples)")
    ap.add_argument("--scheduler", help="an existing Dask scheduler (default $DASK_SCHEDULER_ADDRESS, else local)")
    ap.add_argument("--workers", type=int, help="local cluster's worker processes (default one per core)")
    args = ap.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    known = {} if args.fresh or not POINTS.exists() else json.loads(POINTS.read_text())
    with tempfile.TemporaryDirectory() as tmp, ClusterOnDemand(args.scheduler, args.workers) as client:
        store = SampleStore(tmp if args.fresh else args.store or default_store())
        done, fe_seconds = sweep(jobs(), store, client, known)
    if known:  # points taken from points.json: their FE time is the one recorded there
        fe_seconds = done["rate"]["seconds"] + sum(v["seconds"] for k, v in done.items() if k != "rate")
    wall = time.perf_counter() - t_start
    p = done["rate"]["p"]
    print(f"observed order p = {p:.3f}", flush=True)
    write_text_atomic(POINTS, json.dumps(done, indent=1))
    table = build_table(done, p)
    write_text_atomic(wc.CHART_FILE, json.dumps(table, indent=1))
    write_text_atomic(OUT / "web_chart.md", markdown(table, done, fe_seconds))
    plot(table, done)
    print(f"{len(done) - 1} points, FE time {fe_seconds:.0f} s, wall this run {wall:.0f} s", flush=True)
    return 0


def build_table(done: dict, p: float) -> dict:
    grid = np.array([[done[key("grid", c, q)]["le_dt"] for q in Q_GRID] for c in C_GRID])
    base = done[key("grid", *CENTRE)]["le_dt"]
    fil = [0.0] + [done[key("fillet", *CENTRE, r)]["le_dt"] - base for r in FILLETS]
    oil = [0.0] + [done[key("oil", *CENTRE, h)]["le_dt"] - base for h in OIL_HOLES]
    table = {
        "description": "L_e0/D_t of a plain crank web (per web, reduced to D_e = D_t) from static 3D FE "
                       "of the throw, fetorsion issue 8; family and method in fetorsion/webs/chart.py",
        "family": {"pin_diameter_dt": wc.PIN_DIAMETER, "journal_length_dt": wc.JOURNAL_LENGTH,
                   "pin_length_dt": wc.PIN_LENGTH, "width_ratio_bmin_bmax": wc.WIDTH_RATIO,
                   "ref_thickness_dt": wc.REF_THICKNESS, "ref_width_dt": wc.REF_WIDTH, "split": 0.5,
                   "poisson_ratio": wc.STEEL.poisson_ratio, "counterweight": False},
        "grid": {"c": C_GRID, "q": Q_GRID, "le_dt": grid.tolist()},
        "interpolation": "cubic",
        "mesh": {"shares_dt": list(wc.MESH_SHARES), "richardson_order": p},
        "corrections": {
            "fillet": {"x": [0.0] + FILLETS, "dle_dt": fil, "x_is": "r/D_t (journal and pin)",
                       "at": list(CENTRE)},
            "oil_hole": {"x": [0.0] + OIL_HOLES, "dle_dt": oil, "x_is": "phi/D_t (journals and pin)",
                         "at": list(CENTRE)},
        },
    }
    table["validity"] = validity(table, done)
    return table


def validity(table: dict, done: dict) -> dict:
    """Errors of the shipped chart on points it was not built from."""
    wc.load_chart.cache_clear(), wc._interpolator.cache_clear()
    tmp = OUT / ".chart_tmp.json"
    tmp.write_text(json.dumps(table))
    try:
        held = [(c, q, done[key("held", c, q)]["le_dt"], wc.le0_dt(c, q, str(tmp))) for c, q in HELD_OUT]
        splits = [(c, q, s, done[key("split", c, q, s)]["le_dt"], done[key("grid", c, q)]["le_dt"])
                  for c, q, s in SPLITS]
        cors = []
        for c, q in CORRECTION_CHECKS:
            b = done[key("base", c, q)]["le_dt"]
            cors.append((c, q, "fillet", done[key("fillet", c, q, 0.045)]["le_dt"] - b,
                         wc.correction_dt("fillet", 0.045, str(tmp))))
            cors.append((c, q, "oil_hole", done[key("oil", c, q, 0.08)]["le_dt"] - b,
                         wc.correction_dt("oil_hole", 0.08, str(tmp))))
    finally:
        tmp.unlink()
        wc.load_chart.cache_clear(), wc._interpolator.cache_clear()
    interp = max(abs(i / f - 1) for *_, f, i in held)
    spread = max(abs(s / g - 1) for *_, s, g in splits)
    cor = max(abs(a - b) for *_, a, b in cors)
    return {"c": [C_GRID[0], C_GRID[-1]], "q": [Q_GRID[0], Q_GRID[-1]],
            "fillet_r_dt": [0.0, FILLETS[-1]], "oil_hole_dt": [0.0, OIL_HOLES[-1]],
            "interpolation_rel_error": interp,
            "thickness_width_split_rel_spread": spread,
            "correction_abs_error_dt": cor,
            "held_out": [{"c": c, "q": q, "fe": f, "chart": i} for c, q, f, i in held],
            "splits": [{"c": c, "q": q, "split": s, "fe": v, "grid": g} for c, q, s, v, g in splits],
            "correction_checks": [{"c": c, "q": q, "kind": k, "fe": a, "chart": b} for c, q, k, a, b in cors]}


def markdown(table: dict, done: dict, fe_seconds: float) -> str:
    v = table["validity"]
    lines = ["# Computed BICERA web chart: L_e0/D_t", "",
             "Static 3D FE torsion of one throw of the parametric family in `fetorsion/webs/chart.py` "
             "(no counterweight, sharp junctions), web term per web reduced to D_e = D_t; each point "
             f"Richardson-extrapolated from meshes D_t/8 and D_t/12 with the observed order "
             f"p = {table['mesh']['richardson_order']:.2f}. Written by `scripts/web_chart.py`.", "",
             "| c \\ R·D_e³/(L_b·B_e³) | " + " | ".join(f"{q:g}" for q in Q_GRID) + " |",
             "|---|" + "---|" * len(Q_GRID)]
    for c, row in zip(C_GRID, table["grid"]["le_dt"]):
        lines.append(f"| {c:g} | " + " | ".join(f"{x:.4f}" for x in row) + " |")
    lines += ["", f"Corrections at c = {CENTRE[0]:g}, q = {CENTRE[1]:g} (ΔL/D_t, added to L_e0/D_t):", "",
              "| r/D_t (fillets) | " + " | ".join(f"{x:g}" for x in table["corrections"]["fillet"]["x"]) + " |",
              "|---|" + "---|" * len(table["corrections"]["fillet"]["x"]),
              "| ΔL/D_t | " + " | ".join(f"{x:+.4f}" for x in table["corrections"]["fillet"]["dle_dt"]) + " |", "",
              "| φ/D_t (oil holes) | " + " | ".join(f"{x:g}" for x in table["corrections"]["oil_hole"]["x"]) + " |",
              "|---|" + "---|" * len(table["corrections"]["oil_hole"]["x"]),
              "| ΔL/D_t | " + " | ".join(f"{x:+.4f}" for x in table["corrections"]["oil_hole"]["dle_dt"]) + " |", "",
              "## Validity", "",
              f"- Range: c in [{v['c'][0]:g}, {v['c'][1]:g}], R·D_e³/(L_b·B_e³) in [{v['q'][0]:g}, {v['q'][1]:g}], "
              f"r/D_t ≤ {v['fillet_r_dt'][1]:g}, φ/D_t ≤ {v['oil_hole_dt'][1]:g}; outside: FetorsionError.",
              f"- Interpolation (cubic in c and log q) on {len(v['held_out'])} held-out FE points: "
              f"max error {100 * v['interpolation_rel_error']:.2f} %.",
              f"- Two parameters do not fix a web: moving the thickness/width split (0.25 and 0.75 instead "
              f"of 0.5) at the same (c, q) changes L_e0 by up to {100 * v['thickness_width_split_rel_spread']:.1f} %.",
              f"- Corrections taken at the centre and used elsewhere: off by up to "
              f"{v['correction_abs_error_dt']:.4f} D_t at the check points.", "",
              "| check | c | q | FE | chart |", "|---|---|---|---|---|"]
    lines += [f"| held out | {h['c']:g} | {h['q']:g} | {h['fe']:.4f} | {h['chart']:.4f} |" for h in v["held_out"]]
    lines += [f"| split {s['split']:g} | {s['c']:g} | {s['q']:g} | {s['fe']:.4f} | {s['grid']:.4f} (split 0.5) |"
              for s in v["splits"]]
    lines += [f"| {k['kind']} ΔL | {k['c']:g} | {k['q']:g} | {k['fe']:+.4f} | {k['chart']:+.4f} |"
              for k in v["correction_checks"]]
    n = len([k for k in done if k != "rate"])
    lines += ["", f"Sweep: {n} chart points (two meshes each) plus a three-mesh convergence study (its two coarser "
              f"meshes are the centre point's); {fe_seconds:.0f} s of FE time summed over the runs (meshing "
              "included; each run a sample on a Dask cluster, one BLAS thread per worker, 2 CPU cores shared with "
              "other work).", ""]
    return "\n".join(lines)


def plot(table: dict, done: dict) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), gridspec_kw={"width_ratios": [2, 1]})
    ax = axes[0]
    qs = np.geomspace(Q_GRID[0], Q_GRID[-1], 60)
    for c, row in zip(C_GRID, table["grid"]["le_dt"]):
        line = ax.plot(qs, [wc.le0_dt(c, q) for q in qs], lw=1.2, label=f"c = {c:g}")[0]
        ax.plot(Q_GRID, row, "o", color=line.get_color(), ms=4)
    for h in table["validity"]["held_out"]:
        ax.plot(h["q"], h["fe"], "kx", ms=6)
    ax.plot([], [], "kx", label="held-out FE")
    ax.set_xscale("log")
    ax.set_xticks(Q_GRID, [f"{q:g}" for q in Q_GRID])
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("R·D_e³ / (L_b·B_e³)")
    ax.set_ylabel("L_e0 / D_t (per web)")
    ax.set_title("Computed web chart (static 3D FE of the throw)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[1]
    for name, label in (("fillet", "fillets, x = r/D_t"), ("oil_hole", "oil holes, x = φ/D_t")):
        cor = table["corrections"][name]
        ax.plot(cor["x"], cor["dle_dt"], "o-", label=label)
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("x")
    ax.set_ylabel("ΔL / D_t")
    ax.set_title(f"Corrections at c = {CENTRE[0]:g}, q = {CENTRE[1]:g}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure_atomic(fig, OUT / "web_chart.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    raise SystemExit(main())
