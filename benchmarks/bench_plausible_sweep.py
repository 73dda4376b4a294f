"""Plausible cranks of new users through `lumped --stiffness fe` and `modal` (issue 53).

Draws ``--count`` in-line cranks from one seed (:mod:`fetorsion.description.samples`: bore and
stroke to truck sizes, fillets, drillings, hollow pins and counterweights on and off), reads
each like a file and runs both FE steps at the default mesh size. Prints the table that
docs/plausible-cranks.md carries and writes results/plausible/sweep.json. Heavy (about a
minute per crank on 2 cores): run it niced, alone.

    nice -n 5 .venv/bin/python benchmarks/bench_plausible_sweep.py [--seed 53] [--count 40] [--layout vee]
"""

import argparse
import json
import platform
import time
from pathlib import Path

from fetorsion.description.samples import plausible_cranks
from fetorsion.studies.plausible import try_crank
from fetorsion.io import write_text_atomic

ROOT = Path(__file__).resolve().parents[1]


def cpu() -> str:
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return platform.processor()


def row_text(i: int, r: dict) -> str:
    lumped, modal = r.get("lumped, fe webs", {}), r.get("modal", {})
    feats = ", ".join(k for k in ("fillets", "drillings", "counterweights", "hollow_pins") if r[k]) or "-"
    f1 = (f"{lumped['f1_hz']:.0f} / {modal['f1_hz']:.0f} ({100 * (lumped['f1_hz'] / modal['f1_hz'] - 1):+.1f} %)"
          if "f1_hz" in modal else "")
    time_s = f"{lumped.get('seconds', 0):.0f} + {modal.get('seconds', 0):.0f}"
    why = "" if r["status"] == "ok" else f"{r['step']}: {r['message'].splitlines()[0][:160]}"
    return (f"| {i} | {r['cylinders']} | {r['stroke_mm']:g} | {feats} | {r['status']} | {modal.get('dofs', '')} | "
            f"{f1} | {time_s} | {why} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=53)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--layout", choices=("in-line", "vee"), default="in-line")
    ap.add_argument("--out", help="the table as JSON (default results/plausible/sweep.json, sweep_vee.json)")
    args = ap.parse_args()
    t0 = time.perf_counter()
    rows = []
    print("| # | cyl | stroke (mm) | features | status | modal DOF | f1 lumped fe / 3D FE (Hz) | time (s) | why |")
    print("|---|---|---|---|---|---|---|---|---|")
    for i, raw in enumerate(plausible_cranks(args.seed, args.count, args.layout)):
        rows.append(try_crank(raw, f"plausible {args.layout} seed {args.seed} #{i}"))
        print(row_text(i, rows[-1]), flush=True)
    total = time.perf_counter() - t0
    counts = {s: sum(r["status"] == s for r in rows) for s in ("ok", "refused", "failed")}
    print(f"\n{counts['ok']} ok, {counts['refused']} refused, {counts['failed']} failed of {len(rows)} "
          f"in {total / 60:.1f} min on {cpu()}")
    out = Path(args.out or ROOT / "results" / "plausible" / ("sweep.json" if args.layout == "in-line" else
                                                             "sweep_vee.json"))
    out.parent.mkdir(parents=True, exist_ok=True)
    write_text_atomic(out, json.dumps({"seed": args.seed, "count": args.count, "layout": args.layout,
                                       "seconds": total, "cpu": cpu(),
                                       "counts": counts, "rows": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
