"""``fetorsion calibrate``: the description's ``[uncertainty]`` inputs fitted to measured natural
frequencies, typed or fitted to measured FRFs; the calibrated description written as a new file."""

from __future__ import annotations

import sys
from pathlib import Path

from ..description.defaults import LUMPED17
from ..measured.uff import UnstatedUnit
from ..measured.reading import UFF_SUFFIXES, MeasuredOptions, read_measured
from .common import add_band_option, add_json_option, emit_json, load_description, save_plot
from .options import integer, real
from ..errors import FetorsionError


def _calibration_frequencies(args) -> list[float] | None:
    """The measured frequencies: typed (``--measured-hz``), or None when they come from the FRFs
    of ``--measured`` files (fitted after every other check)."""
    if args.measured_hz is not None:
        if args.band is not None:
            raise FetorsionError("--band goes with --measured (the FRFs' modes are fitted in it), not with --measured-hz")
        return list(args.measured_hz)
    for m in args.measured:
        if not Path(m).is_file():
            raise FetorsionError(f"--measured {m}: no such file")
        if Path(m).suffix.lower() not in UFF_SUFFIXES:
            raise FetorsionError(f"--measured {m}: give a universal file of FRFs ({', '.join(UFF_SUFFIXES)}); "
                                 "the modes fitted in --band (default the files' own) are the measured frequencies")
    if args.band is not None and not 0 <= args.band[0] < args.band[1]:
        raise FetorsionError(f"--band {args.band[0]:g} {args.band[1]:g}: give 0 <= LOW < HIGH (Hz)")
    return None


def check_calibrate_out(out: str, source: str, force: bool) -> None:
    """``--out``: a new .toml file, never the description itself; an existing one only with --force."""
    import os

    from ..io import check_writable_location

    p = Path(out)
    if p.suffix.lower() != ".toml":
        raise FetorsionError(f"--out {out}: the calibrated description is a .toml file")
    if p.is_dir():
        raise FetorsionError(f"--out {out}: is a folder; give a new file name")
    if p.exists() and Path(source).exists() and os.path.samefile(p, source):
        raise FetorsionError(f"--out {out}: is the description being calibrated; the calibrated one is written as "
                             "a new file, never over the original")
    if p.exists() and not force:
        raise FetorsionError(f"--out {out}: exists; give a new file name, or --force to replace it")
    check_writable_location(p, "--out")


def cmd_calibrate(args) -> int:
    from ..studies.calibrated import write_calibrated
    from ..studies.calibration_fit import calibration_inputs, check_ensemble, check_measured_hz, run_calibration

    # Everything that needs no model run first: the options, the files, the description.
    measured_hz = _calibration_frequencies(args)
    if not Path(args.file).is_file():
        raise FetorsionError(f"{args.file}: no such file")
    if args.out:
        check_calibrate_out(args.out, args.file, args.force)
    elif args.force:
        raise FetorsionError("--force replaces an existing --out file; give --out")
    crank = load_description(args.file)  # a crank description, a chain or a network: each may carry [uncertainty]
    inputs = calibration_inputs(crank, args.inputs)
    if args.method != "lsq":
        check_ensemble(len(inputs), args.walkers, args.steps, args.burn)
    if measured_hz is not None:
        check_measured_hz(measured_hz, args.sigma_hz, args.sigma_percent)
    else:
        from ..measured.modal import run_modal_fit

        try:
            measured = read_measured(args.measured, MeasuredOptions(band=None if args.band is None else tuple(args.band)))
        except UnstatedUnit as exc:
            raise FetorsionError(exc.stating("an FRF file whose records say their units")) from None
        if not measured.frfs:
            raise FetorsionError(f"--measured: {', '.join(args.measured)} hold no FRF to fit modes to")
        for line in measured.notes:
            print(f"fetorsion: warning: {line}", file=sys.stderr)
        band = measured.band
        measured_hz = sorted(run_modal_fit(measured.frfs, band).frequencies_hz)
        print(f"measured (fitted in {band[0]:g}-{band[1]:g} Hz): "
              f"{', '.join(f'{f:.2f}' for f in measured_hz)} Hz", file=sys.stderr)
    res = run_calibration(crank, measured_hz, args.sigma_hz, args.sigma_percent, args.inputs, args.model,
                          args.method, args.stiffness, args.walkers, args.steps, args.burn, args.seed, args.write_all)
    print(res.table(), file=sys.stderr if args.json == "-" else sys.stdout)
    emit_json(res.to_dict(), args.json)
    if args.plot:
        save_plot(res, args.plot)
    if args.out:
        changed = write_calibrated(res, args.out, force=args.force)
        print(f"calibrated description ({len(changed)} values changed): {args.out}", file=sys.stderr)
    return 0


def add_calibrate_parser(sub) -> None:
    from ..description.defaults import DEFAULT_WEB_METHOD
    from ..studies.calibration import (CALIBRATION_MODELS, CALIBRATION_STIFFNESS, DEFAULT_BURN, DEFAULT_SIGMA_PERCENT,
                                       DEFAULT_STEPS, DEFAULT_WALKERS, IDENTIFIED_RATIO, METHODS)

    cp = sub.add_parser("calibrate", help="fit the description's [uncertainty] inputs to measured natural frequencies: "
                        "regularised least squares and a Bayesian posterior (MCMC); the calibrated description "
                        "as a new file")
    cp.add_argument("file", help="crank description, chain or network file with an [uncertainty] table (.toml)")
    what = cp.add_mutually_exclusive_group(required=True)
    what.add_argument("--measured-hz", type=real(0.0, unit="Hz"), nargs="+", metavar="HZ",
                      help="measured natural frequencies (Hz): the lowest elastic torsional modes of the free-free "
                           "crank, ascending (matched by order to the model's)")
    what.add_argument("--measured", nargs="+", metavar="FILE",
                      help="universal files (.uff/.unv) of measured FRFs: their modes fitted in --band are the "
                           "measured frequencies")
    add_band_option(cp)
    sig = cp.add_mutually_exclusive_group()
    sig.add_argument("--sigma-hz", type=real(0.0, unit="Hz"), nargs="+", metavar="HZ",
                     help="standard deviation of the measured frequencies, measurement and model error (Hz): "
                          "one for all, or one each")
    sig.add_argument("--sigma-percent", type=real(0.0, 100.0, unit="%"), default=DEFAULT_SIGMA_PERCENT, metavar="P",
                     help="... or in %% of each frequency (default %(default)s: the lumped chain's difference "
                          "from the 3D FE)")
    cp.add_argument("--inputs", nargs="+", metavar="NAME",
                    help="[uncertainty] entries to calibrate (default all; the others stay as in the file)")
    cp.add_argument("--method", choices=METHODS, default="both",
                    help="lsq: regularised least squares; bayes: the MCMC posterior (emcee); both (default)")
    cp.add_argument("--model", choices=CALIBRATION_MODELS, default=LUMPED17, help="lumped chain (default %(default)s)")
    cp.add_argument("--stiffness", choices=CALIBRATION_STIFFNESS, default=DEFAULT_WEB_METHOD,
                    help="web stiffness method of the lumped model (default %(default)s; not an FE method, which "
                         "would mesh every variant)")
    cp.add_argument("--walkers", type=integer(2), metavar="N",
                    help=f"walkers of the ensemble (default {DEFAULT_WALKERS}, at least 2 per input plus 2)")
    cp.add_argument("--steps", type=integer(1), default=DEFAULT_STEPS, metavar="N",
                    help="steps of each walker kept (default %(default)s)")
    cp.add_argument("--burn", type=integer(0), default=DEFAULT_BURN, metavar="N",
                    help="steps of burn-in discarded first (default %(default)s)")
    cp.add_argument("--seed", type=integer(0, 2**32 - 1), default=0, help="seed of the MCMC (default %(default)s)")
    cp.add_argument("--out", metavar="NEW.toml", help="write the calibrated description to this NEW file (never over "
                    "the original): every changed value commented with its source")
    cp.add_argument("--force", action="store_true", help="replace an existing --out file (never the original)")
    cp.add_argument("--write-all", action="store_true",
                    help="--out changes every input the least squares moved, not only the identified ones "
                         "(without it: the identified ones, or every one moved where none is identified on its own)")
    cp.add_argument("--plot", metavar="PATH", help="figure of each input's prior, estimate and posterior "
                    "(.png, .pdf, .svg)")
    add_json_option(cp)
    cp.set_defaults(func=cmd_calibrate)
    cp.epilog = (f"An input is identified when the data's information at the least-squares estimate brings its "
                 f"(Laplace) posterior standard deviation below {IDENTIFIED_RATIO:g} of its prior's: a deterministic "
                 "rule, the same for every seed; the sampled posterior's width is reported beside it. --out writes "
                 "the identified inputs (least squares); where none is identified on its own, every input the "
                 "calibration moved, at its posterior median, each change commented; every input the least squares "
                 "moved with --write-all.")
