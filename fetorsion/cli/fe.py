"""``fetorsion mesh``, ``modal`` and ``condense``: the Gmsh solid and its mesh, the 3D FE modes, the
condensed crank."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .options import MM, integer, millimetres
from ..errors import FetorsionError
from ..solid.isolate import call_isolated
from ..io import Stages, write_text_atomic
from ..description.defaults import DEFAULT_MESH_SIZE, DEFAULT_MODES, DEFAULT_WEB_METHOD
from .common import (SUPPORT_CHOICES, add_json_option, add_mesh_size_option, check_mesh_size, emit_json, load_crank,
                     report, save_plot)


def cmd_mesh(args) -> int:
    outputs = args.output or []
    if not outputs and args.png is None and args.step_file is None:
        raise FetorsionError("mesh: give -o OUT (.msh, .vtu, .inp), --png OUT.png and/or --step OUT.step")
    crank = load_crank(args.file, "a geometry to mesh")
    if args.step_file is not None:
        from ..io import atomic_output
        from ..solid.geometry import write_step

        with atomic_output(args.step_file) as tmp:
            call_isolated(write_step, crank, tmp, what=f"{crank.name}: STEP")
        print(f"STEP -> {args.step_file}")
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


def cmd_modal(args) -> int:
    from ..fe.crankfe import REFINE_RATIO, run_modal, run_refinement
    from ..modes import TORSION_SHARE_NOTED
    from ..solid.mesh import read_mesh

    if args.refine and args.mesh:
        raise FetorsionError("--refine meshes the crank three times; it cannot use --mesh")
    crank = load_crank(args.file, "geometry")
    if args.support == "bearings" and (args.refine or args.html):
        raise FetorsionError("--support bearings: the modes in bearings come from the condensed crank; "
                             "--refine and --html work with --support free")
    if not args.mesh:
        check_mesh_size(crank, args.mesh_size * (REFINE_RATIO**2 if args.refine else 1.0), "modal", args.purpose,
                        None if args.fillet_size is None else args.fillet_size * (REFINE_RATIO**2 if args.refine else 1.0))
    if args.support == "bearings":
        cc = condensed(crank, args.mesh_size, read_mesh(args.mesh, crank) if args.mesh else None)
        return report(cc, f"{crank.name}\n{cc.table()}", args)
    refinement = None
    if args.refine:
        runs, refinement = run_refinement(crank, args.mesh_size, args.modes, args.fillet_size, args.purpose)
        fe = runs[-1]
    else:
        from ..fe.crankfe import MODAL_STAGES

        mesh = read_mesh(args.mesh, crank) if args.mesh else None
        fe = run_modal(crank, args.mesh_size, args.modes, args.fillet_size, mesh=mesh, purpose=args.purpose,
                       stage=Stages("modal", MODAL_STAGES, say))
    res = fe
    out = sys.stderr if args.json == "-" else sys.stdout
    print(f"{crank.name}: {res.table()}", file=out)
    payload = {"file": args.file, **res.to_dict()}
    torsional = res.of_kind("torsional")
    payload["first_torsional_hz"] = float(torsional[0]) if len(torsional) else None
    print(f"first torsional: {payload['first_torsional_hz']} Hz", file=out)
    carrying = res.first_carrying_torsion() if (res.fractions[:, 0] >= TORSION_SHARE_NOTED).any() else None
    payload["first_carrying_torsion_hz"] = carrying
    if carrying is not None and payload["first_torsional_hz"] is not None and carrying < payload["first_torsional_hz"]:
        print(f"first mode with at least {100 * TORSION_SHARE_NOTED:.0f} % torsion: {carrying} Hz (coupled with "
              "bending; the engine's torque drives it first)", file=out)
    if refinement:
        payload["refinement"] = refinement
        print(f"refinement: f1 = {refinement['first_torsional_hz']} Hz at {refinement['dofs']} DOF -> "
              f"extrapolated {refinement['extrapolated']:.1f} Hz, error estimate {refinement['error_estimate']:.1f} Hz",
              file=out)
    emit_json(payload, args.json)
    if args.plot:
        save_plot(res, args.plot)
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
    from ..response.coupled import with_film_bearings

    if args.with_shapes and not args.npz:
        raise FetorsionError("--with-shapes is saved in the --npz file; give --npz PATH")
    crank = load_crank(args.file, "geometry")
    check_mesh_size(crank, args.mesh_size, "modal")
    if args.with_shapes:  # the mesh's shape basis is not kept in the store: built here, then kept
        from ..design.stress import fillet_cuts
        from ..fe.store import remember_condensed

        cuts = fillet_cuts(crank, engine_fillets(crank))
        cc = run_condensed(crank, args.mesh_size, keep_basis=True, cuts=cuts)
        remember_condensed(cc, args.mesh_size, cuts)
        cc = with_film_bearings(cc)
    else:
        cc = condensed(crank, args.mesh_size)
    report(cc, f"{crank.name}\n{cc.table()}", args)
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


def engine_fillets(crank):
    """The crank's fillets, as the run finds them (their cuts are part of the condensed crank)."""
    from ..app.engine import engine_fillets as fillets

    return fillets(crank)


def condensed(crank, mesh_size: float, mesh=None):
    """The run's condensed crank — section cuts at every fillet — from the store
    (:mod:`fetorsion.fe.store`), else built here (said on stderr) and kept; its oil-film
    bearings at the journals' mean loads when the description states none. A mesh read from a
    file is condensed as it is and not kept."""
    from ..app.engine import engine_condensed
    from ..fe.condensed import run_condensed
    from ..response.coupled import with_film_bearings

    from ..fe.condensed import CONDENSE_STAGES

    stage = Stages("condense", CONDENSE_STAGES, say)
    if mesh is not None:
        return with_film_bearings(run_condensed(crank, mesh_size, mesh=mesh, stage=stage))
    return engine_condensed(crank, mesh_size, say, stage)


def say(line: str) -> None:
    """A progress line on stderr (stdout keeps the results)."""
    print(f"[fetorsion] {line}", file=sys.stderr, flush=True)


def _add_purpose_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--purpose", choices=("modal", "stress"), default="modal",
                   help="what the mesh is for (default %(default)s): modal, the sizes the frequency convergence "
                        "study chose (docs/modal-mesh.md); stress, fillet elements of the fillet radius")
    p.add_argument("--fillet-size", type=millimetres(), metavar="MM",
                   help="element size at fillets and drillings in mm (default from --purpose)")


def add_parsers(sub) -> None:
    """The ``mesh``, ``modal``, ``condense`` commands."""
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
    mp.add_argument("--step", dest="step_file", metavar="OUT.step",
                    help="write the solid built from the dimensions as a STEP file (mm; crank axis x, front end at "
                         "x = 0: what a description's [solid] reads back)")
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
    add_json_option(fp)
    fp.add_argument("--html", metavar="PATH", help="write the mode shapes as an interactive 3D web page (.html)")
    fp.set_defaults(func=cmd_modal)

    kp = sub.add_parser("condense", help="the 3D FE crank condensed (Craig-Bampton) to journal, pin and end masters, "
                        "kept in the store for the other commands")
    kp.add_argument("file", help="crank description (.toml)")
    add_mesh_size_option(kp)
    kp.add_argument("--npz", metavar="PATH", help="save the reduced model (.npz; layout in docs/condensed-crank.md)")
    kp.add_argument("--with-shapes", action="store_true",
                    help="with --npz: also the recovery basis at the mesh vertices (for pictures; tens of MB)")
    add_json_option(kp)
    kp.add_argument("--plot", metavar="PATH", help="save the torsion share of each mode, free and in bearings")
    kp.set_defaults(func=cmd_condense)
