"""What every command family shares: loading a description (with its plausibility warnings),
writing JSON and plots, the mesh-size check made before any FE job."""

from __future__ import annotations

import json
import sys

from .options import MM
from ..description.files import load
from ..description.chain_model import Chain, Network
from ..description.plausibility import plausibility_warnings
from ..design.methods import described_method
from ..errors import FetorsionError
from ..io import save_figure_atomic, write_text_atomic


PLOT_FORMATS = (".png", ".pdf", ".svg")


SUPPORT_CHOICES = ("free", "bearings")


def emit_json(payload: dict, target: str | None) -> None:
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
    if not isinstance(model, (Chain, Network)):
        described_method(model)  # [limits] fatigue_method against the registry, before any work
        for line in plausibility_warnings(model):
            print(f"fetorsion: warning: {path}: {line}", file=sys.stderr)
    return model


def load_crank(path: str, needs: str):
    crank = load_description(path)
    if isinstance(crank, (Chain, Network)):
        raise FetorsionError(f"{path}: this command needs a crank description with {needs}, not a chain file")
    return crank


def save_plot(obj, path: str) -> None:
    """Draw ``obj.plot()`` and save it atomically to ``path`` (format from the extension)."""
    import matplotlib

    matplotlib.use("Agg")
    out = obj.plot()
    save_figure_atomic(out.figure if hasattr(out, "figure") else out, path, close=True, dpi=130)


def partition_of(source: str) -> int:
    return int(source.removeprefix("lumped"))


def report(res, text: str, args) -> int:
    """Print ``text`` (to stderr when JSON takes stdout), then write the JSON and the plot."""
    print(text, file=sys.stderr if args.json == "-" else sys.stdout)
    emit_json(res.to_dict(), args.json)
    if args.plot:
        save_plot(res, args.plot)
    return 0


def load_excited(path: str, source: str):
    """A crank description or chain file with an [excitation] table (a chain: lumped modes only)."""
    model = load_description(path)
    if isinstance(model, (Chain, Network)) and source in ("fe", "condensed"):
        raise FetorsionError(f"--source {source}: {path} is a chain file, it has no geometry to mesh; leave --source out")
    if model.excitation is None:
        raise FetorsionError(f"{path}: the description has no [excitation] table"
                             + (" (a chain file needs [engine], [excitation] and chain.cylinder_stations)"
                                if isinstance(model, (Chain, Network)) else ""))
    return model


def refuse_network(model, path: str, command: str) -> None:
    """A network file (geared or branched) where ``command`` does not handle one yet: one message."""
    if isinstance(model, Network):
        raise FetorsionError(f"{path}: '{command}' does not take a network (stations, shafts and gears) yet; "
                             "'lumped', 'campbell', 'response', 'transient' and 'run' do")


def stiffness_for(args) -> str:
    """The web method in the support condition asked for (``fe`` in bearings is ``fe-held``)."""
    from ..webs.methods import IN_BEARINGS

    return IN_BEARINGS.get(args.stiffness, args.stiffness) if args.support == "bearings" else args.stiffness


def check_mesh_size(crank, mesh_size: float, job: str, purpose: str = "modal", fillet_size: float | None = None,
                    option: str = "--mesh-size") -> None:
    """Refuse a mesh size whose mesh (``job`` 'mesh') or FE modal job ('modal') would not fit in
    memory, naming the option and the estimate; print the estimate when the job is long."""
    from ..io import available_memory
    from ..solid.mesh import estimate_mesh

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


def add_json_option(p) -> None:
    """``--json PATH|-``: the command's results as JSON, to a file or standard output."""
    p.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")


def add_band_option(p, what: str = "") -> None:
    """``--band LOW HIGH``: the frequency band (Hz) to fit measured FRFs' modes in (``what``:
    the words after the default, where a command says more)."""
    from .options import real

    p.add_argument("--band", type=real(0.0, low_open=False), nargs=2, metavar=("LOW", "HIGH"),
                   help=f"{'with --measured: ' if not what else ''}the frequency band (Hz) to fit the measured "
                        f"FRFs' modes in (default: the FRFs' own{what})")


def add_mesh_size_option(p, what: str = "global element size") -> None:
    """``--mesh-size MM``: the FE mesh's element size, in mm on the command line (m inside)."""
    from ..description.defaults import DEFAULT_MESH_SIZE
    from .options import MM, millimetres

    p.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                   help=f"{what} in mm (default {DEFAULT_MESH_SIZE / MM:g})")
