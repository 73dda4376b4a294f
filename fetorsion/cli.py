"""Command line: ``fetorsion <command> ...``. User mistakes print one clear message, exit 2."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .crank import Chain, load
from .errors import FetorsionError
from .io import write_text_atomic
from .lumped import PARTITIONS, lumped
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
    _emit_json({"file": args.file, "stiffness_method": None if isinstance(model, Chain) else args.stiffness,
                "models": [r.to_dict() for r in results]}, args.json)
    return 0


def cmd_mesh(args) -> int:
    # Imported here: gmsh and VTK take a second to load and 'lumped' needs neither.
    from .geometry import build_solid, gmsh_session, solid_mass_properties
    from .mesh import MESH_FORMATS, mesh_solid, write_mesh

    if args.output is None and args.png is None:
        raise FetorsionError("mesh: give -o OUT (.msh, .vtu, .inp) and/or --png OUT.png")
    if args.output is not None and Path(args.output).suffix.lower() not in MESH_FORMATS:
        raise FetorsionError(f"-o {args.output}: unknown mesh format; use one of {', '.join(MESH_FORMATS)}")
    if args.mesh_size <= 0:
        raise FetorsionError(f"--mesh-size {args.mesh_size:g}: must be > 0 (mm)")
    crank = load(args.file)
    if isinstance(crank, Chain):
        raise FetorsionError(f"{args.file}: a chain file has no geometry to mesh; give a crank description")
    with gmsh_session():
        solid = build_solid(crank)
        total, parts = solid_mass_properties(solid, crank.material.density)
        print(format_mass_table(crank.name, total, parts))
        if args.output is not None:
            mesh = mesh_solid(solid, crank, args.mesh_size * 1e-3)
            q = mesh.quality
            write_mesh(mesh, args.output)
            print(f"mesh: {q.n_tets} curved 10-node tets, {q.n_nodes} nodes, size {q.size * 1e3:g} mm "
                  f"({q.fillet_size * 1e3:g} mm at fillets and drillings), minimum SICN {q.min_sicn:.3f}, "
                  f"{q.seconds:.1f} s -> {args.output}")
    if args.png is not None:
        from .picture import render_png

        print(f"picture -> {render_png(crank, args.png)}")
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

    mp = sub.add_parser("mesh", help="Gmsh solid of a crank description: mass properties, curved tet mesh, picture")
    mp.add_argument("file", help="crank description (.toml)")
    mp.add_argument("-o", "--output", metavar="OUT", help="mesh file: .msh, .vtu or .inp (CalculiX, C3D10)")
    mp.add_argument("--mesh-size", type=float, default=6.0, metavar="MM",
                    help="global element size in mm (default %(default)s); fillets and drillings get finer")
    mp.add_argument("--png", metavar="OUT.png", help="write an off-screen picture of the solid")
    mp.set_defaults(func=cmd_mesh)
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
