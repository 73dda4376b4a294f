"""Lumped study throughput (issue 15: target >= 500 samples/s on this 2-core machine).

A Monte Carlo study of f1 (lumped 17 DOF, Carter webs) on the embedded LocalCluster, into a
fresh sample store, with the wall split into cluster start and the study itself; then the
same samples once more (all stored: the cost of resuming), and serially in this process
for comparison. Prints figures, asserts nothing.

    python benchmarks/bench_study.py [--crank geometry/peugeot_glx.toml] [--samples 10000] [--workers 2]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import fetorsion  # noqa: E402
from fetorsion.studies.runner import SampleStore, open_client  # noqa: E402
from fetorsion.studies.models import make_model  # noqa: E402
from fetorsion.studies.sampling import study_inputs  # noqa: E402
from fetorsion.studies.study import run_study  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--crank", default=str(ROOT / "geometry" / "peugeot_glx.toml"))
    ap.add_argument("--samples", type=int, default=10000)
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--serial", type=int, default=1000, help="samples of the serial comparison (0: none)")
    args = ap.parse_args(argv)
    crank = fetorsion.load(args.crank)
    inputs, _ = study_inputs(crank)
    model = make_model(crank, "lumped17")
    print(f"{crank.name}: {len(inputs)} inputs, lumped 17 DOF; load average before: {os.getloadavg()[0]:.2f}")
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        with open_client(workers=args.workers) as client:
            n_workers = len(client.scheduler_info()["workers"])
            t1 = time.perf_counter()
            res = run_study(model, inputs, "montecarlo", args.samples, client=client, store=SampleStore(Path(tmp) / "a"))
            t2 = time.perf_counter()
            again = run_study(model, inputs, "montecarlo", args.samples, client=client, store=SampleStore(Path(tmp) / "a"))
            t3 = time.perf_counter()
        print(f"local cluster of {n_workers} workers started in {t1 - t0:.1f} s")
        print(f"study: {len(res.X)} samples computed and stored in {t2 - t1:.2f} s: "
              f"{len(res.X) / (t2 - t1):.0f} samples/s (f1 5-95 %: {res.bands['f1']['p5']:.1f}-"
              f"{res.bands['f1']['p95']:.1f} Hz, {len(res.errors)} failed)")
        print(f"same study again, every sample stored: {t3 - t2:.2f} s ({again.summary.computed} computed)")
        if args.serial:
            t4 = time.perf_counter()
            run_study(model, inputs, "montecarlo", args.serial, seed=1, client=None, store=SampleStore(Path(tmp) / "b"),
                      progress=False)
            t5 = time.perf_counter()
            print(f"serial, this process: {args.serial} samples in {t5 - t4:.2f} s: {args.serial / (t5 - t4):.0f} samples/s")
    print(f"load average after: {os.getloadavg()[0]:.2f} (2 cores shared with other work)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
