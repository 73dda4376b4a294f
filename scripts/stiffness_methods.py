"""First torsional frequency of both reference cranks with every web stiffness method (issue 8).

Run from the repository root, after ``scripts/web_chart.py`` (the ``chart`` method reads its table):

    nice -n 10 python scripts/stiffness_methods.py               # lumped models + FE throws
    nice -n 10 python scripts/stiffness_methods.py --modal 0.012 # also the full 3D FE f1 at 12 mm

The throws' FE results are written into ``fetorsion/data/throw_fe.json`` (the package's shipped
cache, so that ``fetorsion run --all`` never re-meshes them). Writes
``results/chart/stiffness_methods.md`` and ``results/chart/stiffness_methods.json``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from fetorsion.webs import throwfe  # noqa: E402

# Every throw computed here goes into the shipped cache.
os.environ[throwfe.CACHE_ENV] = str(throwfe.SHIPPED_CACHE)

import fetorsion  # noqa: E402
from fetorsion.io import write_text_atomic  # noqa: E402
from fetorsion.lumped_model.lumped import PARTITIONS  # noqa: E402
from fetorsion.webs.methods import WEB_METHODS, web_equivalent_length  # noqa: E402
from fetorsion.webs.chart import chart_coordinates  # noqa: E402

OUT = ROOT / "results" / "chart"
CRANKS = ("peugeot_glx", "renault21")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--modal", type=float, metavar="SIZE_M", help="also the full 3D FE f1 at this mesh size (m)")
    args = ap.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    report = {}
    lines = ["# Web stiffness methods side by side (issue 8)", "",
             "Lumped free-free models of seed 003 (partitions in `fetorsion/lumped_model/lumped.py`), first torsional "
             "frequency f1 in Hz, one column per web method. `fe`: static 3D FE of each throw "
             "(`fetorsion/webs/throwfe.py`); `chart`: the computed web chart (`fetorsion/webs/chart.py`, "
             "`results/chart/web_chart.md`). Carter and Ker Wilson are as commonly quoted (unverified). "
             "Written by `scripts/stiffness_methods.py`.", ""]
    for name in CRANKS:
        crank = fetorsion.load(ROOT / "geometry" / f"{name}.toml")
        d_e = crank.journals[0].diameter
        t0 = time.perf_counter()
        table = {m: [float(fetorsion.lumped(crank, d, m).frequencies_hz[0]) for d in PARTITIONS] for m in WEB_METHODS}
        seconds = time.perf_counter() - t0
        webs = {m: [web_equivalent_length(crank, w, d_e, m) for w in range(len(crank.webs))] for m in WEB_METHODS}
        throws = [throwfe.throw_torsion(throwfe.throw_of(crank, i)) for i in range(crank.throws)]
        c, q = chart_coordinates(crank, 0)
        bare = dataclasses.replace(crank, webs=tuple(dataclasses.replace(w, counterweight_radius=0.0,
                                                                            counterweight_angle=0.0)
                                                     for w in crank.webs))
        no_cw = web_equivalent_length(bare, 0, d_e, "fe")
        entry = {"f1_hz": table, "web_le_m": webs, "throws": throws, "chart_c": c, "chart_q": q,
                 "fe_web_without_counterweight_m": no_cw, "lumped_seconds": seconds}
        if args.modal:
            from fetorsion.fe.crankfe import run_modal

            t0 = time.perf_counter()
            res = run_modal(crank, args.modal, modes=12)
            entry["fe_modal"] = {"mesh_size_m": args.modal, "dofs": res.dofs, "f1_hz": res.first_torsional(),
                                 "seconds": time.perf_counter() - t0}
        report[name] = entry
        lines += section(crank, entry)
    write_text_atomic(OUT / "stiffness_methods.json", json.dumps(report, indent=1))
    write_text_atomic(OUT / "stiffness_methods.md", "\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


def section(crank, e: dict) -> list[str]:
    methods = list(WEB_METHODS)
    paper = crank.notes.get("paper_lumped_first_torsional_hz", {})
    measured = crank.notes.get("measured_first_torsional_hz")
    out = [f"## {crank.name}", "", "| model | " + " | ".join(methods) + " | paper (BICERA) |",
           "|---|" + "---|" * (len(methods) + 1)]
    for i, d in enumerate(PARTITIONS):
        out.append(f"| {d} DOF | " + " | ".join(f"{e['f1_hz'][m][i]:.1f}" for m in methods)
                   + f" | {paper.get(str(d), '')} |")
    fe = e.get("fe_modal")
    if fe:
        f17 = {m: e["f1_hz"][m][PARTITIONS.index(17)] for m in methods}
        out.append(f"| 3D FE modal (this branch, {fe['mesh_size_m'] * 1e3:g} mm mesh, {fe['dofs']} DOF) | "
                   + " | ".join(f"{fe['f1_hz']:.1f}" for _ in methods) + " | |")
        out.append("| 17 DOF vs 3D FE | " + " | ".join(f"{100 * (f17[m] / fe['f1_hz'] - 1):+.1f} %" for m in methods)
                   + " | |")
    if measured:
        out += ["", f"Measured (seed 003, free-free modal test): {measured:g} Hz; "
                f"paper's ANSYS FE: {crank.notes.get('paper_fe_first_torsional_hz', '')} Hz."]
    d_e = crank.journals[0].diameter
    le = {m: e["web_le_m"][m][0] for m in methods}
    out += ["", f"Web 1 equivalent length L_eb (mm, reduced to D_e = {d_e * 1e3:g} mm): "
            + ", ".join(f"{m} {v * 1e3:.2f}" for m, v in le.items())
            + f". FE web without its counterweight: {e['fe_web_without_counterweight_m'] * 1e3:.2f} mm. "
            f"Chart coordinates c = {e['chart_c']:.3f}, R·D_e³/(L_b·B_e³) = {e['chart_q']:.3f}.", ""]
    out += ["| throw | FE k (N·m/rad) | L_e (mm at D_e) | DOF | mesh (mm) / fillets (mm) | time (s) |",
            "|---|---|---|---|---|---|"]
    G = crank.material.shear_modulus
    for i, t in enumerate(e["throws"]):
        L = G * 3.141592653589793 * d_e**4 / (32 * t["stiffness"])
        out.append(f"| {i + 1} | {t['stiffness']:.4g} | {L * 1e3:.2f} | {t['dofs']} | "
                   f"{t['mesh_size'] * 1e3:.1f} / {t['fillet_size'] * 1e3:.2f} | {t['seconds']:.1f} |")
    out.append("")
    return out


if __name__ == "__main__":
    raise SystemExit(main())
