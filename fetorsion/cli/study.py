"""``fetorsion study``: an uncertainty or sensitivity study of a crank on a Dask cluster.

Every option and the description are checked before the cluster starts; the samples are
stored as they finish (``--store``), so an interrupted study resumes when the same command
is run again, and the report folder (``--out``) is written atomically at the end.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from ..description.defaults import CHECK_MESH_SIZE, DEFAULT_STUDY_SAMPLES, DEFAULT_WEB_METHOD, LUMPED17
from ..errors import FetorsionError
from ..studies.runner import (SCHEDULER_ENV, STORE_ENV, STORE_MAX_ENV, check_scheduler, check_store, default_store,
                              open_store, scheduler_address, store_max_bytes)
from ..studies.models import FE_LEFT_OUT, MODEL_CHOICES, make_model
from ..studies.sampling import METHODS, check_samples, runs_for, study_inputs
from ..studies.study import run_crank_study, write_study_folder
from ..webs.methods import WEB_METHODS
from .common import check_mesh_size, load_crank
from .options import MM, integer, millimetres



def _names(option: str):
    def parse(text: str) -> list[str]:
        names = [t.strip() for t in text.split(",")]
        if not all(names):
            raise argparse.ArgumentTypeError(f"{text!r}: give comma-separated names, e.g. f1,f2")
        return names

    return parse


def add_parser(sub) -> None:
    """Register ``study`` on an argparse subparsers object."""
    sp = sub.add_parser("study", help="Monte Carlo, Sobol', Morris or grid study of a crank's [uncertainty] inputs, "
                                      "on a Dask cluster (local by default)")
    sp.add_argument("file", help="crank description with an [uncertainty] table (.toml)")
    sp.add_argument("--method", choices=METHODS, default="montecarlo", help="sampling and analysis (default %(default)s)")
    sp.add_argument("--samples", type=integer(1, 10_000_000), metavar="N",
                    help="montecarlo: runs; sobol: base samples, a power of 2 (N·(inputs+2) runs); morris: "
                         "trajectories (N·(inputs+1) runs); grid: levels per input. Default: "
                         + ", ".join(f"{m} {n}" for m, n in DEFAULT_STUDY_SAMPLES.items()))
    sp.add_argument("--model", choices=MODEL_CHOICES, default=LUMPED17,
                    help="lumpedN: the N-DOF lumped chain; fe: 3D FE without fillets and drillings at "
                         "--mesh-size (default %(default)s)")
    sp.add_argument("--outputs", type=_names("--outputs"), default=["f1"],
                    help="comma-separated: f1, f2, f3, severity (lumped) or f1, f2 (fe); default f1")
    sp.add_argument("--inputs", type=_names("--inputs"), help="only these [uncertainty] entries (others nominal)")
    sp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD,
                    help="web stiffness method of the lumped model (default %(default)s)")
    sp.add_argument("--mesh-size", type=millimetres(), default=CHECK_MESH_SIZE, metavar="MM",
                    help=f"--model fe: global element size in mm (default {CHECK_MESH_SIZE / MM:g})")
    sp.add_argument("--scheduler", metavar="ADDRESS",
                    help=f"an existing Dask scheduler, e.g. tcp://host:8786 (default ${SCHEDULER_ENV}, "
                         "else a local cluster)")
    sp.add_argument("--workers", type=integer(1, 4096), metavar="N",
                    help="worker processes of the local cluster (default one per core)")
    sp.add_argument("--seed", type=integer(0, 2**32 - 1), default=0, help="seed of the sampling (default %(default)s)")
    sp.add_argument("--batch", type=integer(1, 100_000), metavar="N",
                    help="samples per task (default: 1 for fe, else about 8 tasks per worker)")
    sp.add_argument("--out", metavar="DIR", help="report folder (default out/<file>-<method>)")
    sp.add_argument("--store", metavar="DIR",
                    help="where each sample's result is kept (default $FETORSION_STORE, else ~/.cache/fetorsion/samples)")
    sp.add_argument("--retry-failed", action="store_true", help="compute again the samples stored with an error")
    sp.add_argument("--force", action="store_true", help="replace --out even if it is not an earlier fetorsion report")
    sp.set_defaults(func=cmd_study)

    tp = sub.add_parser("store", help="where the store is (the studies' samples, the condensed cranks, the "
                        "stress-recovery fields, the runs' FE modes and verdicts), how full; --clear empties it")
    tp.add_argument("--store", metavar="DIR", help=f"the store's folder (default ${STORE_ENV}, else "
                                                   "~/.cache/fetorsion/samples)")
    tp.add_argument("--clear", action="store_true", help="remove every stored sample, condensed crank, "
                    "stress-recovery field and run section")
    tp.set_defaults(func=cmd_store)


def cmd_store(args) -> int:
    """Print the store's location, sample count and size against its bound; empty it with --clear."""
    folder = Path(args.store) if args.store else default_store()
    if os.path.lexists(folder) and not folder.is_dir():
        raise FetorsionError(f"--store {folder}: exists and is not a folder")
    store_max_bytes()  # a bad $FETORSION_STORE_MAX_MB is named before anything is touched
    from ..app.run_store import FOLDER as RUNS_FOLDER
    from ..design.recovery import FOLDER as RECOVERY_FOLDER
    from ..fe.store import clear_condensed, condensed_store_info

    store = open_store(folder)
    if args.clear:
        n = store.clear()
        print(f"removed {n} samples from {store.file}")
        n = clear_condensed(folder)
        print(f"removed {n} condensed cranks from {folder / 'condensed'}")
        n = clear_condensed(folder, RECOVERY_FOLDER)
        print(f"removed {n} stress-recovery fields from {folder / RECOVERY_FOLDER}")
        n = clear_condensed(folder, RUNS_FOLDER)
        print(f"removed {n} run sections (FE modes, fatigue verdicts) from {folder / RUNS_FOLDER}")
    print(store.describe().replace("sample store ", "", 1) + f" (the bound: ${STORE_MAX_ENV})")
    c = condensed_store_info(folder)
    print(f"{c['folder']}: {c['cranks']} condensed cranks, {c['bytes'] / 2**20:.1f} MiB of at most "
          f"{c['max_bytes'] / 2**20:.0f} MiB (a quarter of the bound)")
    r = condensed_store_info(folder, RECOVERY_FOLDER)
    print(f"{r['folder']}: {r['cranks']} stress-recovery fields (throws and drilled bars of the fe fatigue path), "
          f"{r['bytes'] / 2**20:.1f} MiB of at most {r['max_bytes'] / 2**20:.0f} MiB (a quarter of the bound)")
    s = condensed_store_info(folder, RUNS_FOLDER)
    print(f"{s['folder']}: {s['cranks']} run sections (the FE step's modes and pictures, fatigue verdicts), "
          f"{s['bytes'] / 2**20:.1f} MiB of at most {s['max_bytes'] / 2**20:.0f} MiB (a quarter of the bound)")
    return 0


def cmd_study(args) -> int:
    from ..io import check_report_folder

    # Options that need no file first, then the description, then what needs both.
    if args.scheduler and args.workers:
        raise FetorsionError("--workers sizes the local cluster; an existing cluster (--scheduler) has its own workers")
    address, where = scheduler_address(args.scheduler)
    if address:
        check_scheduler(address, where)
    n = args.samples or DEFAULT_STUDY_SAMPLES[args.method]
    out = Path(args.out) if args.out else Path("out") / f"{Path(args.file).stem}-{args.method}"
    check_report_folder(out, "--out", force=args.force, inputs=[args.file], force_option="--force")
    store_dir = Path(args.store) if args.store else default_store()
    check_store(store_dir, "--store" if args.store else "the sample store")
    store_max_bytes()
    crank = load_crank(args.file, "an [uncertainty] table")
    if not crank.uncertainty:
        raise FetorsionError(f"{args.file}: the description has no [uncertainty] table")
    model = make_model(crank, args.model, args.outputs, args.stiffness, args.mesh_size)
    inputs, held = study_inputs(crank, args.inputs, FE_LEFT_OUT if args.model == "fe" else ())
    if not inputs:
        raise FetorsionError(f"--inputs: none of {', '.join(args.inputs or [])} can be sampled by --model {args.model} "
                             f"({', '.join(FE_LEFT_OUT)} are left out of its variant)")
    check_samples(args.method, n, len(inputs))
    if args.model == "fe":
        check_mesh_size(crank, args.mesh_size, "modal")
    print(f"[fetorsion] {crank.name}: {args.method} study of {len(inputs)} inputs, "
          f"{runs_for(args.method, n, len(inputs))} runs of {model.label}", file=sys.stderr, flush=True)
    store = open_store(store_dir)
    print(f"[fetorsion] {store.describe()} ('fetorsion store --clear' empties it)", file=sys.stderr, flush=True)
    try:
        res = run_crank_study(crank, args.method, n, args.model, args.outputs, args.inputs, seed=args.seed,
                              stiffness=args.stiffness, mesh_size=args.mesh_size, scheduler=address,
                              workers=args.workers, store=store, batch_size=args.batch,
                              retry_failed=args.retry_failed)
    except KeyboardInterrupt:
        print(f"\nfetorsion: interrupted; the finished samples are kept in {store_dir}: the same command resumes "
              "the study", file=sys.stderr)
        return 130
    write_study_folder(res, out, force=args.force, inputs=[args.file])
    print(res.table())
    print(f"report folder -> {out}")
    return 0
