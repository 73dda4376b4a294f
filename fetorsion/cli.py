"""Command line: ``fetorsion <command> ...``. User mistakes print one clear message, exit 2."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from . import cli_mechanics
from .crank import Chain, load
from .errors import FetorsionError
from .io import save_figure_atomic, write_text_atomic
from .lumped import PARTITIONS, lumped
from .parts import build_parts
from .stiffness import DEFAULT_WEB_METHOD, WEB_METHODS


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


def cmd_lumped(args) -> int:
    model = load(args.file)
    results = [lumped(model)] if isinstance(model, Chain) else [lumped(model, d, args.stiffness) for d in args.dof]
    out = sys.stderr if args.json == "-" else sys.stdout
    print(format_lumped_table(results), file=out)
    payload = {"file": args.file, "models": [r.to_dict() for r in results]}
    if not isinstance(model, Chain):
        payload.update(stiffness_method=args.stiffness, parts=parts_table(build_parts(model, args.stiffness)),
                       web_inertia="analytic web outline (fetorsion.web), no fillets", description=model.raw)
    _emit_json(payload, args.json)
    return 0


def parts_table(chain) -> list[dict]:
    """The crank parts with their equivalent lengths, stiffnesses and inertias (SI)."""
    return [{"part": p.label, "x0_m": p.x0, "x1_m": p.x1, "equivalent_length_m": p.equivalent_length,
             "stiffness_nm_per_rad": 1.0 / p.compliance, "inertia_kgm2": p.inertia,
             "attached_inertia_kgm2": p.attached_inertia} for p in chain.parts]


def cmd_mesh(args) -> int:
    # Imported here: gmsh and VTK take a second to load and 'lumped' needs neither.
    from .geometry import build_solid, gmsh_session, solid_mass_properties
    from .mesh import MESH_FORMATS, mesh_solid, write_mesh

    outputs = args.output or []
    if not outputs and args.png is None:
        raise FetorsionError("mesh: give -o OUT (.msh, .vtu, .inp) and/or --png OUT.png")
    for out in outputs:
        if Path(out).suffix.lower() not in MESH_FORMATS:
            raise FetorsionError(f"-o {out}: unknown mesh format; use one of {', '.join(MESH_FORMATS)}")
    if args.mesh_size <= 0:
        raise FetorsionError(f"--mesh-size {args.mesh_size:g}: must be > 0 (mm)")
    crank = load(args.file)
    if isinstance(crank, Chain):
        raise FetorsionError(f"{args.file}: a chain file has no geometry to mesh; give a crank description")
    with gmsh_session():
        solid = build_solid(crank)
        total, parts = solid_mass_properties(solid, crank.material.density)
        print(format_mass_table(crank.name, total, parts))
        if outputs:
            mesh = mesh_solid(solid, crank, args.mesh_size * 1e-3, _fillet_m(args), args.purpose)
            q = mesh.quality
            for out in outputs:  # one mesh, several formats: the same elements in each file
                write_mesh(mesh, out, modes=args.modes)
            print(f"mesh ({args.purpose}): {q.n_tets} curved 10-node tets, {q.n_nodes} nodes, size {q.size * 1e3:g} mm "
                  f"({q.fillet_size * 1e3:g} mm at fillets and drillings, {q.straightened} folded elements "
                  f"straightened), minimum SICN {q.min_sicn:.3f}, {q.seconds:.1f} s -> {', '.join(outputs)}")
    if args.png is not None:
        from .render import render_solid

        print(f"picture -> {render_solid(crank, args.png)}")
    return 0


def _fillet_m(args) -> float | None:
    """``--fillet-size`` in m (None: the default for ``--purpose``)."""
    if args.fillet_size is None:
        return None
    if args.fillet_size <= 0:
        raise FetorsionError(f"--fillet-size {args.fillet_size:g}: must be > 0 (mm)")
    return args.fillet_size * 1e-3


def cmd_modal(args) -> int:
    from .crankfe import run_modal, run_refinement
    from .mesh import read_mesh

    crank = _load_crank(args.file, "geometry")
    if args.mesh_size <= 0:
        raise FetorsionError(f"--mesh-size {args.mesh_size:g}: must be > 0 (mm)")
    if args.modes < 1:
        raise FetorsionError(f"--modes {args.modes}: must be >= 1")
    refinement = None
    if args.refine:
        if args.mesh:
            raise FetorsionError("--refine meshes the crank three times; it cannot use --mesh")
        runs, refinement = run_refinement(crank, args.mesh_size * 1e-3, args.modes, _fillet_m(args), args.purpose)
        fe = runs[-1]
    else:
        mesh = read_mesh(args.mesh, crank) if args.mesh else None
        fe = run_modal(crank, args.mesh_size * 1e-3, args.modes, _fillet_m(args), mesh=mesh, purpose=args.purpose)
    res = fe.result
    out = sys.stderr if args.json == "-" else sys.stdout
    print(f"{crank.name}: free-free FE modes ({res.dofs} DOF, {res.elements} curved P2 tets, "
          f"{res.backend}/{res.method}, {res.timings_s['total']:.1f} s)", file=out)
    print(f"{'mode':>4} {'f [Hz]':>9} {'kind':>10} {'torsion':>8} {'bending':>8} {'axial':>8}", file=out)
    for j, (f, k, fr) in enumerate(zip(res.frequencies_hz, res.kinds, res.fractions)):
        print(f"{j + 1:>4} {f:9.1f} {k:>10} {fr[0]:8.3f} {fr[1]:8.3f} {fr[2]:8.3f}", file=out)
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
    return 0


def format_mass_table(name: str, total, parts: dict) -> str:
    """Plain-text table of mass (kg) and polar inertia about the crank axis (kg·m²) per part."""
    lines = [f"{name}: mass properties of the solid", f"{'part':>10} {'mass [kg]':>10} {'J [kg m2]':>12}"]
    lines += [f"{n:>10} {b.mass:10.4f} {b.polar_inertia:12.4e}" for n, b in parts.items()]
    lines.append(f"{'total':>10} {total.mass:10.4f} {total.polar_inertia:12.4e}")
    return "\n".join(lines)


def format_lumped_table(results, modes: int = 4) -> str:
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
    crank = load(path)
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


def cmd_campbell(args) -> int:
    from .campbell import lumped_modes, run_campbell

    crank = _load_crank(args.file, "[excitation]")
    if crank.excitation is None:
        raise FetorsionError(f"{args.file}: the description has no [excitation] table")
    if args.source == "fe":
        from .crankfe import run_modal

        modes = run_modal(crank, args.mesh_size * 1e-3, modes=20).torsional_modes(args.modes)
    else:
        modes = lumped_modes(crank, _partition_of(args.source), args.stiffness)
    res = run_campbell(crank, modes, orders=args.orders,
                       speed_range=args.speed_range, n_modes=args.modes, damping_ratio=args.damping)
    head = (f"{res.name}: crossings inside {res.speed_range_rpm[0]:.0f}-{res.speed_range_rpm[1]:.0f} rpm, "
            f"most severe first ({res.source})")
    return _report(res, head + "\n" + res.table(), args)


def cmd_response(args) -> int:
    from .response import run_response

    crank = _load_crank(args.file, "[excitation]")
    if args.source == "fe":
        raise FetorsionError("response: the forced response uses a lumped model; choose --source lumpedN")
    rpm = None if args.speed_range is None else np.linspace(*args.speed_range, args.steps)
    res = run_response(crank, _partition_of(args.source), rpm=rpm, orders=args.orders, damping_ratio=args.damping,
                       web_method=args.stiffness)
    return _report(res, res.summary(), args)


def cmd_sensitivity(args) -> int:
    from .sensitivity import run_sensitivity

    res = run_sensitivity(_load_crank(args.file, "[uncertainty]"), args.dof, args.stiffness)
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


def cmd_run(args) -> int:
    from pathlib import Path

    from .pipeline import run

    if args.all:
        folder = _geometry_folder()
        jobs = [(folder / f"{name}.toml", Path(args.out or "results") / name) for name in REFERENCE_CRANKS]
    else:
        file = Path(args.file) if args.file else _geometry_folder() / f"{REFERENCE_CRANKS[0]}.toml"
        jobs = [(file, Path(args.out) if args.out else Path("out") / file.stem)]
    for file, out in jobs:
        folder = run(file, out)
        print(f"report: {folder / 'report.md'}")
    return 0


def _orders(text: str) -> list[float]:
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--orders {text!r}: give comma-separated numbers, e.g. 0.5,1,1.5") from None
    if any(v <= 0 for v in values):
        raise argparse.ArgumentTypeError(f"--orders {text!r}: orders must be > 0")
    return values


def _add_excitation_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", help="crank description with an [excitation] table (.toml)")
    p.add_argument("--source", default="lumped17", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe"],
                   help="which model gives the modes (default %(default)s; fe: campbell only)")
    p.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    p.add_argument("--speed-range", nargs=2, type=float, metavar=("LOW", "HIGH"), help="rpm")
    p.add_argument("--orders", type=_orders, help="comma-separated orders (default 0.5 ... 12 for a 4-stroke)")
    p.add_argument("--damping", type=float, help="modal damping ratio (default from the file, else 0.02)")
    p.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    p.add_argument("--plot", metavar="PATH", help="save the plot (.png, .svg)")


def _add_purpose_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--purpose", choices=("modal", "stress"), default="modal",
                   help="what the mesh is for (default %(default)s): modal, the sizes the frequency convergence "
                        "study chose (docs/modal-mesh.md); stress, fillet elements of the fillet radius")
    p.add_argument("--fillet-size", type=float, metavar="MM",
                   help="element size at fillets and drillings in mm (default from --purpose)")


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="fetorsion", description="Torsional vibration analysis of engine crankshafts.")
    sub = p.add_subparsers(dest="command", required=True)

    lp = sub.add_parser("lumped", help="BICERA-style equivalent-length lumped models (5/6/17/19/21 DOF)")
    lp.add_argument("file", help="crank description or chain file (.toml)")
    lp.add_argument("--dof", type=_dof_list, default=[17], help="partition(s): 5, 6, 17, 19, 21, a list, or 'all'")
    lp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD,
                    help="web stiffness method (default %(default)s)")
    lp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    lp.set_defaults(func=cmd_lumped)

    cp = sub.add_parser("campbell", help="Campbell diagram: crossings of modes and orders, with severity")
    _add_excitation_options(cp)
    cp.add_argument("--modes", type=int, default=3, help="number of lowest modes (default %(default)s)")
    cp.add_argument("--mesh-size", type=float, default=10.0, metavar="MM", help="FE mesh size for --source fe")
    cp.set_defaults(func=cmd_campbell)

    rp = sub.add_parser("response", help="forced torsional response of a lumped model versus speed")
    _add_excitation_options(rp)
    rp.add_argument("--steps", type=int, default=300, help="speeds in the range (default %(default)s)")
    rp.set_defaults(func=cmd_response)

    sp = sub.add_parser("sensitivity", help="f1 against each reconstructed input, and the f1 band")
    sp.add_argument("file", help="crank description with an [uncertainty] table (.toml)")
    sp.add_argument("--dof", type=int, choices=PARTITIONS, default=17)
    sp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    sp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    sp.add_argument("--plot", metavar="PATH", help="save the tornado chart (.png, .svg)")
    sp.set_defaults(func=cmd_sensitivity)

    cli_mechanics.add_parsers(sub, _emit_json)

    up = sub.add_parser("run", help="the main job: every analysis of a crank into one report folder")
    up.add_argument("file", nargs="?", help="crank description (default geometry/renault21.toml)")
    up.add_argument("--out", metavar="DIR", help="report folder (default out/<name>; with --all, the parent folder)")
    up.add_argument("--all", action="store_true", help="both reference cranks into results/<name>/")
    up.set_defaults(func=cmd_run)


    mp = sub.add_parser("mesh", help="Gmsh solid of a crank description: mass properties, curved tet mesh, picture")
    mp.add_argument("file", help="crank description (.toml)")
    mp.add_argument("-o", "--output", metavar="OUT", action="append",
                    help="mesh file: .msh, .vtu or .inp (CalculiX, C3D10); repeat for the same mesh in several formats")
    mp.add_argument("--mesh-size", type=float, default=10.0, metavar="MM",
                    help="global element size in mm (default %(default)s); fillets and drillings get finer")
    _add_purpose_options(mp)
    mp.add_argument("--modes", type=int, default=20,
                    help=".inp: eigenfrequencies asked of *FREQUENCY, rigid-body ones included (default %(default)s)")
    mp.add_argument("--png", metavar="OUT.png", help="write an off-screen picture of the solid")
    mp.set_defaults(func=cmd_mesh)

    fp = sub.add_parser("modal", help="free-free 3D FE modal analysis with attachments, modes labelled")
    fp.add_argument("file", help="crank description (.toml)")
    fp.add_argument("--mesh-size", type=float, default=10.0, metavar="MM",
                    help="global element size in mm (default %(default)s), as for 'fetorsion mesh'")
    fp.add_argument("--mesh", metavar="MESHFILE", help="use a .msh written by 'fetorsion mesh' instead of meshing")
    _add_purpose_options(fp)
    fp.add_argument("--modes", type=int, default=20, help="elastic modes to compute (default %(default)s)")
    fp.add_argument("--refine", action="store_true",
                    help="three meshes (sizes x1, x0.8, x0.64) and the extrapolated first torsional frequency")
    fp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    fp.set_defaults(func=cmd_modal)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except FetorsionError as exc:
        print(f"fetorsion: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
