"""Command line: ``fetorsion <command> ...``. User mistakes print one clear message, exit 2."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from . import mechanics as cli_mechanics
from . import study as cli_study
from .options import MM, integer, millimetres, option_of, read_compare_csv, real
from ..description.crank import load
from ..description.model import Chain
from ..description.plausibility import plausibility_warnings
from ..errors import FetorsionError, ParameterError
from ..solid.isolate import call_isolated
from ..io import check_output_file, check_report_folder, save_figure_atomic, write_text_atomic
from ..lumped_model.lumped import MODES_SHOWN, PARTITIONS, lumped
from ..lumped_model.parts import build_parts
from ..response.forced import COMPARE_UNITS
from ..description.defaults import (DEFAULT_DAMPING_RATIO, DEFAULT_INERTIA_RATIO, DEFAULT_MESH_SIZE, DEFAULT_MODES,
                                    DEFAULT_PARTITION, DEFAULT_SPEED_STEPS, DEFAULT_WEB_METHOD)
from ..webs.methods import WEB_METHODS
from ..description.model import DAMPER_STATIONS, DAMPER_TYPES
from ..design.dampers import OBJECTIVES

PLOT_FORMATS = (".png", ".pdf", ".svg")
SUPPORT_CHOICES = ("free", "bearings")


def _dof_list(text: str) -> list[int]:
    if text == "all":
        return list(PARTITIONS)
    try:
        values = [int(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--dof {text!r}: give 'all' or some of {PARTITIONS}") from None
    bad = [v for v in values if v not in PARTITIONS]
    if bad:
        raise argparse.ArgumentTypeError(f"--dof {bad[0]} is not a partition; choose from {PARTITIONS} or 'all'")
    return values


def _emit_json(payload: dict, target: str | None) -> None:
    if target is None:
        return
    text = json.dumps(payload, indent=2) + "\n"
    if target == "-":
        sys.stdout.write(text)
    else:
        write_text_atomic(target, text)


def load_description(path: str):
    """Read a description; print a warning line for each implausible dimension."""
    model = load(path)
    if not isinstance(model, Chain):
        for line in plausibility_warnings(model):
            print(f"fetorsion: warning: {path}: {line}", file=sys.stderr)
    return model


def cmd_lumped(args) -> int:
    model = load_description(args.file)
    results = [lumped(model)] if isinstance(model, Chain) else [lumped(model, d, args.stiffness) for d in args.dof]
    out = sys.stderr if args.json == "-" else sys.stdout
    print(format_lumped_table(results), file=out)
    payload = {"file": args.file, "models": [r.to_dict() for r in results]}
    if not isinstance(model, Chain):
        payload.update(stiffness_method=args.stiffness, parts=parts_table(build_parts(model, args.stiffness)),
                       web_inertia="analytic web outline (fetorsion.solid.outline), no fillets", description=model.raw)
    _emit_json(payload, args.json)
    return 0


def parts_table(chain) -> list[dict]:
    """The crank parts with their equivalent lengths, stiffnesses and inertias (SI)."""
    return [{"part": p.label, "x0_m": p.x0, "x1_m": p.x1, "equivalent_length_m": p.equivalent_length,
             "stiffness_nm_per_rad": 1.0 / p.compliance, "inertia_kgm2": p.inertia,
             "attached_inertia_kgm2": p.attached_inertia} for p in chain.parts]


def cmd_mesh(args) -> int:
    outputs = args.output or []
    if not outputs and args.png is None:
        raise FetorsionError("mesh: give -o OUT (.msh, .vtu, .inp) and/or --png OUT.png")
    crank = _load_crank(args.file, "a geometry to mesh")
    if outputs:
        check_mesh_size(crank, args.mesh_size, "mesh", args.purpose, args.fillet_size)
    print(call_isolated(_mesh_job, crank, args.mesh_size, outputs, args.fillet_size, args.purpose, args.modes,
                        what=f"{crank.name}: Gmsh, at --mesh-size {args.mesh_size / MM:g} mm"))
    if args.png is not None:
        from ..report.render import render_solid

        print(f"picture -> {render_solid(crank, args.png)}")
    return 0


def _mesh_job(crank, size: float, outputs: list[str], fillet_size: float | None, purpose: str, modes: int) -> str:
    """Mass table, and one mesh written to every file of ``outputs``: one Gmsh session (in a
    child process)."""
    from ..solid.geometry import build_solid, gmsh_session, solid_mass_properties
    from ..solid.mesh import mesh_solid, write_mesh

    with gmsh_session():
        solid = build_solid(crank)
        total, parts = solid_mass_properties(solid, crank.material.density)
        lines = [format_mass_table(crank.name, total, parts)]
        if outputs:
            mesh = mesh_solid(solid, crank, size, fillet_size, purpose)
            q = mesh.quality
            for out in outputs:  # one mesh, several formats: the same elements in each file
                write_mesh(mesh, out, modes=modes)
            lines.append(f"mesh ({purpose}): {q.n_tets} curved 10-node tets, {q.n_nodes} nodes, size "
                         f"{q.size / MM:g} mm ({q.fillet_size / MM:g} mm at fillets and drillings, {q.straightened} "
                         f"folded elements straightened), minimum SICN {q.min_sicn:.2g}, {q.seconds:.1f} s -> "
                         f"{', '.join(outputs)}")
    return "\n".join(lines)


def check_mesh_size(crank, mesh_size: float, job: str, purpose: str = "modal", fillet_size: float | None = None,
                    option: str = "--mesh-size") -> None:
    """Refuse a mesh size whose mesh (``job`` 'mesh') or FE modal job ('modal') would not fit in
    memory, naming the option and the estimate; print the estimate when the job is long."""
    from ..solid.mesh import available_memory, estimate_mesh

    est = estimate_mesh(crank, mesh_size, fillet_size, purpose)
    mesh_size_mm = mesh_size / MM
    need = est.mesh_bytes if job == "mesh" else est.mesh_bytes + est.modal_bytes
    have = available_memory()
    gib = 2.0**30
    what = f"about {est.tets:,} tetrahedra (±25 %) and {need / gib:.1f} GiB of memory"
    if need > have:
        raise FetorsionError(f"{option} {mesh_size_mm:g}: the {job} job would need {what}; this machine has "
                             f"{have / gib:.1f} GiB available. Give a larger {option}")
    if est.tets > 150_000:
        print(f"fetorsion: {option} {mesh_size_mm:g} mm: expect {what} (available {have / gib:.1f} GiB); "
              f"meshing alone takes about {est.mesh_seconds:.0f} s", file=sys.stderr)


def cmd_modal(args) -> int:
    from ..fe.crankfe import REFINE_RATIO, run_modal, run_refinement
    from ..solid.mesh import read_mesh

    if args.refine and args.mesh:
        raise FetorsionError("--refine meshes the crank three times; it cannot use --mesh")
    crank = _load_crank(args.file, "geometry")
    if args.support == "bearings" and (args.refine or args.html):
        raise FetorsionError("--support bearings: the modes in bearings come from the condensed crank; "
                             "--refine and --html work with --support free")
    if not args.mesh:
        check_mesh_size(crank, args.mesh_size * (REFINE_RATIO**2 if args.refine else 1.0), "modal", args.purpose,
                        None if args.fillet_size is None else args.fillet_size * (REFINE_RATIO**2 if args.refine else 1.0))
    if args.support == "bearings":
        cc = _condensed(crank, args.mesh_size, read_mesh(args.mesh, crank) if args.mesh else None)
        return _report(cc, f"{crank.name}\n{cc.table()}", args)
    refinement = None
    if args.refine:
        runs, refinement = run_refinement(crank, args.mesh_size, args.modes, args.fillet_size, args.purpose)
        fe = runs[-1]
    else:
        mesh = read_mesh(args.mesh, crank) if args.mesh else None
        fe = run_modal(crank, args.mesh_size, args.modes, args.fillet_size, mesh=mesh, purpose=args.purpose)
    res = fe
    out = sys.stderr if args.json == "-" else sys.stdout
    print(f"{crank.name}: {res.table()}", file=out)
    payload = {"file": args.file, **res.to_dict()}
    torsional = res.of_kind("torsional")
    payload["first_torsional_hz"] = float(torsional[0]) if len(torsional) else None
    print(f"first torsional: {payload['first_torsional_hz']} Hz", file=out)
    if refinement:
        payload["refinement"] = refinement
        print(f"refinement: f1 = {refinement['first_torsional_hz']} Hz at {refinement['dofs']} DOF -> "
              f"extrapolated {refinement['extrapolated']:.1f} Hz, error estimate {refinement['error_estimate']:.1f} Hz",
              file=out)
    _emit_json(payload, args.json)
    if args.plot:
        _save_plot(res, args.plot)
    if args.html:
        from ..report.html import mode_view, page

        picks = [j for j, k in enumerate(res.kinds) if k in ("torsional", "bending")][:6] or [0]
        view = mode_view(res.mesh.nodes, res.mesh.tets, [res.shapes[j] for j in picks],
                         [f"mode {j + 1}: {res.frequencies_hz[j]:.1f} Hz, {res.kinds[j]}" for j in picks], "modes")
        text = f"# {crank.name}: free-free FE modes\n\n![](modes.png)\n\n```\n{res.table()}\n```\n"
        write_text_atomic(args.html, page(crank.name, text, {"modes.png": view}, Path(args.html).parent))
    return 0


def cmd_condense(args) -> int:
    from ..fe.condensed import run_condensed, save_condensed

    if args.with_shapes and not args.npz:
        raise FetorsionError("--with-shapes is saved in the --npz file; give --npz PATH")
    crank = _load_crank(args.file, "geometry")
    check_mesh_size(crank, args.mesh_size, "modal")
    cc = run_condensed(crank, args.mesh_size, keep_basis=args.with_shapes)
    _report(cc, f"{crank.name}\n{cc.table()}", args)
    if args.npz:
        save_condensed(cc, args.npz)
        print(f"condensed crank -> {args.npz}", file=sys.stderr if args.json == "-" else sys.stdout)
    return 0


def format_mass_table(name: str, total, parts: dict) -> str:
    """Plain-text table of mass (kg) and polar inertia about the crank axis (kg·m²) per part."""
    lines = [f"{name}: mass properties of the solid", f"{'part':>10} {'mass [kg]':>10} {'J [kg m2]':>12}"]
    lines += [f"{n:>10} {b.mass:10.4f} {b.polar_inertia:12.4e}" for n, b in parts.items()]
    lines.append(f"{'total':>10} {total.mass:10.4f} {total.polar_inertia:12.4e}")
    return "\n".join(lines)


def format_lumped_table(results, modes: int = MODES_SHOWN) -> str:
    """Plain-text table of the first ``modes`` elastic frequencies of each model."""
    name = results[0].name
    head = f"{'model':>8} " + " ".join(f"{'f' + str(j + 1) + ' [Hz]':>10}" for j in range(modes))
    lines = [f"{name}: free-free torsional natural frequencies", head, "-" * len(head)]
    for r in results:
        tag = f"{r.dof} DOF" if r.partition else "chain"
        freqs = " ".join(f"{f:10.1f}" for f in r.frequencies_hz[:modes])
        lines.append(f"{tag:>8} {freqs}")
    return "\n".join(lines)


def _save_plot(obj, path: str) -> None:
    """Draw ``obj.plot()`` and save it atomically to ``path`` (format from the extension)."""
    import matplotlib

    matplotlib.use("Agg")
    out = obj.plot()
    save_figure_atomic(out.figure if hasattr(out, "figure") else out, path, close=True, dpi=130)


def _partition_of(source: str) -> int:
    return int(source.removeprefix("lumped"))


def _load_crank(path: str, needs: str):
    crank = load_description(path)
    if isinstance(crank, Chain):
        raise FetorsionError(f"{path}: this command needs a crank description with {needs}, not a chain file")
    return crank


def _report(res, text: str, args) -> int:
    """Print ``text`` (to stderr when JSON takes stdout), then write the JSON and the plot."""
    print(text, file=sys.stderr if args.json == "-" else sys.stdout)
    _emit_json(res.to_dict(), args.json)
    if args.plot:
        _save_plot(res, args.plot)
    return 0


def _load_excited(path: str, source: str):
    """A crank description or chain file with an [excitation] table (a chain: lumped modes only)."""
    model = load_description(path)
    if isinstance(model, Chain) and source in ("fe", "condensed"):
        raise FetorsionError(f"--source {source}: {path} is a chain file, it has no geometry to mesh; leave --source out")
    if model.excitation is None:
        raise FetorsionError(f"{path}: the description has no [excitation] table"
                             + (" (a chain file needs [engine], [excitation] and chain.cylinder_stations)"
                                if isinstance(model, Chain) else ""))
    return model


def _condensed(crank, mesh_size: float, mesh=None):
    """The condensed crank (meshing in this process: the FE job needs the mesh's arrays)."""
    from ..fe.condensed import run_condensed

    return run_condensed(crank, mesh_size, mesh=mesh)


def _stiffness_for(args) -> str:
    """The web method in the support condition asked for (``fe`` in bearings is ``fe-held``)."""
    from ..webs.methods import IN_BEARINGS

    return IN_BEARINGS.get(args.stiffness, args.stiffness) if args.support == "bearings" else args.stiffness


def cmd_campbell(args) -> int:
    from ..excitation.campbell import lumped_modes, run_campbell

    crank = _load_excited(args.file, args.source)
    if not args.source.startswith("lumped") and getattr(crank, "dampers", ()):
        print(f"fetorsion: warning: {args.file}: the FE modes are the crank's without its [[dampers]] "
              "(lumped sources and 'response --source condensed' include them)", file=sys.stderr)
    if args.source == "condensed" or (args.source == "fe" and args.support == "bearings"):
        check_mesh_size(crank, args.mesh_size, "modal")
        modes = _condensed(crank, args.mesh_size).torsional_modes(args.support, args.modes)
    elif args.source == "fe":
        from ..fe.crankfe import run_modal

        check_mesh_size(crank, args.mesh_size, "modal")

        modes = run_modal(crank, args.mesh_size, modes=DEFAULT_MODES).torsional_modes(args.modes)
    else:  # with [[dampers]], run_campbell builds the damped lumped modes itself
        modes = None if crank.dampers else lumped_modes(crank, _partition_of(args.source), _stiffness_for(args))
    res = run_campbell(crank, modes, orders=args.orders, speed_range=args.speed_range, n_modes=args.modes,
                       damping_ratio=args.damping,
                       partition=_partition_of(args.source) if args.source.startswith("lumped") else DEFAULT_PARTITION,
                       web_method=_stiffness_for(args))
    head = (f"{res.name}: crossings inside {res.speed_range_rpm[0]:.0f}-{res.speed_range_rpm[1]:.0f} rpm, "
            f"most severe first ({res.source})")
    _report(res, head + "\n" + res.table(), args)
    if args.html:
        from ..report.html import campbell_figure, page

        text = f"# {res.name}: Campbell diagram\n\n![](campbell.png)\n\n```\n{head}\n{res.table()}\n```\n"
        write_text_atomic(args.html, page(res.name, text, {"campbell.png": campbell_figure(res, "campbell")},
                                          Path(args.html).parent))
    return 0


def cmd_response(args) -> int:
    from ..response.forced import run_response

    if args.source == "fe":
        raise FetorsionError("--source fe: the forced response uses a lumped model or the condensed crank; "
                             "choose --source lumpedN or condensed")
    crank = _load_excited(args.file, args.source)
    rpm = np.linspace(*(args.speed_range or crank.excitation.speed_range), args.steps)
    if args.source == "condensed":
        from ..response.coupled import run_coupled_response

        if args.compare is not None:
            raise FetorsionError("--compare works with a lumped source (its section torques); "
                                 "leave --source condensed out")
        if args.misfire is not None:
            raise FetorsionError("--misfire works with a lumped source; leave --source condensed out")
        check_mesh_size(crank, args.mesh_size, "modal")
        res = run_coupled_response(_condensed(crank, args.mesh_size), args.support, rpm=rpm, orders=args.orders,
                                   damping_ratio=args.damping)
        return _report(res, res.table(), args)
    if args.compare_section is not None:  # checked on the model's springs before the response is computed
        springs = len(lumped(crank, _partition_of(args.source), args.stiffness).stiffnesses_nm_per_rad)
        if args.compare_section > springs:
            raise FetorsionError(f"--compare-section {args.compare_section}: the model has {springs} shaft sections")
    if args.misfire is not None and args.misfire > crank.engine.cylinders:
        raise FetorsionError(f"--misfire {args.misfire}: the engine has cylinders 1..{crank.engine.cylinders}")
    if args.misfire is not None and crank.excitation.pressure_curve is not None:
        raise FetorsionError(f"--misfire: {args.file} gives a measured pressure_csv; the motored cycle of a misfiring "
                             "cylinder needs the synthetic cycle (compression_ratio)")
    res = run_response(crank, _partition_of(args.source), rpm=rpm, orders=args.orders, damping_ratio=args.damping,
                       web_method=_stiffness_for(args), misfire=None if args.misfire is None else args.misfire - 1)
    if args.compare is not None:
        from ..response.forced import compare_curve

        rpm_c, value, name, unit = args.compare_curve
        compare_curve(res, rpm_c, value, name, unit,
                      None if args.compare_section is None else args.compare_section - 1)
    return _report(res, res.table(), args)


def cmd_damper(args) -> int:
    from ..design.dampers import run_damper

    if args.source in ("fe", "condensed"):
        raise FetorsionError(f"--source {args.source}: the damper is tuned on a lumped model; choose --source lumpedN")
    crank = _load_excited(args.file, args.source)
    if args.objective == "stress" and isinstance(crank, Chain):
        raise FetorsionError(f"--objective stress: {args.file} is a chain file, it has no shaft sections; "
                             "use --objective twist")
    if args.objective == "stress" and not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
        raise FetorsionError(f"--objective stress: {args.file} has no fillet radii (a sharp corner has no finite "
                             "SCF); give [fillets] or use --objective twist")
    rpm = np.linspace(*(args.speed_range or crank.excitation.speed_range), args.steps)
    res = run_damper(crank, args.type, args.inertia_ratio, args.optimise, args.objective, args.at, args.hub_inertia,
                     rpm=rpm, partition=_partition_of(args.source), orders=args.orders, damping_ratio=args.damping,
                     web_method=_stiffness_for(args))
    return _report(res, res.table(), args)


def cmd_sensitivity(args) -> int:
    from ..studies.sensitivity import run_sensitivity

    crank = _load_crank(args.file, "[uncertainty]")
    if not crank.uncertainty:
        raise FetorsionError(f"{args.file}: the description has no [uncertainty] table")
    res = run_sensitivity(crank, args.dof, args.stiffness)
    return _report(res, res.table(), args)


REFERENCE_CRANKS = ("renault21", "peugeot_glx")


def _geometry_folder():
    """``geometry/`` in the working folder, else beside the package (a source checkout)."""
    from pathlib import Path

    import os

    for folder in (Path("geometry"), Path(__file__).resolve().parents[1] / "geometry"):
        if (folder / f"{REFERENCE_CRANKS[0]}.toml").exists():
            rel = os.path.relpath(folder)
            return Path(rel) if not rel.startswith("..") else folder
    raise FetorsionError("no FILE given and no geometry/ folder with the reference cranks found; give FILE")


def run_jobs(args) -> list[tuple[Path, Path]]:
    """(description, report folder) of each crank ``run`` will do."""
    if args.all:
        if args.file:
            raise FetorsionError("--all runs both reference cranks; it takes no FILE")
        folder = _geometry_folder()
        return [(folder / f"{name}.toml", Path(args.out or "results") / name) for name in REFERENCE_CRANKS]
    file = Path(args.file) if args.file else _geometry_folder() / f"{REFERENCE_CRANKS[0]}.toml"
    return [(file, Path(args.out) if args.out else Path("out") / file.stem)]


def cmd_run(args) -> int:
    from ..app.run import FAST_STEPS, run

    jobs = run_jobs(args)
    for file, out in jobs:  # every destination and description is checked before any work
        check_report_folder(out, "--out", force=args.force, inputs=[file], force_option="--force")
        crank = load_description(str(file))
        if not args.no_fe and not isinstance(crank, Chain):  # a chain has no geometry: no FE step
            check_mesh_size(crank, args.mesh_size, "modal")
    options = {"mesh_size": args.mesh_size, "support": args.support, "inertia_ratio": args.inertia_ratio}
    for file, out in jobs:
        folder = run(file, out, options={**options, "html": not args.no_html}, force=args.force,
                     **({"steps": FAST_STEPS} if args.no_fe else {}))
        print(f"report: {folder / 'report.md'}")
    return 0


def _orders(text: str) -> list[float]:
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--orders {text!r}: give comma-separated numbers, e.g. 0.5,1,1.5") from None
    if any(not (math.isfinite(v) and 0 < v <= 100) for v in values):
        raise argparse.ArgumentTypeError(f"--orders {text!r}: orders must be > 0 and <= 100")
    return values


def _add_excitation_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", help="crank description or chain file with an [excitation] table (.toml)")
    p.add_argument("--source", default="lumped17", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe", "condensed"],
                   help="which model gives the modes (default %(default)s; fe: campbell only; condensed: the 3D FE "
                        "crank condensed to its journal and pin centres, torsion and bending coupled)")
    p.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings",
                   help="the crank in its main bearings (default, as it runs) or free-free (as on a modal test "
                        "bench); lumped: the fe web method becomes fe-held")
    p.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    p.add_argument("--speed-range", nargs=2, type=real(0.0, unit="rpm"), metavar=("LOW", "HIGH"),
                   help="rpm, 0 < LOW < HIGH")
    p.add_argument("--orders", type=_orders, help="comma-separated orders (default 0.5 ... 12 for a 4-stroke)")
    p.add_argument("--damping", type=real(0.0, 1.0), help=f"modal damping ratio, 0 < ζ < 1 (default from the file, else {DEFAULT_DAMPING_RATIO:g})")
    p.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    p.add_argument("--plot", metavar="PATH", help="save the plot (.png, .pdf, .svg)")


def _add_purpose_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--purpose", choices=("modal", "stress"), default="modal",
                   help="what the mesh is for (default %(default)s): modal, the sizes the frequency convergence "
                        "study chose (docs/modal-mesh.md); stress, fillet elements of the fillet radius")
    p.add_argument("--fillet-size", type=millimetres(), metavar="MM",
                   help="element size at fillets and drillings in mm (default from --purpose)")


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="fetorsion", description="Torsional vibration analysis of engine crankshafts.")
    sub = p.add_subparsers(dest="command", required=True)

    lp = sub.add_parser("lumped", help="BICERA-style equivalent-length lumped models (5/6/17/19/21 DOF)")
    lp.add_argument("file", help="crank description or chain file (.toml)")
    lp.add_argument("--dof", type=_dof_list, default=[DEFAULT_PARTITION], help="partition(s): 5, 6, 17, 19, 21, a list, or 'all'")
    lp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD,
                    help="web stiffness method (default %(default)s)")
    lp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    lp.set_defaults(func=cmd_lumped)

    cp = sub.add_parser("campbell", help="Campbell diagram: crossings of modes and orders, with severity")
    _add_excitation_options(cp)
    cp.add_argument("--modes", type=integer(1, 50), default=3, help="number of lowest modes (default %(default)s)")
    cp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size for --source fe (default {DEFAULT_MESH_SIZE / MM:g})")
    cp.add_argument("--html", metavar="PATH", help="write the interactive Campbell diagram as a web page (.html)")
    cp.set_defaults(func=cmd_campbell)

    dp = sub.add_parser("damper", help="torsional damper: Den Hartog start, optimised on the whole crank")
    _add_excitation_options(dp)
    dp.add_argument("--type", choices=DAMPER_TYPES, default="rubber", help="damper type (default %(default)s)")
    dp.add_argument("--inertia-ratio", type=real(0.0, 2.0), default=DEFAULT_INERTIA_RATIO, metavar="MU",
                    help="ring inertia over the damped mode's equivalent inertia at the station, 0 < MU < 2 "
                         "(default %(default)s)")
    dp.add_argument("--optimise", action="store_true", help="optimise stiffness and damping on the whole crank "
                    "over the speed range after the Den Hartog start (ring inertia held)")
    dp.add_argument("--objective", choices=OBJECTIVES, default="stress",
                    help="what the optimiser minimises: the largest fillet shear stress or the pulley twist")
    dp.add_argument("--at", choices=DAMPER_STATIONS, default="front", help="pulley end (front) or flywheel side")
    dp.add_argument("--hub-inertia", type=real(0.0, 10.0, low_open=False, unit="kg m^2"), default=0.0,
                    metavar="KGM2", help="hub or housing inertia, kg m^2 (default 0)")
    dp.add_argument("--steps", type=integer(2, 2000), default=100, help="speeds in the range (default %(default)s)")
    dp.set_defaults(func=cmd_damper)

    rp = sub.add_parser("response", help="forced torsional response of a lumped model versus speed")
    _add_excitation_options(rp)
    rp.add_argument("--steps", type=integer(2, 100_000), default=DEFAULT_SPEED_STEPS, help="speeds in the range (default %(default)s)")
    rp.add_argument("--misfire", type=integer(1), metavar="CYL",
                    help="cylinder CYL (1-based) does not fire: compression and expansion only")
    rp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size for --source condensed (default {DEFAULT_MESH_SIZE / MM:g})")
    rp.add_argument("--compare", metavar="CSV", help="a published or measured curve, rows 'rpm, value' ('#' lines: "
                    "comments, '# name = ...' and '# unit = ...' read), drawn over the response; the table gives "
                    "the difference at its peak")
    rp.add_argument("--compare-name", metavar="TEXT", help="what the --compare curve is (default the CSV's '# name')")
    rp.add_argument("--compare-unit", choices=sorted(COMPARE_UNITS),
                    help="its unit: a torque is compared with a section's torque, an angle with the pulley angle "
                         "(default the CSV's '# unit')")
    rp.add_argument("--compare-section", type=integer(1), metavar="N",
                    help="1-based shaft section (spring) whose torque is compared (default the most loaded)")
    rp.set_defaults(func=cmd_response)

    sp = sub.add_parser("sensitivity", help="f1 against each reconstructed input, and the f1 band")
    sp.add_argument("file", help="crank description with an [uncertainty] table (.toml)")
    sp.add_argument("--dof", type=int, choices=PARTITIONS, default=DEFAULT_PARTITION)
    sp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    sp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    sp.add_argument("--plot", metavar="PATH", help="save the tornado chart (.png, .pdf, .svg)")
    sp.set_defaults(func=cmd_sensitivity)

    cli_mechanics.add_parsers(sub, _emit_json)
    cli_study.add_parser(sub, _load_crank, check_mesh_size)

    up = sub.add_parser("run", help="the main job: every analysis of a crank into one report folder")
    up.add_argument("file", nargs="?", help="crank description or chain file (default geometry/renault21.toml; "
                                            "a chain gets the report without the FE sections)")
    up.add_argument("--out", metavar="DIR", help="report folder (default out/<name>; with --all, the parent folder)")
    up.add_argument("--all", action="store_true", help="both reference cranks into results/<name>/")
    up.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size in mm (default {DEFAULT_MESH_SIZE / MM:g})")
    up.add_argument("--no-fe", action="store_true", help="skip the mesh and FE modal steps (a quick report)")
    up.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings",
                    help="the modes the Campbell diagram uses: the condensed crank in its bearings (default) or the "
                         "free-free FE; the report shows both")
    up.add_argument("--inertia-ratio", type=real(0.0, 2.0), default=DEFAULT_INERTIA_RATIO, metavar="MU",
                    help="the verdict's damper designs: ring inertia ratio, 0 < MU < 2 (default %(default)s)")
    up.add_argument("--no-html", action="store_true", help="no report.html (the interactive web page) beside report.md")
    up.add_argument("--force", action="store_true",
                    help="replace --out even if it is not an earlier fetorsion report (its contents are lost)")
    up.set_defaults(func=cmd_run)


    mp = sub.add_parser("mesh", help="Gmsh solid of a crank description: mass properties, curved tet mesh, picture")
    mp.add_argument("file", help="crank description (.toml)")
    mp.add_argument("-o", "--output", metavar="OUT", action="append",
                    help="mesh file: .msh, .vtu or .inp (CalculiX, C3D10); repeat for the same mesh in several formats")
    mp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"global element size in mm (default {DEFAULT_MESH_SIZE / MM:g}); fillets and drillings get finer")
    _add_purpose_options(mp)
    mp.add_argument("--modes", type=integer(1, 1000), default=DEFAULT_MODES,
                    help=".inp: eigenfrequencies asked of *FREQUENCY, rigid-body ones included (default %(default)s)")
    mp.add_argument("--png", metavar="OUT.png", help="write an off-screen picture of the solid")
    mp.set_defaults(func=cmd_mesh)

    fp = sub.add_parser("modal", help="free-free 3D FE modal analysis with attachments, modes labelled")
    fp.add_argument("file", help="crank description (.toml)")
    fp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"global element size in mm (default {DEFAULT_MESH_SIZE / MM:g}), as for 'fetorsion mesh'")
    fp.add_argument("--mesh", metavar="MESHFILE", help="use a .msh written by 'fetorsion mesh' instead of meshing")
    _add_purpose_options(fp)
    fp.add_argument("--modes", type=integer(1, 200), default=DEFAULT_MODES, help="elastic modes to compute (default %(default)s)")
    fp.add_argument("--support", choices=SUPPORT_CHOICES, default="free",
                    help="free-free (default: what a modal test measures) or in the main bearings of [bearings] "
                         "(the condensed crank's modes, torsion and bending shares; plot: shares against frequency)")
    fp.add_argument("--plot", metavar="PATH", help="save the modes' torsion/bending shares (.png, .pdf, .svg)")
    fp.add_argument("--refine", action="store_true",
                    help="three meshes (sizes x1, x0.8, x0.64) and the extrapolated first torsional frequency")
    fp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    fp.add_argument("--html", metavar="PATH", help="write the mode shapes as an interactive 3D web page (.html)")
    fp.set_defaults(func=cmd_modal)

    kp = sub.add_parser("condense", help="the 3D FE crank condensed (Craig-Bampton) to journal, pin and end masters")
    kp.add_argument("file", help="crank description (.toml)")
    kp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"global element size in mm (default {DEFAULT_MESH_SIZE / MM:g})")
    kp.add_argument("--npz", metavar="PATH", help="save the reduced model (.npz; layout in docs/condensed-crank.md)")
    kp.add_argument("--with-shapes", action="store_true",
                    help="with --npz: also the recovery basis at the mesh vertices (for pictures; tens of MB)")
    kp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    kp.add_argument("--plot", metavar="PATH", help="save the torsion share of each mode, free and in bearings")
    kp.set_defaults(func=cmd_condense)
    return p


# Output options: (attribute, option name, accepted suffixes); "-" means standard output.
OUTPUT_OPTIONS = (("json", "--json", (".json",)), ("plot", "--plot", PLOT_FORMATS), ("html", "--html", (".html",)),
                  ("output", "-o", None), ("png", "--png", (".png",)), ("npz", "--npz", (".npz",)))


def check_options(args) -> None:
    """Every check on the command line that needs no file read: before any work."""
    from ..solid.mesh import MESH_FORMATS

    inputs = [getattr(args, "file", None), getattr(args, "mesh", None)]
    for attr, option, suffixes in OUTPUT_OPTIONS:
        targets = getattr(args, attr, None)
        for target in targets if isinstance(targets, list) else [targets]:
            if target is None or (attr == "json" and target == "-"):
                continue
            check_output_file(target, option, suffixes or MESH_FORMATS, inputs)
    speeds = getattr(args, "speed_range", None)
    if speeds is not None and not speeds[0] < speeds[1]:
        raise FetorsionError(f"--speed-range {speeds[0]:g} {speeds[1]:g}: LOW must be below HIGH (rpm)")
    if getattr(args, "compare", None) is not None:
        args.compare_curve = read_compare_csv(args.compare, args.compare_name, args.compare_unit)
    elif getattr(args, "compare_name", None) or getattr(args, "compare_unit", None) or getattr(
            args, "compare_section", None):
        raise FetorsionError("--compare-name, --compare-unit and --compare-section need --compare CSV")
    mesh = getattr(args, "mesh", None)
    if mesh is not None and not Path(mesh).is_file():
        raise FetorsionError(f"--mesh {mesh}: no such file")
    if args.command in ("run", "study") and not getattr(args, "scheduler", None):
        # Both run their studies on the cluster this names, if it is set.
        from ..studies.runner import SCHEDULER_ENV, check_scheduler, scheduler_address

        address, _ = scheduler_address(None)
        if address:
            check_scheduler(address, SCHEDULER_ENV)


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        check_options(args)
        return args.func(args)
    except ParameterError as exc:  # an argument of the API: named by the option that set it
        print(f"fetorsion: error: {exc.named(option_of(exc.parameter))}", file=sys.stderr)
        return 2
    except FetorsionError as exc:
        print(f"fetorsion: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("fetorsion: interrupted; nothing was written", file=sys.stderr)
        return 130
    except OSError as exc:  # the file system refused something after the checks (disk full, ...)
        where = f" {exc.filename}" if exc.filename else ""
        print(f"fetorsion: error:{where}: {exc.strerror or exc}", file=sys.stderr)
        return 1


