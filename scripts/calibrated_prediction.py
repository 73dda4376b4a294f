"""What a calibration predicts for the engine: the crank in its bearings (f1) and its fatigue
(UR M53's governing place, Q and equivalent stress at the description's damping), with a band.

    python scripts/calibrated_prediction.py [geometry/renault21.toml] [--measured-hz 530]
        [--inputs NAME ...] [--mesh-size MM] [--json PATH]

1. ``run_calibration`` (both methods) of the description's ``--inputs`` on the measured free-free
   frequencies, with the lumped chain (the fast model the posterior needs thousands of runs of).
2. The posterior samples whose lumped f1 sits nearest its 5, 50 and 95 % points, and the least-squares
   point, each made into a description variant.
3. Each variant's condensed 3D FE crank in its bearings at ``--mesh-size`` (one mesh, one
   factorisation, one condensation): its first torsional frequency, and UR M53 as written (the
   verdict's default method) on every throw at the description's damping ratio.

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
    """(f1 in bearings Hz, governing place, its Q, its equivalent alternating stress σ_V Pa, the
    speed of its torsion, the worst fillet's Q) of ``crank``: UR M53 as written (the verdict's
    default method, :func:`fetorsion.design.m53.run_m53_crank`) at the description's damping."""
    from fetorsion.design.crank_verdict import fillet_torque_amplitude
    from fetorsion.design.m53 import run_m53_crank
    from fetorsion.design.stress import fillet_cuts, fillets_of
    from fetorsion.fe.condensed import run_condensed
    from fetorsion.fe.cranksystem import build_system
    from fetorsion.lumped_model.parts import build_parts
    from fetorsion.response.coupled import condensed_setup
    from fetorsion.response.forced import solve_response
    from fetorsion.solid.mesh import mesh_crank

    fillets = fillets_of(crank, build_parts(crank, DEFAULT_WEB_METHOD))
    system = build_system(crank, mesh_size, mesh_crank(crank, mesh_size))
    cc = run_condensed(crank, system=system, cuts=fillet_cuts(crank, fillets))
    f_bearings = cc.modes("bearings").first_torsional()
    setup = condensed_setup(cc, "bearings", section_labels=[f.label for f in fillets])
    torque = fillet_torque_amplitude(setup, solve_response(setup, crank.dampers), fillets)
    m = run_m53_crank(crank, fillets, torque, setup.rpm, fe_scf=scf)
    g = m.governing
    fillet = min((a for a in m.locations if "fillet" in a.kind), key=lambda a: a.safety / a.required)
    return {"f1_bearings_hz": float(f_bearings), "governing": g.name, "safety": float(g.safety),
            "equivalent_stress_mpa": g.equivalent / 1e6, "rpm": float(g.torque_rpm),
            "worst_fillet": fillet.name, "worst_fillet_safety": float(fillet.safety),
            "worst_fillet_stress_mpa": fillet.equivalent / 1e6, "required": float(g.required),
            "damping_ratio": float(setup.zeta)}


def main(argv=None):
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.lumped_model.lumped import lumped
    from fetorsion.studies.calibration_fit import calibration_inputs, run_calibration
    from fetorsion.description.edit import with_values

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
    measured = args.measured_hz or [crank.measured_f1_hz]
    t0 = time.perf_counter()
    cal = run_calibration(crank, measured, inputs=args.inputs, method="both")
    inputs = calibration_inputs(crank, args.inputs)
    f1 = cal.posterior.frequencies_hz[:, 0]
    points = {f"posterior f1 {q:g} %": cal.posterior.samples[int(np.argmin(np.abs(f1 - np.percentile(f1, q))))]
              for q in QUANTILES}
    points["least squares"] = cal.lsq.values
    scf = verdict_scfs(crank)
    size = args.mesh_size * 1e-3
    rows = {"nominal": {"inputs": {i.name: i.nominal for i in inputs},
                        "f1_free_lumped_hz": float(lumped(crank, 17).frequencies_hz[0]), **engine_answers(crank, scf, size)}}
    for name, x in points.items():
        changes = {}
        for i, v in zip(inputs, x):
            changes.update(i.values(float(v)))
        v = with_values(crank, changes)
        rows[name] = {"inputs": {i.name: float(val) for i, val in zip(inputs, x)},
                      "f1_free_lumped_hz": float(lumped(v, 17).frequencies_hz[0]), **engine_answers(v, scf, size)}
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")),
               platform.processor())
    out = {"description": args.file, "measured_hz": measured, "inputs": args.inputs, "mesh_size_mm": args.mesh_size,
           "scf_source": scf.source, "identified": {r["input"]: r["identified"] for r in cal.input_rows()},
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
