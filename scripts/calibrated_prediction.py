"""What a calibration predicts for the engine: the crank in its bearings (f1) and its fatigue
(governing location, safety and equivalent stress at the damping band's low end), with a band.

    python scripts/calibrated_prediction.py [geometry/renault21.toml] [--measured-hz 530]
        [--inputs NAME ...] [--mesh-size MM] [--json PATH]

1. ``run_calibration`` (both methods) of the description's ``--inputs`` on the measured free-free
   frequencies, with the lumped chain (the fast model the posterior needs thousands of runs of).
2. The posterior samples whose lumped f1 sits nearest its 5, 50 and 95 % points, and the least-squares
   point, each made into a description variant.
3. Each variant's condensed 3D FE crank in its bearings at ``--mesh-size`` (one mesh, one
   factorisation, one condensation): its first torsional frequency, and the fatigue assessment of
   every fillet and oil bore (IACS UR M53) at the low end of the damping band.

The SCFs are the nominal crank's, held: the default inputs (counterweight radius, steel's E and
density) leave the fillets' and drillings' local geometry as it is, and an elastic SCF does not
depend on E. Naming an input that moves a fillet or a diameter would need the SCFs of each variant,
and is refused. The band is that of the variants at the f1 quantiles, not a propagated
distribution: four FE runs, not thousands.
"""

from __future__ import annotations

import argparse
import json
import platform
import time

import numpy as np

import fetorsion
from fetorsion.description.defaults import DEFAULT_MESH_SIZE, DEFAULT_WEB_METHOD
from fetorsion.io import write_text_atomic

#: Inputs whose change leaves every fillet's and drilling's local geometry (and so the SCFs) alone
SCF_NEUTRAL = ("webs.*.counterweight_radius", "webs.*.counterweight_angle_deg", "material", "front.*.length",
               "rear.*.length")
QUANTILES = (5.0, 50.0, 95.0)


def engine_answers(crank, scf, mesh_size):
    """(f1 in bearings Hz, governing location, its safety, its equivalent alternating stress Pa, rpm,
    the governing fillet's safety) of ``crank`` at the damping band's low end."""
    from fetorsion.design.assessment import run_assessment
    from fetorsion.design.stress import fillet_cuts, fillets_of
    from fetorsion.fe.condensed import run_condensed
    from fetorsion.fe.cranksystem import build_system
    from fetorsion.lumped_model.parts import build_parts
    from fetorsion.response.coupled import condensed_setup
    from fetorsion.response.cycle import run_load_cycle
    from fetorsion.solid.mesh import mesh_crank

    fillets = fillets_of(crank, build_parts(crank, DEFAULT_WEB_METHOD))
    system = build_system(crank, mesh_size, mesh_crank(crank, mesh_size))
    cc = run_condensed(crank, system=system, cuts=fillet_cuts(crank, fillets))
    f_bearings = cc.modes("bearings").first_torsional()
    setup = condensed_setup(cc, "bearings", damping_ratio=crank.excitation.damping_band[0],
                            section_labels=[f.label for f in fillets])
    a = run_assessment(crank, run_load_cycle(cc, setup, crank.dampers), fillets, scf, "iacs-m53")
    g = a.governing
    fillet_cols = [j for j, k in enumerate(a.labels) if "fillet" in k]
    worst_fillet = min(fillet_cols, key=lambda j: a.safety[:, j].min())
    return {"f1_bearings_hz": float(f_bearings), "governing": a.labels[g], "safety": float(a.safety[:, g].min()),
            "equivalent_stress_mpa": a.worst.locations[g].equivalent_alternating / 1e6, "rpm": float(a.worst_rpm[g]),
            "worst_fillet": a.labels[worst_fillet], "worst_fillet_safety": float(a.safety[:, worst_fillet].min()),
            "worst_fillet_stress_mpa": a.worst.locations[worst_fillet].equivalent_alternating / 1e6,
            "required": float(a.worst.locations[g].required)}


def main(argv=None):
    from fetorsion.design.oilbore import oil_bore_scfs
    from fetorsion.design.scf import fillet_scfs
    from fetorsion.lumped_model.lumped import lumped
    from fetorsion.studies.calibration import calibration_inputs, run_calibration, variant

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("file", nargs="?", default="geometry/renault21.toml")
    p.add_argument("--measured-hz", type=float, nargs="+", default=None,
                   help="default: the description's [meta] measured_first_torsional_hz")
    p.add_argument("--inputs", nargs="+", default=["webs.*.counterweight_radius", "material"])
    p.add_argument("--mesh-size", type=float, default=DEFAULT_MESH_SIZE * 1e3, metavar="MM")
    p.add_argument("--json", default=None)
    args = p.parse_args(argv)
    moved = [n for n in args.inputs if n not in SCF_NEUTRAL]
    if moved:
        raise SystemExit(f"--inputs {moved[0]}: moves a fillet's or drilling's geometry, so each variant would need "
                         f"its own SCFs; choose among {', '.join(SCF_NEUTRAL)}")
    crank = fetorsion.load(args.file)
    measured = args.measured_hz or [float(crank.notes["measured_first_torsional_hz"])]
    t0 = time.perf_counter()
    cal = run_calibration(crank, measured, inputs=args.inputs, method="both")
    inputs = calibration_inputs(crank, args.inputs)
    f1 = cal.posterior.frequencies_hz[:, 0]
    points = {f"posterior f1 {q:g} %": cal.posterior.samples[int(np.argmin(np.abs(f1 - np.percentile(f1, q))))]
              for q in QUANTILES}
    points["least squares"] = cal.lsq.values
    scf = dict(fillet_scfs(crank))
    bores = oil_bore_scfs(crank)
    for kind in ("pin", "journal"):
        if kind in bores:
            scf[f"{kind}_oil_bore_bending"], scf[f"{kind}_oil_bore_torsion"] = bores[kind]
    size = args.mesh_size * 1e-3
    rows = {"nominal": {"inputs": {i.name: i.nominal for i in inputs},
                        "f1_free_lumped_hz": float(lumped(crank, 17).frequencies_hz[0]), **engine_answers(crank, scf, size)}}
    for name, x in points.items():
        changes = {}
        for i, v in zip(inputs, x):
            changes.update(i.values(float(v)))
        v = variant(crank, changes)
        rows[name] = {"inputs": {i.name: float(val) for i, val in zip(inputs, x)},
                      "f1_free_lumped_hz": float(lumped(v, 17).frequencies_hz[0]), **engine_answers(v, scf, size)}
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")),
               platform.processor())
    out = {"description": args.file, "measured_hz": measured, "inputs": args.inputs, "mesh_size_mm": args.mesh_size,
           "scf_source": scf.get("source"), "identified": {r["input"]: r["identified"] for r in cal.input_rows()},
           "posterior": {r["input"]: {k: r[k] for k in ("median", "q5", "q95", "width_ratio")} for r in cal.input_rows()},
           "rows": rows, "seconds": time.perf_counter() - t0, "cpu": cpu}
    print(f"{crank.name}: calibrated on {measured} Hz ({', '.join(args.inputs)}), engine model at {args.mesh_size:g} mm")
    print(f"{'point':22} {'inputs':38} {'f1 free (chain)':>15} {'f1 bearings':>11} {'governing':>24} {'Q':>5} "
          f"{'sigma_V MPa':>11} {'worst fillet Q':>14}")
    for name, r in rows.items():
        ins = ", ".join(f"{v:.4g}" for v in r["inputs"].values())
        print(f"{name:22} {ins:38} {r['f1_free_lumped_hz']:15.1f} {r['f1_bearings_hz']:11.1f} "
              f"{r['governing'] + ' ' + format(r['rpm'], '.0f'):>24} {r['safety']:5.2f} {r['equivalent_stress_mpa']:11.1f} "
              f"{r['worst_fillet_safety']:14.2f}")
    print(f"{out['seconds']:.0f} s on {cpu}")
    if args.json:
        write_text_atomic(args.json, json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
